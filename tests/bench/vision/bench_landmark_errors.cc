// Where an adjustment's landmark error comes from, on a simulated survey
// with truth (for front-end tracks the truth is derived from the scene, as
// the pipeline does). Reads a bundle and a results directory written by
// `hullinspect-cli run` (or `adjust`) and prints:
//   - the model pose: initial, adjusted, true, and their differences;
//   - the landmark error in M after the best rigid fit to the truth (and the
//     fit's scale when a similarity is allowed: mono scale drift), binned by
//     the largest triangulation angle of the track (true cameras), by the
//     number of views and by whether the initial point fell back to the
//     prior mesh;
//   - the initial landmarks (triangulated from the navigation prior, as the
//     adjustment starts): error against the truth in g;
//   - the adjusted camera positions against the truth along the survey.
//
//   bench_landmark_errors BUNDLE RESULTS_DIR
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <unordered_map>
#include <vector>

#include "adjust/adjust_result.h"
#include "adjust/triangulation.h"
#include "geometry/mesh_index.h"
#include "pipeline/pipeline.h"
#include "results/adjustment_files.h"
#include "simulate/image_track_truth.h"

namespace {
using namespace hull;

struct Bin {
  double sum2 = 0;
  std::size_t n = 0;
  void Add(double e) {
    sum2 += e * e;
    ++n;
  }
  double Rms() const { return n ? std::sqrt(sum2 / static_cast<double>(n)) : std::nan(""); }
};

void PrintBins(const char* title, const std::map<int, Bin>& bins, const char* unit) {
  std::printf("%s\n", title);
  for (const auto& [k, b] : bins) std::printf("  %6d %s: %8zu landmarks, RMSE %.4f m\n", k, unit, b.n, b.Rms());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: bench_landmark_errors BUNDLE RESULTS_DIR\n");
    return 2;
  }
  const PipelineInputs in = LoadPipelineInputs(argv[1]);
  const SurveyBundle& b = in.bundle;
  if (!b.truth) {
    std::fprintf(stderr, "%s: no truth\n", argv[1]);
    return 1;
  }
  const AdjustmentResult r = ReadAdjustmentResult((std::filesystem::path(argv[2]) / "adjustment").string());
  const SurveyTruth& t = *b.truth;
  const Pose est_gM = Pose::FromVector(r.x_gM), init_gM = Pose::FromVector(r.x_gM_initial);
  const Pose true_gM = Pose::FromVector(t.x_gM);
  auto describe = [](const char* name, const Pose& p) {
    const Vector6d v = p.ToVector();
    std::printf("  %-9s %9.3f %9.3f %7.3f  rpy %8.4f %8.4f %8.4f\n", name, v[0], v[1], v[2], v[3], v[4], v[5]);
  };
  std::printf("model pose x_gM:\n");
  describe("initial", init_gM);
  describe("adjusted", est_gM);
  describe("true", true_gM);
  std::printf("  initial vs true: %.3f m, %.3f deg; adjusted vs true: %.3f m, %.3f deg\n",
              Pose::DistanceBetween(init_gM, true_gM), Pose::AngleBetween(init_gM, true_gM) * 180 / M_PI,
              Pose::DistanceBetween(est_gM, true_gM), Pose::AngleBetween(est_gM, true_gM) * 180 / M_PI);

  // Truth per landmark, true camera per keyframe.
  std::unordered_map<std::int64_t, const TrueLandmark*> truth;
  for (const TrueLandmark& l : t.landmarks) truth[l.landmark] = &l;
  std::unordered_map<std::int64_t, std::size_t> truth_pose;
  for (std::size_t i = 0; i < t.poses.size(); ++i) truth_pose[t.poses[i].keyframe] = i;
  std::unordered_map<std::int64_t, std::vector<const FeatureObservation*>> obs;
  for (const FeatureObservation& f : b.features) obs[f.landmark].push_back(&f);
  const auto kf = b.KeyframeIndex();
  const Pose x_s_cT0 = Pose::FromVector(b.manifest.camera.servo_to_top);
  const MeshIndex index(in.mesh);

