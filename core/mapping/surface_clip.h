// Exact areas of the parts of a triangle where linear functions are
// non-negative (Sutherland-Hodgman against one plane at a time), carrying a
// linearly interpolated value along: how much of a face lies in a station,
// or where its interpolated deviation exceeds h_min.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hull {

struct ClipVertex {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double value = 0;  // interpolated linearly along edges
};
using ClipPolygon = std::vector<ClipVertex>;

// Keeps the part of the (convex) polygon where f(vertex) >= 0; f must be
// linear along the polygon's edges (an affine function of p, or of value).
template <typename F>
void ClipKeep(ClipPolygon& poly, F f) {
  if (poly.empty()) return;
  ClipPolygon out;
  out.reserve(poly.size() + 2);
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const ClipVertex& a = poly[i];
    const ClipVertex& b = poly[(i + 1) % poly.size()];
    const double fa = f(a), fb = f(b);
    if (fa >= 0) out.push_back(a);
    if ((fa >= 0) != (fb >= 0)) {
      const double t = fa / (fa - fb);
      out.push_back({a.p + t * (b.p - a.p), a.value + t * (b.value - a.value)});
    }
  }
  poly.swap(out);
}

struct ClipMoments {
  double area = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();  // integral of p dA (centroid * area)
  double value = 0;                                 // integral of value dA
};

// Area, first moment and integral of the value of a convex polygon (a fan
// of triangles; exact for the linear value).
inline ClipMoments Moments(const ClipPolygon& poly) {
  ClipMoments m;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    const ClipVertex &a = poly[0], &b = poly[i], &c = poly[i + 1];
    const double area = 0.5 * (b.p - a.p).cross(c.p - a.p).norm();
    m.area += area;
    m.first += area * (a.p + b.p + c.p) / 3.0;
    m.value += area * (a.value + b.value + c.value) / 3.0;
  }
  return m;
}

}  // namespace hull
