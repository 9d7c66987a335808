#include "vision/loop_closure.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "vision/camera_geometry.h"

namespace hull {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr std::size_t kMinFootprintPoints = 10;

// Median, smallest and largest depth of the points.
void SetDepths(KeyframeFootprint& f) {
  std::vector<double> z;
  z.reserve(f.points.size());
  for (const auto& p : f.points) z.push_back(p.z());
  std::sort(z.begin(), z.end());
  f.depth = z[z.size() / 2];
  f.min_depth = z.front();
  f.max_depth = z.back();
}

}  // namespace

KeyframeFootprint StereoFootprint(const KeyframeView& view, int max_points) {
  KeyframeFootprint f;
  const std::size_t n = view.stereo.size();
  if (n < kMinFootprintPoints || max_points < 1) return f;
  const std::size_t stride = (n + static_cast<std::size_t>(max_points) - 1) / static_cast<std::size_t>(max_points);
  for (std::size_t k = 0; k < n; k += stride) f.points.push_back(view.stereo[k].p_top);
  f.source = KeyframeFootprint::Source::kStereo;
  SetDepths(f);
  return f;
}

bool DvlPlane(const SurveyManifest& man, const DvlRecord& dvl, CameraPlane& plane) {
  // The DVL and the camera ride on the same servo: x_cT_d = (-)servo_to_top (+) servo_to_dvl.
  const Pose x_c_d = Pose::FromVector(man.camera.servo_to_top).Inverse() * Pose::FromVector(man.servo_to_dvl);
  std::vector<Eigen::Vector3d> hits;
  for (int b = 0; b < 4; ++b) {
    const double r = dvl.range[static_cast<std::size_t>(b)];
    if (!DvlRecord::HasReturn(r) || !(r > 0)) continue;
    const Eigen::Vector3d p = x_c_d * (r * man.BeamDirection(b));
    if (p.z() > 0) hits.push_back(p);
  }
  if (hits.empty()) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : hits) c += p;
  c /= static_cast<double>(hits.size());
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // fronto-parallel at the returns' depth
  if (hits.size() >= 3) {
    Eigen::MatrixXd A(static_cast<Eigen::Index>(hits.size()), 3);
    for (std::size_t k = 0; k < hits.size(); ++k) A.row(static_cast<Eigen::Index>(k)) = (hits[k] - c).transpose();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
    normal = svd.matrixV().col(2);
    if (normal.dot(c) < 0) normal = -normal;
  }
  const double nc = normal.dot(c);
  if (!(nc > 0)) return false;  // the plane passes through (or behind) the camera
  plane.normal = normal;
  plane.offset = nc;
  plane.centre = c;
  return true;
}

KeyframeFootprint DvlFootprint(const SurveyManifest& man, const DvlRecord& dvl, int max_points) {
  KeyframeFootprint f;
  CameraPlane plane;
  if (max_points < 1 || !DvlPlane(man, dvl, plane)) return f;
  const Eigen::Vector3d& normal = plane.normal;
  const double nc = plane.offset;
  const double far = 3.0 * plane.centre.z();
  const CameraRig& rig = man.camera;
  const double aspect = static_cast<double>(rig.width) / rig.height;
  const int nx = std::max(2, static_cast<int>(std::lround(std::sqrt(max_points * aspect))));
  const int ny = std::max(2, max_points / nx);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d uv((i + 0.5) / nx * rig.width - 0.5, (j + 0.5) / ny * rig.height - 0.5);
      const Eigen::Vector3d ray = rig.top.Unproject(uv);
      const double nr = normal.dot(ray);
      if (!(nr > 1e-9)) continue;
      const double t = nc / nr;  // the ray has unit depth: t is the point's z
      if (t > 0 && t <= far) f.points.push_back(t * ray);
    }
  }
  if (f.points.size() < kMinFootprintPoints) {
    f.points.clear();
    return f;
  }
  f.source = KeyframeFootprint::Source::kDvl;
  SetDepths(f);
  return f;
}

void PlaceFootprint(KeyframeFootprint& f, const Pose& x_g_c) {
  f.centre_g.setZero();
  f.radius = 0;
  if (f.points.empty()) return;
  for (const auto& p : f.points) f.centre_g += x_g_c * p;
  f.centre_g /= static_cast<double>(f.points.size());
  for (const auto& p : f.points) f.radius = std::max(f.radius, (x_g_c * p - f.centre_g).norm());
}

double FootprintShareInView(const KeyframeFootprint& a, const Pose& x_g_ca, const Pose& x_g_cb, const CameraRig& rig) {
  if (a.points.empty()) return 0;
  const Pose x_cb_ca = x_g_cb.Inverse() * x_g_ca;
  int in = 0;
  for (const auto& p : a.points) {
    const Eigen::Vector3d q = x_cb_ca * p;
    if (q.z() > 1e-6 && rig.InImage(rig.top.Project(q))) ++in;
  }
  return static_cast<double>(in) / static_cast<double>(a.points.size());
}

