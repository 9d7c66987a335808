// 2-D alpha shapes (Edelsbrunner and Muecke) by CGAL's Alpha_shape_2 over a
// Delaunay triangulation: the triangles of the alpha complex, i.e. the
// Delaunay triangles whose circumradius is at most alpha. Algorithm 1 of
// Ozog et al. meshes each cluster of features this way over their camera
// (x, y) and lifts the vertices by their camera z (a 2.5-D shape).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace hull {

// Triangles (indices into xy, counter-clockwise in the (x, y) plane) of the
// regularized alpha shape of xy for the radius alpha (CGAL is given
// alpha^2). A point that repeats an earlier one exactly is left out (the
// first stands for both); fewer than three distinct points, or points on a
// line, give no triangles.
std::vector<Face> AlphaShapeTriangles(const std::vector<Eigen::Vector2d>& xy, double alpha);

}  // namespace hull
