// DBSCAN (Ester, Kriegel, Sander and Xu, 1996) over 3-D points, with the
// neighbourhoods from the k-d tree of geometry/point_index.h.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hull {

struct DbscanResult {
  static constexpr int kNoise = -1;
  // Per point: the cluster (0 .. num_clusters - 1) or kNoise. Clusters are
  // numbered in the order of their first core point (by index); a border
  // point reachable from several clusters belongs to the first of them.
  std::vector<int> labels;
  int num_clusters = 0;
};

// A point is a core point when at least min_points points (itself included)
// lie within eps of it (Euclidean, distance <= eps). Every point
// density-reachable from a core point joins its cluster; the rest is noise.
// Deterministic; O(n log n) for bounded density.
DbscanResult Dbscan(const std::vector<Eigen::Vector3d>& points, double eps, int min_points);

}  // namespace hull
