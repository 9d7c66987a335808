#include "mapping/point_cone_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hull {
namespace {

constexpr int kLeafSize = 16;
// Relative slack of the sphere tests, far above rounding error.
constexpr double kSlack = 1e-9;

}  // namespace

PointConeTree::PointConeTree(std::vector<Eigen::Vector3d> points) : points_(std::move(points)) {
  order_.resize(points_.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (!points_.empty()) {
    nodes_.reserve(2 * points_.size() / kLeafSize + 2);
    Build(0, static_cast<int>(points_.size()));
  }
}

int PointConeTree::Build(int begin, int end) {
  Eigen::AlignedBox3d box;
  for (int k = begin; k < end; ++k) box.extend(points_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back({box.center(), 0.5 * box.diagonal().norm(), begin, end, -1, -1});
  if (end - begin <= kLeafSize) return id;
  int axis = 0;
  box.sizes().maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
    const double pa = points_[static_cast<std::size_t>(a)][axis], pb = points_[static_cast<std::size_t>(b)][axis];
    return pa < pb || (pa == pb && a < b);
  });
  // Depth is O(log n) (median split), far below the query stack's 128.
  const int left = Build(begin, mid);
  const int right = Build(mid, end);
  nodes_[static_cast<std::size_t>(id)].left = left;
  nodes_[static_cast<std::size_t>(id)].right = right;
  return id;
}

bool PointConeTree::MayHold(const Node& n, const Eigen::Vector3d& apex, double radius, const Eigen::Vector3d& axis,
                            double cos_half, double sin_half, bool narrow) const {
  const Eigen::Vector3d d = n.centre - apex;
  const double dist = d.norm();
  const double r = n.radius * (1 + kSlack) + kSlack * (1 + dist);
  if (dist - r > radius) return false;  // the sphere lies beyond the ball
  if (!narrow || dist <= r) return true;
  // The sphere meets the cone iff the angle between d and the axis is at
  // most the half-angle plus asin(r / dist): compare sin/cos without acos.
  const double along = d.dot(axis);
  const double across = std::sqrt(std::max(0.0, dist * dist - along * along));
  // Distance from the sphere's centre to the cone's surface (positive
  // outside): across * cos - along * sin, valid where the centre projects
  // onto the cone's side; a centre behind the apex is handled by dist > r
  // above and the cone apex test below.
  const double outside = across * cos_half - along * sin_half;
  if (along * cos_half + across * sin_half < 0) return dist <= r;  // closest cone point is the apex
  return outside <= r;
}

}  // namespace hull
