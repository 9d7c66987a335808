#include "simulate/image_track_truth.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <unordered_map>

#include "geometry/mesh_index.h"
#include "geometry/mesh_io.h"
#include "simulate/true_scene.h"

namespace hull {
namespace {

struct Ray {
  Eigen::Vector3d origin, direction;  // in M, unit direction
};

Eigen::Vector3d PixelRay(const PinholeIntrinsics& k, double u, double v) {
  return Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0).normalized();
}

// The point nearest to every ray in the least-squares sense (false when the
// rays are near parallel).
bool NearestToRays(const std::vector<Ray>& rays, Eigen::Vector3d& p) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const Ray& r : rays) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - r.direction * r.direction.transpose();
    A += P;
    b += P * r.origin;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  if (es.eigenvalues()(0) < 1e-6 * es.eigenvalues()(2)) return false;
  p = A.ldlt().solve(b);
  return p.allFinite();
}

}  // namespace

double ImageTrackTruth::WrongObservationFraction() const {
  const std::size_t hit = observations - observations_missed;
  return hit ? static_cast<double>(wrong_observations) / static_cast<double>(hit) : 0.0;
}

double ImageTrackTruth::TriangulatedWithinFraction() const {
  return triangulated ? static_cast<double>(triangulated_within) / static_cast<double>(triangulated) : 0.0;
}

std::string ImageTrackTruth::ToString() const {
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "feature tracks from images, scored against truth/scene.ply (tolerance %.3f m):\n"
                "  %zu tracks, %zu top observations (%zu rays hit nothing)\n"
                "  wrong matches: %zu observations (%.2f %%) in %zu tracks, farther than the tolerance from their "
                "track's true point\n"
                "  triangulated with the true cameras: %.2f %% of %zu tracks within the tolerance of the true "
                "surface\n",
                tolerance, tracks, observations, observations_missed, wrong_observations,
                100.0 * WrongObservationFraction(), tracks_with_wrong, 100.0 * TriangulatedWithinFraction(),
                triangulated);
  return buf;
}

Pose TrueCameraPoseFromTruth(const SurveyBundle& b, std::size_t k, bool bottom_camera) {
  const SurveyTruth& t = *b.truth;
  const TruePose& p = t.poses.at(k);
  const Pose x_gc = Pose::FromVector(p.x_gv) * b.manifest.VehicleToServo(p.servo) * Pose::FromVector(t.x_s_cT);
  const Pose x_Mc = Pose::FromVector(t.x_gM).Inverse() * x_gc;
  return bottom_camera ? x_Mc * Pose::FromVector(b.manifest.camera.top_to_bottom) : x_Mc;
}

ImageTrackTruth DeriveImageTrackTruth(const SurveyBundle& b, const TrueScene& scene, const TriangleMesh& cad,
                                      double tolerance) {
  if (!b.truth) throw std::invalid_argument("DeriveImageTrackTruth: the bundle has no truth");
  const SurveyTruth& truth = *b.truth;
  std::unordered_map<std::int64_t, std::size_t> pose_of;
  for (std::size_t i = 0; i < truth.poses.size(); ++i) pose_of[truth.poses[i].keyframe] = i;
  const CameraRig& rig = b.manifest.camera;
  const bool stereo = rig.stereo();

  // Observations grouped by landmark, in the order of their first appearance.
  std::unordered_map<std::int64_t, std::size_t> track_of;
  std::vector<std::vector<const FeatureObservation*>> tracks;
  std::vector<std::int64_t> ids;
  for (const FeatureObservation& f : b.features) {
    auto [it, fresh] = track_of.try_emplace(f.landmark, tracks.size());
    if (fresh) {
      tracks.emplace_back();
      ids.push_back(f.landmark);
    }
    tracks[it->second].push_back(&f);
  }

  const MeshIndex cad_index(cad);
  const Pose x_gM = Pose::FromVector(truth.x_gM);
  ImageTrackTruth out;
  out.tolerance = tolerance;
  out.tracks = tracks.size();
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    std::vector<RayHit> hits;
    std::vector<Ray> rays;
    for (const FeatureObservation* f : tracks[t]) {
      auto p = pose_of.find(f->keyframe);
      if (p == pose_of.end()) continue;  // a keyframe without a true pose: nothing to score
      ++out.observations;
      const Pose top = TrueCameraPoseFromTruth(b, p->second, false);
      const Ray ray{top.translation(), top.rotation() * PixelRay(rig.top, f->top.x(), f->top.y())};
      rays.push_back(ray);
      const RayHit h = scene.index().Raycast(ray.origin, ray.direction);
      if (h.hit) {
        hits.push_back(h);
      } else {
        ++out.observations_missed;
      }
      if (stereo && f->has_bottom) {
        const Pose bottom = TrueCameraPoseFromTruth(b, p->second, true);
        rays.push_back({bottom.translation(), bottom.rotation() * PixelRay(rig.bottom, f->bottom.x(), f->bottom.y())});
      }
    }
    if (hits.empty()) continue;
    // The medoid of the hits: the one with the smallest summed distance.
    std::size_t best = 0;
    double best_sum = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < hits.size(); ++i) {
      double s = 0;
      for (const RayHit& h : hits) s += (h.point - hits[i].point).norm();
      if (s < best_sum) {
        best_sum = s;
        best = i;
      }
    }
    const RayHit& centre = hits[best];
    std::size_t wrong = 0;
    for (const RayHit& h : hits) wrong += (h.point - centre.point).norm() > tolerance;
    out.wrong_observations += wrong;
    out.tracks_with_wrong += wrong > 0;
    Eigen::Vector3d tri;
    if (rays.size() >= 2 && NearestToRays(rays, tri)) {
      ++out.triangulated;
      out.triangulated_within += scene.index().Closest(tri).distance <= tolerance;
    }
    TrueLandmark l;
    l.landmark = ids[t];
    l.p = x_gM * centre.point;
    if (const TrueObject* o = scene.ObjectOfFace(centre.face)) {
      l.object = o->id;
      l.deviation = cad_index.SignedDistance(centre.point);
    }
    out.landmarks.push_back(l);
  }
  return out;
}

std::optional<ImageTrackTruth> AttachImageTrackTruth(SurveyBundle& b) {
  namespace fs = std::filesystem;
  if (!b.truth) return std::nullopt;
  b.truth->landmarks.clear();
  std::error_code ec;
  if (b.directory.empty() || !fs::exists(fs::path(b.directory) / "truth" / "scene.ply", ec)) return std::nullopt;
  const std::string cad_path = b.ModelHintPath();
  if (cad_path.empty()) return std::nullopt;
  const std::unique_ptr<TrueScene> scene = TrueScene::Load(b);
  ImageTrackTruth t = DeriveImageTrackTruth(b, *scene, LoadMesh(cad_path));
  b.truth->landmarks = t.landmarks;
  return t;
}

}  // namespace hull
