// The only translation unit that instantiates CGAL's Alpha_shape_2.
#include "mapping/alpha_shape.h"

#include <CGAL/Alpha_shape_2.h>
#include <CGAL/Alpha_shape_face_base_2.h>
#include <CGAL/Alpha_shape_vertex_base_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <utility>

namespace hull {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb0 = CGAL::Alpha_shape_vertex_base_2<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K, Vb0>;
using Fb = CGAL::Alpha_shape_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using AlphaShape = CGAL::Alpha_shape_2<Delaunay>;

}  // namespace

std::vector<Face> AlphaShapeTriangles(const std::vector<Eigen::Vector2d>& xy, double alpha) {
  std::vector<Face> out;
  if (xy.size() < 3 || !(alpha > 0)) return out;
  std::vector<std::pair<K::Point_2, int>> points;
  points.reserve(xy.size());
  for (std::size_t i = 0; i < xy.size(); ++i)
    points.emplace_back(K::Point_2(xy[i].x(), xy[i].y()), static_cast<int>(i));
  // Inserted one by one in input order, so that a repeated point keeps the
  // info (index) of its first occurrence.
  Delaunay dt;
  for (const auto& p : points) {
    const std::size_t before = dt.number_of_vertices();
    const auto v = dt.insert(p.first);
    if (dt.number_of_vertices() > before) v->info() = p.second;  // a new vertex, not a repeat
  }
  if (dt.dimension() < 2) return out;
  AlphaShape shape(dt, alpha * alpha, AlphaShape::REGULARIZED);
  for (auto f = shape.finite_faces_begin(); f != shape.finite_faces_end(); ++f) {
    if (shape.classify(f) != AlphaShape::INTERIOR) continue;
    out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  return out;
}

}  // namespace hull
