// A bounding-volume tree over a fixed point set that finds the points inside
// a ball around an apex and inside a circular cone from it: the model
// vertices a camera's rays through a shape can reach (Algorithm 2) and the
// surface samples a camera's image can see (the inspected area). Nodes are
// bounded by spheres; a node is skipped only when its sphere misses the
// ball or the cone, so the query is exact up to the final per-point test,
// which the caller makes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace hull {

class PointConeTree {
 public:
  explicit PointConeTree(std::vector<Eigen::Vector3d> points);

  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3d& point(int i) const { return points_[static_cast<std::size_t>(i)]; }

  // Calls visit(i) for every point i that may lie within `radius` of apex
  // and within the cone (unit axis, half-angle with the given cosine and
  // sine, below 90 degrees): every point that does is visited (once), a few
  // that do not may be. With narrow = false the cone is ignored (a ball
  // query).
  template <typename Visit>
  void Query(const Eigen::Vector3d& apex, double radius, const Eigen::Vector3d& axis, double cos_half, double sin_half,
             bool narrow, Visit&& visit) const;

 private:
  struct Node {
    Eigen::Vector3d centre;
    double radius;
    int begin, end;   // range of order_
    int left, right;  // children, -1 for a leaf
  };
  int Build(int begin, int end);
  bool MayHold(const Node& n, const Eigen::Vector3d& apex, double radius, const Eigen::Vector3d& axis, double cos_half,
               double sin_half, bool narrow) const;

  std::vector<Eigen::Vector3d> points_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

template <typename Visit>
void PointConeTree::Query(const Eigen::Vector3d& apex, double radius, const Eigen::Vector3d& axis, double cos_half,
                          double sin_half, bool narrow, Visit&& visit) const {
  if (nodes_.empty()) return;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    if (!MayHold(n, apex, radius, axis, cos_half, sin_half, narrow)) continue;
    if (n.left < 0) {
      for (int k = n.begin; k < n.end; ++k) visit(order_[static_cast<std::size_t>(k)]);
    } else {
      stack[top++] = n.right;
      stack[top++] = n.left;
    }
  }
}

}  // namespace hull