std::vector<LoopCandidate> FindLoopCandidates(const std::vector<LoopKeyframe>& kf, const CameraRig& rig, int neighbours,
                                              const LoopOptions& o, std::size_t* considered) {
  o.Check();
  std::vector<std::size_t> ids;  // keyframes with a footprint, by footprint centre x
  double max_radius = 0;
  for (std::size_t i = 0; i < kf.size(); ++i) {
    if (kf[i].footprint.empty()) continue;
    ids.push_back(i);
    max_radius = std::max(max_radius, kf[i].footprint.radius);
  }
  std::stable_sort(ids.begin(), ids.end(), [&](std::size_t a, std::size_t b) {
    return kf[a].footprint.centre_g.x() < kf[b].footprint.centre_g.x();
  });
  const double cos_view = std::cos(o.max_view_angle_deg * kDeg);
  std::vector<LoopCandidate> found;
  std::size_t tried = 0;
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const LoopKeyframe& A = kf[ids[p]];
    for (std::size_t q = p + 1; q < ids.size(); ++q) {
      const LoopKeyframe& B = kf[ids[q]];
      const double reach = A.footprint.radius + B.footprint.radius;
      if (B.footprint.centre_g.x() - A.footprint.centre_g.x() > A.footprint.radius + max_radius) break;
      if ((B.footprint.centre_g - A.footprint.centre_g).norm() > reach) continue;  // footprints apart
      if (std::abs(A.order - B.order) <= neighbours) continue;                     // matched as neighbours
      const double path = std::abs(B.path - A.path);
      const double distance = (B.x_g_cT.translation() - A.x_g_cT.translation()).norm();
      if (path < o.min_path_ratio * std::max(distance, 0.5 * reach)) continue;  // the next ones along the way
      if (A.x_g_cT.rotation().col(2).dot(B.x_g_cT.rotation().col(2)) < cos_view) continue;
      ++tried;
      const double overlap = std::min(FootprintShareInView(A.footprint, A.x_g_cT, B.x_g_cT, rig),
                                      FootprintShareInView(B.footprint, B.x_g_cT, A.x_g_cT, rig));
      if (overlap < o.min_overlap) continue;
      LoopCandidate c;
      c.a = std::min(ids[p], ids[q]);
      c.b = std::max(ids[p], ids[q]);
      c.overlap = overlap;
      c.seconds = std::abs(B.t - A.t);
      c.path = path;
      found.push_back(c);
    }
  }
  if (considered) *considered = tried;
  // Each keyframe keeps its best `candidates` partners: larger overlap first,
  // then the partner nearer in order, then the smaller index.
  std::vector<std::vector<std::size_t>> of(kf.size());  // keyframe -> indices into found
  for (std::size_t c = 0; c < found.size(); ++c) {
    of[found[c].a].push_back(c);
    of[found[c].b].push_back(c);
  }
  std::vector<char> keep(found.size(), 0);
  for (std::size_t k = 0; k < kf.size(); ++k) {
    auto& list = of[k];
    auto key = [&](std::size_t c) {
      const std::size_t other = found[c].a == k ? found[c].b : found[c].a;
      return std::make_tuple(-found[c].overlap, std::abs(kf[other].order - kf[k].order), other);
    };
    std::sort(list.begin(), list.end(), [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
    for (std::size_t r = 0; r < list.size() && r < static_cast<std::size_t>(o.candidates); ++r) keep[list[r]] = 1;
  }
  std::vector<LoopCandidate> out;
  for (std::size_t c = 0; c < found.size(); ++c) {
    if (keep[c]) out.push_back(found[c]);
  }
  std::sort(out.begin(), out.end(),
            [](const LoopCandidate& x, const LoopCandidate& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  return out;
}

TemporalOptions LoopMatchingOptions(const TemporalOptions& base, const LoopOptions& loop, const NoiseModel& noise,
                                    double focal_px, const KeyframeFootprint& a, double seconds, double path,
                                    double distance) {
  TemporalOptions o = base;
  const double sigma_rot = noise.odometry_rotation_rate * std::abs(seconds);
  const double sigma_pos = noise.odometry_translation_rate * std::abs(seconds) + 0.5 * sigma_rot * std::abs(path);
  const double k = loop.drift_sigmas;
  const double z = std::max(a.depth, 1e-3);
  o.window = std::min(loop.max_window, base.window + k * focal_px * (sigma_pos / z + sigma_rot));
  o.window = std::max(o.window, base.window);
  o.max_rotation_error_deg = std::min(180.0, base.max_rotation_error_deg + k * sigma_rot / kDeg);
  o.max_translation_error = base.max_translation_error + k * sigma_pos;
  if (distance > 1e-9) {
    o.max_direction_error_deg =
        std::min(180.0, base.max_direction_error_deg + std::atan(k * sigma_pos / distance) / kDeg);
  }
  o.min_inliers = loop.min_inliers;
  if (!a.empty()) {
    const double near = std::max(base.mono_min_depth, a.min_depth / 1.5);
    const double far = std::min(base.mono_max_depth, a.max_depth * 1.5);
    if (near < far) {
      o.mono_min_depth = near;
      o.mono_max_depth = far;
    }
  }
  return o;
}

}  // namespace hull