  // Estimated and true points in M; best rigid (and similarity) fit.
  const Pose est_Mg = est_gM.Inverse(), true_Mg = true_gM.Inverse();
  std::vector<const LandmarkEstimate*> used;
  Eigen::Matrix3Xd E(3, static_cast<Eigen::Index>(r.landmarks.size())), T(3, E.cols());
  Eigen::Index n = 0;
  for (const LandmarkEstimate& l : r.landmarks) {
    auto it = truth.find(l.id);
    if (it == truth.end()) continue;
    E.col(n) = est_Mg * l.p;
    T.col(n) = true_Mg * it->second->p;
    used.push_back(&l);
    ++n;
  }
  E.conservativeResize(3, n);
  T.conservativeResize(3, n);
  const Eigen::Matrix4d rigid = Eigen::umeyama(E, T, false);
  const Eigen::Matrix4d similar = Eigen::umeyama(E, T, true);
  const double scale = std::cbrt(similar.topLeftCorner<3, 3>().determinant());
  const Eigen::Matrix3Xd F = (rigid.topLeftCorner<3, 3>() * E).colwise() + rigid.topRightCorner<3, 1>();
  const Eigen::Matrix3Xd S = (similar.topLeftCorner<3, 3>() * E).colwise() + similar.topRightCorner<3, 1>();
  const double rot_deg = Eigen::AngleAxisd(rigid.topLeftCorner<3, 3>()).angle() * 180 / M_PI;
  std::printf(
      "landmarks %ld: RMSE in M raw %.4f m; rigid fit %.4f m (rotation %.3f deg, translation %.3f m); "
      "similarity %.4f m (scale %.5f)\n",
      static_cast<long>(n), std::sqrt((E - T).colwise().squaredNorm().mean()),
      std::sqrt((F - T).colwise().squaredNorm().mean()), rot_deg, rigid.topRightCorner<3, 1>().norm(),
      std::sqrt((S - T).colwise().squaredNorm().mean()), scale);
  // Error components in the true hull's frame (x along, z normal).
  Eigen::Vector3d comp = (F - T).array().square().rowwise().mean().sqrt();
  std::printf("  rigid-fit error per M axis (rms): x %.4f y %.4f z %.4f m\n", comp.x(), comp.y(), comp.z());

