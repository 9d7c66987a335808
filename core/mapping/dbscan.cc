#include "mapping/dbscan.h"

#include "geometry/point_index.h"

namespace hull {

DbscanResult Dbscan(const std::vector<Eigen::Vector3d>& points, double eps, int min_points) {
  DbscanResult r;
  const int n = static_cast<int>(points.size());
  constexpr int kUnvisited = -2;
  r.labels.assign(static_cast<std::size_t>(n), kUnvisited);
  if (n == 0) return r;
  const PointIndex index(points);
  std::vector<int> queue;
  for (int i = 0; i < n; ++i) {
    if (r.labels[static_cast<std::size_t>(i)] != kUnvisited) continue;
    const auto seeds = index.Within(points[static_cast<std::size_t>(i)], eps);
    if (static_cast<int>(seeds.size()) < min_points) {
      r.labels[static_cast<std::size_t>(i)] = DbscanResult::kNoise;  // may become a border point later
      continue;
    }
    const int cluster = r.num_clusters++;
    r.labels[static_cast<std::size_t>(i)] = cluster;
    queue.clear();
    for (const auto& s : seeds) queue.push_back(s.first);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int j = queue[q];
      int& label = r.labels[static_cast<std::size_t>(j)];
      if (label == DbscanResult::kNoise) label = cluster;  // border point
      if (label != kUnvisited) continue;
      label = cluster;
      const auto more = index.Within(points[static_cast<std::size_t>(j)], eps);
      if (static_cast<int>(more.size()) >= min_points) {
        for (const auto& s : more) {
          const int l = r.labels[static_cast<std::size_t>(s.first)];
          if (l == kUnvisited || l == DbscanResult::kNoise) queue.push_back(s.first);
        }
      }
    }
  }
  return r;
}

}  // namespace hull
