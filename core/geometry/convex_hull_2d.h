// The convex hull of points in the plane (Andrew's monotone chain).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hull {

// Counter-clockwise, without repeated or collinear points; fewer than three
// distinct points: those, sorted.
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points);

}  // namespace hull
