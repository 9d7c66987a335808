#include "vision/track_check.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <algorithm>
#include <cmath>
#include <limits>

#include "vision/camera_geometry.h"

namespace hull {

bool TrackCheckKeeps(const TrackCheck& c, const TrackOptions& o) {
  if (std::isnan(c.min_height)) return true;
  if (c.min_height > o.check_max_height || c.max_height < o.check_min_height) return false;
  return !(c.members.size() >= 3 && c.max_reprojection > o.check_max_reprojection &&
           c.min_height >= o.check_reprojection_height);
}

std::vector<TrackCheck> CheckTrackHeights(const std::vector<TrackBuilder::Track>& tracks,
                                          const std::vector<KeyframeView>& views,
                                          const std::vector<std::vector<char>>& has_stereo,
                                          const std::vector<std::optional<CameraPlane>>& planes, const CameraRig& rig,
                                          const TrackOptions& o, int threads) {
  o.Check();
  const Eigen::Matrix3d K = CameraMatrix(rig.top);
  const std::size_t n = views.size();
  std::vector<Pose> x_c_g(n);
  std::vector<Eigen::Matrix<double, 3, 4>> P(n);
  for (std::size_t k = 0; k < n; ++k) {
    x_c_g[k] = views[k].x_g_cT.Inverse();
    P[k] = ProjectionMatrix(K, views[k].x_g_cT);
  }
  // The tracks to check: few keyframes, no stereo match among their features.
  std::vector<int> checked;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const TrackBuilder::Track& track = tracks[t];
    if (track.size() < 2 || track.size() > static_cast<std::size_t>(o.check_max_keyframes)) continue;
    bool mono = true;
    for (const auto& [k, f] : track)
      mono = mono && !has_stereo[static_cast<std::size_t>(k)][static_cast<std::size_t>(f)];
    if (mono) checked.push_back(static_cast<int>(t));
  }
  std::vector<TrackCheck> out(checked.size());
  std::vector<char> valid(checked.size(), 0);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, checked.size(), [&](std::size_t i) {
      const TrackBuilder::Track& track = tracks[static_cast<std::size_t>(checked[i])];
      // The two members farthest apart in nav order (the widest baseline along a leg).
      const auto [ka, fa] = track.front();
      const auto [kb, fb] = track.back();
      const std::size_t a = static_cast<std::size_t>(ka), b = static_cast<std::size_t>(kb);
      const Eigen::Vector3d X = TriangulateDlt(P[a], P[b], views[a].top.points[static_cast<std::size_t>(fa)],
                                               views[b].top.points[static_cast<std::size_t>(fb)]);
      if (!X.allFinite()) return;
      TrackCheck c;
      c.track = checked[i];
      c.members = track;
      c.point = X;
      c.min_height = std::numeric_limits<double>::infinity();
      c.max_height = -std::numeric_limits<double>::infinity();
      for (const auto& [k, f] : track) {
        const std::size_t ki = static_cast<std::size_t>(k);
        const Eigen::Vector3d Xc = x_c_g[ki] * X;
        if (Xc.z() <= 0) return;  // behind a camera of its own: left to the adjustment
        const Eigen::Vector2d uv = (K * Xc).hnormalized();
        c.max_reprojection =
            std::max(c.max_reprojection, (uv - views[ki].top.points[static_cast<std::size_t>(f)]).norm());
        if (!planes[ki]) continue;
        const double h = planes[ki]->HeightOf(Xc);
        c.min_height = std::min(c.min_height, h);
        c.max_height = std::max(c.max_height, h);
      }
      if (std::isinf(c.min_height)) {
        c.min_height = c.max_height = std::nan("");
      } else {
        c.kept = TrackCheckKeeps(c, o);
      }
      out[i] = c;
      valid[i] = 1;
    });
  });
  std::vector<TrackCheck> result;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (valid[i]) result.push_back(std::move(out[i]));
  }
  return result;
}

}  // namespace hull