  std::map<int, Bin> by_angle, by_views, by_init, by_depth_ratio;
  std::map<int, Bin> init_by_angle;
  Bin init_all, init_mesh, init_tri;
  std::vector<std::pair<double, std::int64_t>> worst;
  std::unordered_map<std::int64_t, std::array<double, 6>> detail;
  for (Eigen::Index i = 0; i < n; ++i) {
    const LandmarkEstimate& l = *used[static_cast<std::size_t>(i)];
    const double e = (F.col(i) - T.col(i)).norm();
    worst.push_back({e, l.id});
    const auto& list = obs[l.id];
    // Largest angle between the true rays to the true point.
    const Eigen::Vector3d Xm = T.col(i);
    std::vector<Eigen::Vector3d> dirs;
    double min_depth = 1e9, max_depth = 0;
    std::vector<ViewRay> rays;
    for (const FeatureObservation* f : list) {
      auto p = truth_pose.find(f->keyframe);
      if (p == truth_pose.end()) continue;
      const Pose c = TrueCameraPoseFromTruth(b, p->second, false);
      const Eigen::Vector3d d = Xm - c.translation();
      dirs.push_back(d.normalized());
      min_depth = std::min(min_depth, d.norm());
      max_depth = std::max(max_depth, d.norm());
      // The initial ray from the navigation prior.
      const int k = kf.at(f->keyframe);
      const NavRecord& nv = b.nav[static_cast<std::size_t>(k)];
      const Pose g_c = Pose::FromVector(nv.x_gv) * b.manifest.VehicleToServo(nv.servo) * x_s_cT0;
      ViewRay ray;
      ray.origin = g_c.translation();
      ray.dir = g_c.Rotate(b.manifest.camera.top.Unproject(f->top)).normalized();
      ray.g_c = g_c;
      ray.pixel = f->top;
      ray.fx = b.manifest.camera.top.fx;
      ray.fy = b.manifest.camera.top.fy;
      ray.cx = b.manifest.camera.top.cx;
      ray.cy = b.manifest.camera.top.cy;
      rays.push_back(ray);
    }
    double angle = 0;
    for (std::size_t a = 0; a < dirs.size(); ++a) {
      for (std::size_t c = a + 1; c < dirs.size(); ++c) {
        angle = std::max(angle, std::acos(std::clamp(dirs[a].dot(dirs[c]), -1.0, 1.0)));
      }
    }
    const double deg = angle * 180 / M_PI;
    const int abin = deg < 1 ? 0 : deg < 2 ? 1 : deg < 4 ? 2 : deg < 8 ? 4 : deg < 16 ? 8 : deg < 32 ? 16 : 32;
    by_angle[abin].Add(e);
    by_views[std::min(l.observations, 10)].Add(e);
    const auto tri = TriangulateLandmark(rays, TriangulationOptions{}, &index, init_gM);
    detail[l.id] = std::array<double, 6>{
        deg,
        tri ? (tri->point - truth[l.id]->p).norm() : -1.0,
        tri ? index.OrthogonalSignedDistance(init_gM, tri->point, SurfaceLookup::kClosestFace).signed_distance : 0.0,
        l.deviation,
        truth[l.id]->deviation,
        static_cast<double>(list.size())};
    if (tri) {
      const double ie = (tri->point - truth[l.id]->p).norm();
      init_all.Add(ie);
      (tri->from_mesh ? init_mesh : init_tri).Add(ie);
      init_by_angle[abin].Add(ie);
      by_init[tri->from_mesh ? 1 : 0].Add(e);
    }
  }
  PrintBins("adjusted error (rigid fit) by the largest true triangulation angle (deg, lower bin edge):", by_angle,
            "deg");
  PrintBins("adjusted error by views (10: 10 or more):", by_views, "views");
  PrintBins("adjusted error by initialisation (0 triangulated, 1 on the prior mesh):", by_init, "");
  PrintBins("initial landmark error in g (nav prior) by triangulation angle:", init_by_angle, "deg");
  std::printf("initial landmarks: all %zu RMSE %.4f m; triangulated %zu RMSE %.4f m; on the mesh %zu RMSE %.4f m\n",
              init_all.n, init_all.Rms(), init_tri.n, init_tri.Rms(), init_mesh.n, init_mesh.Rms());
  std::sort(worst.rbegin(), worst.rend());
  std::printf("worst landmarks (rigid fit): ");
  for (std::size_t i = 0; i < std::min<std::size_t>(10, worst.size()); ++i)
    std::printf("%lld:%.2f ", static_cast<long long>(worst[i].second), worst[i].first);
  std::printf("\n");
  std::printf("  id: error, true angle, initial error, initial h, adjusted h, true h, observations\n");
  for (std::size_t i = 0; i < std::min<std::size_t>(25, worst.size()); ++i) {
    const auto& d = detail[worst[i].second];
    std::printf("  %lld: %.3f m, %.1f deg, %.3f m, %.3f m, %.3f m, %.3f m, %.0f\n",
                static_cast<long long>(worst[i].second), worst[i].first, d[0], d[1], d[2], d[3], d[4], d[5]);
  }
  // Landmarks standing higher than their truth (what raises an object's max).
  std::map<int, Bin> high_by_views;
  std::printf(
      "landmarks more than 0.1 m above their true deviation (id, object, error, true angle, initial h, "
      "adjusted h, true h, observations):\n");
  int shown = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const LandmarkEstimate& l = *used[static_cast<std::size_t>(i)];
    const auto& d = detail[l.id];
    if (!(d[3] - d[4] > 0.1) || std::abs(d[2]) > 0.5) continue;
    high_by_views[static_cast<int>(d[5])].Add((F.col(i) - T.col(i)).norm());
    if (shown++ < 30)
      std::printf("  %lld %s: %.3f m, %.1f deg, %.3f, %.3f, %.3f, %.0f\n", static_cast<long long>(l.id),
                  truth[l.id]->object.c_str(), (F.col(i) - T.col(i)).norm(), d[0], d[2], d[3], d[4], d[5]);
  }
  PrintBins("  of them, by observations:", high_by_views, "obs");
  // Large adjusted deviations: how many, and their initial deviations.
  std::map<int, Bin> by_h;
  std::size_t far_init = 0, far_init_bad = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const LandmarkEstimate& l = *used[static_cast<std::size_t>(i)];
    const auto& d = detail[l.id];
    const double e = (F.col(i) - T.col(i)).norm();
    const double h = std::abs(d[2]);
    by_h[h < 0.1 ? 0 : h < 0.3 ? 10 : h < 0.5 ? 30 : h < 1 ? 50 : h < 3 ? 100 : 300].Add(e);
    if (h > 0.5) {
      ++far_init;
      far_init_bad += e > 0.1;
    }
  }
  PrintBins("adjusted error by |initial h| (cm, lower edge):", by_h, "cm");
  for (double lim : {0.2, 0.25, 0.3, 0.4, 0.5, 0.75, 1.0}) {
    std::size_t out = 0, out_bad = 0, in_bad = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const LandmarkEstimate& l = *used[static_cast<std::size_t>(i)];
      const bool bad = (F.col(i) - T.col(i)).norm() > 0.1;
      if (std::abs(detail[l.id][2]) > lim) {
        ++out;
        out_bad += bad;
      } else {
        in_bad += bad;
      }
    }
    std::printf("  initial |h| > %.2f m: %zu landmarks (%zu adjusted > 0.1 m off); %zu within it > 0.1 m off\n", lim,
                out, out_bad, in_bad);
  }
  std::printf("initial |h| > 0.5 m: %zu landmarks, %zu of them adjusted > 0.1 m off\n", far_init, far_init_bad);
  // Error quantiles.
  std::vector<double> errs;
  for (const auto& w : worst) errs.push_back(w.first);
  std::sort(errs.begin(), errs.end());
  auto q = [&](double f) { return errs.empty() ? 0.0 : errs[static_cast<std::size_t>(f * (errs.size() - 1))]; };
  std::printf("error quantiles: 50 %% %.4f, 90 %% %.4f, 99 %% %.4f, 99.9 %% %.4f, max %.4f m\n", q(0.5), q(0.9),
              q(0.99), q(0.999), q(1.0));

  // Camera positions along the survey, in M, after the same fit.
  std::printf("adjusted camera position error in M (rigid fit of the landmarks), every 20th keyframe:\n");
  Bin cams;
  for (std::size_t i = 0; i < r.keyframes.size(); ++i) {
    auto p = truth_pose.find(r.keyframes[i]);
    if (p == truth_pose.end()) continue;
    const Pose tc = TrueCameraPoseFromTruth(b, p->second, false);
    const Pose ec =
        est_Mg * Pose::FromVector(r.poses[i]) * b.manifest.VehicleToServo(r.servo[i]) * Pose::FromVector(r.x_s_cT);
    const Eigen::Vector3d fit = rigid.topLeftCorner<3, 3>() * ec.translation() + rigid.topRightCorner<3, 1>();
    const Eigen::Vector3d d = fit - tc.translation();
    cams.Add(d.norm());
    if (i % 20 == 0)
      std::printf("  kf %4lld: %.4f m (%+.3f %+.3f %+.3f)\n", static_cast<long long>(r.keyframes[i]), d.norm(), d.x(),
                  d.y(), d.z());
  }
  std::printf("camera positions: RMSE %.4f m over %zu keyframes\n", cams.Rms(), cams.n);
  return 0;
}
