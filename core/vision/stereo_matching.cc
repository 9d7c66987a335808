#include "vision/stereo_matching.h"

#include <cmath>
#include <limits>

#include "vision/camera_geometry.h"

namespace hull {

Eigen::Vector3d TriangulateStereo(const CameraRig& rig, const Eigen::Vector2d& top, const Eigen::Vector2d& bottom) {
  const Pose x_cT_cB = Pose::FromVector(rig.top_to_bottom);
  return TriangulateDlt(ProjectionMatrix(CameraMatrix(rig.top), Pose::Identity()),
                        ProjectionMatrix(CameraMatrix(rig.bottom), x_cT_cB), top, bottom);
}

std::vector<StereoMatch> MatchStereo(const ImageFeatures& top, const ImageFeatures& bottom, const CameraRig& rig,
                                     const StereoOptions& o) {
  o.Check();
  const Pose x_cT_cB = Pose::FromVector(rig.top_to_bottom);
  const Pose x_cB_cT = x_cT_cB.Inverse();
  const Eigen::Matrix3d KT = CameraMatrix(rig.top), KB = CameraMatrix(rig.bottom);
  const Eigen::Matrix3d F = FundamentalMatrix(KT, KB, x_cT_cB);
  const Eigen::Matrix<double, 3, 4> PT = ProjectionMatrix(KT, Pose::Identity());
  const Eigen::Matrix<double, 3, 4> PB = ProjectionMatrix(KB, x_cT_cB);

  // Best candidate per top feature.
  std::vector<StereoMatch> best;
  best.reserve(top.size());
  for (std::size_t i = 0; i < top.size(); ++i) {
    Eigen::Vector3d l = F * top.points[i].homogeneous();
    const double n = std::hypot(l.x(), l.y());
    if (!(n > 0)) continue;
    l /= n;
    float d1 = std::numeric_limits<float>::infinity(), d2 = d1;
    int b1 = -1;
    for (std::size_t j = 0; j < bottom.size(); ++j) {
      if (std::abs(l.dot(bottom.points[j].homogeneous())) > o.epipolar_tolerance) continue;
      const float d = std::sqrt(DescriptorDistance2(top.Descriptor(i), bottom.Descriptor(j)));
      if (d >= d2) continue;
      // The depth check only for a descriptor good enough to matter.
      const Eigen::Vector3d p = TriangulateDlt(PT, PB, top.points[i], bottom.points[j]);
      if (!(p.z() >= o.min_depth && p.z() <= o.max_depth) || (x_cB_cT * p).z() <= 0) continue;
      if (d < d1) {
        d2 = d1;
        d1 = d;
        b1 = static_cast<int>(j);
      } else {
        d2 = d;
      }
    }
    if (b1 < 0 || d1 > o.ratio * d2) continue;  // ratio test (a lone candidate passes: d2 = inf)
    StereoMatch m;
    m.top = static_cast<int>(i);
    m.bottom = b1;
    m.distance = d1;
    m.bottom_uv = bottom.points[static_cast<std::size_t>(b1)];
    m.p_top = TriangulateDlt(PT, PB, top.points[i], bottom.points[static_cast<std::size_t>(b1)]);
    best.push_back(m);
  }
  // One-to-one: a bottom feature keeps the top feature with the smallest distance.
  std::vector<int> owner(bottom.size(), -1);
  for (std::size_t k = 0; k < best.size(); ++k) {
    int& w = owner[static_cast<std::size_t>(best[k].bottom)];
    if (w < 0 || best[k].distance < best[static_cast<std::size_t>(w)].distance) w = static_cast<int>(k);
  }
  std::vector<StereoMatch> out;
  for (std::size_t k = 0; k < best.size(); ++k) {
    if (owner[static_cast<std::size_t>(best[k].bottom)] == static_cast<int>(k)) out.push_back(best[k]);
  }
  return out;
}

}  // namespace hull
