// k-nearest and radius search over a 3-D point set (a k-d tree from
// nanoflann, Debian's libnanoflann-dev).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

namespace hull {

class PointIndex {
 public:
  // The points are copied.
  explicit PointIndex(std::vector<Eigen::Vector3d> points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  std::size_t size() const;
  const Eigen::Vector3d& point(std::size_t i) const;

  // Indices of the k nearest points, nearest first, with squared distances.
  std::vector<std::pair<int, double>> Nearest(const Eigen::Vector3d& q, int k) const;
  // The nearest point and its squared distance, without allocating;
  // (-1, infinity) when the index is empty.
  std::pair<int, double> NearestOne(const Eigen::Vector3d& q) const;
  // Indices of all points within radius (not squared), nearest first, or in
  // the tree's order when not `sorted` (saves the sort of a large result).
  std::vector<std::pair<int, double>> Within(const Eigen::Vector3d& q, double radius, bool sorted = true) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hull
