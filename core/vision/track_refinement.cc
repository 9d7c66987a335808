#include "vision/track_refinement.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <algorithm>
#include <numeric>

#include "vision/camera_geometry.h"
#include "vision/feature_detection.h"
#include "vision/patch_alignment.h"

namespace hull {

std::vector<int> DuplicateKeypoints(const std::vector<Eigen::Vector2d>& points) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Eigen::Vector2d &p = points[static_cast<std::size_t>(a)], &q = points[static_cast<std::size_t>(b)];
    return p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : a < b;
  });
  std::vector<int> first(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t f = static_cast<std::size_t>(order[i]);
    const bool same = i > 0 && points[static_cast<std::size_t>(order[i - 1])] == points[f];
    first[f] = same ? first[static_cast<std::size_t>(order[i - 1])] : order[i];
  }
  return first;
}

TrackRefinementStats RefineTrackPixels(const std::vector<TrackBuilder::Track>& tracks,
                                       const std::function<cv::Mat(std::size_t)>& image,
                                       const std::vector<Pose>& cameras, const PinholeIntrinsics& intrinsics,
                                       std::vector<std::vector<Eigen::Vector2d>>& points, const TrackOptions& o,
                                       int threads) {
  o.Check();
  TrackRefinementStats stats;
  const std::size_t n = points.size();
  const int radius = o.refine_radius;
  const Eigen::Matrix3d K = CameraMatrix(intrinsics);
  DetectionOptions grey;  // 8-bit grey, no CLAHE: gain and bias are estimated
  grey.clahe = false;
  // Per keyframe: the tracks it is the reference of, and the members it holds.
  std::vector<std::vector<int>> references(n);
  struct Member {
    int track, feature;
  };
  std::vector<std::vector<Member>> members(n);
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const TrackBuilder::Track& track = tracks[t];
    if (track.size() < 2) continue;
    references[static_cast<std::size_t>(track.front().first)].push_back(static_cast<int>(t));
    for (std::size_t j = 1; j < track.size(); ++j)
      members[static_cast<std::size_t>(track[j].first)].push_back({static_cast<int>(t), track[j].second});
  }
  std::vector<std::vector<float>> patch(tracks.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  // 1. The reference patches.
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t k) {
      if (references[k].empty()) return;
      const GradientImage g = MakeGradientImage(NormaliseImage(image(k), grey));
      for (const int t : references[k]) {
        const auto& [ki, f] = tracks[static_cast<std::size_t>(t)].front();
        if (!SamplePatch(g.image, points[k][static_cast<std::size_t>(f)], radius, patch[static_cast<std::size_t>(t)]))
          patch[static_cast<std::size_t>(t)].clear();
      }
    });
  });
  // 2. Each member aligned with its track's reference.
  std::vector<TrackRefinementStats> per(n);
  std::vector<std::vector<Eigen::Vector2d>> refined(n);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t k) {
      if (members[k].empty()) return;
      const GradientImage g = MakeGradientImage(NormaliseImage(image(k), grey));
      refined[k].resize(members[k].size());
      for (std::size_t m = 0; m < members[k].size(); ++m) {
        const Member& mb = members[k][m];
        const Eigen::Vector2d& start = points[k][static_cast<std::size_t>(mb.feature)];
        refined[k][m] = start;
        ++per[k].members;
        const std::vector<float>& ref = patch[static_cast<std::size_t>(mb.track)];
        if (ref.empty()) {
          ++per[k].kept;
          continue;
        }
        const auto& [ka, fa] = tracks[static_cast<std::size_t>(mb.track)].front();
        const std::size_t a = static_cast<std::size_t>(ka);
        const Eigen::Matrix2d warp0 = InfiniteHomographyWarp(
            K, K, cameras[k].rotation().transpose() * cameras[a].rotation(), points[a][static_cast<std::size_t>(fa)]);
        const PatchAlignment al = AlignPatch(ref, radius, g, start, warp0, false);
        if (!al.converged || (al.point - start).norm() > o.refine_max_shift || al.ncc < o.refine_min_ncc) {
          ++per[k].kept;
          continue;
        }
        refined[k][m] = al.point;
        ++per[k].refined;
      }
    });
  });
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t m = 0; m < members[k].size(); ++m)
      points[k][static_cast<std::size_t>(members[k][m].feature)] = refined[k][m];
    stats.members += per[k].members;
    stats.refined += per[k].refined;
    stats.kept += per[k].kept;
  }
  return stats;
}

}  // namespace hull
