#include "mapping/shape_raycast.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hull {
namespace {

// Margin (on the plane z = 1) around each projected triangle's bounding box:
// far above rounding error, far below any feature's size.
constexpr double kFootprintMargin = 1e-9;
// Widening of the bounding cone (rad), for the same reason.
constexpr double kConeMargin = 1e-7;
// Wider cones than this bound nothing useful.
constexpr double kMaxConeHalfAngle = 80.0 * M_PI / 180.0;
// NormalReach's margin over the shape's largest |deviation| (m): the CAD's
// curvature under a shape (a 5 m bilge radius bends 0.3 m of hull by 2 mm)
// and the adjustment's noise, with room to spare.
constexpr double kNormalReachMargin = 0.05;
// Barycentric coordinates are accepted down to -kBarycentricSlack (a few
// hundred nanometres on a shape's 5-10 cm triangles, far above rounding).
constexpr double kBarycentricSlack = 1e-9;

}  // namespace

bool RayTriangleFromOrigin(const Eigen::Vector3d& dir, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, double* t) {
  return SegmentTriangle(Eigen::Vector3d::Zero(), dir, a, b, c, std::numeric_limits<double>::infinity(), t);
}

bool SegmentTriangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, const Eigen::Vector3d& c, double t_max, double* t) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d pvec = dir.cross(e2);
  const double det = e1.dot(pvec);
  if (det == 0 || !std::isfinite(det)) return false;
  const double inv = 1.0 / det;
  const Eigen::Vector3d tvec = origin - a;
  // Barycentric bounds widened by kBarycentricSlack: a line through a
  // triangle's corner or along its edge (the fusion along normals casts the
  // line of the vertex moved under a shape's vertex exactly through it) is
  // a hit, not a coin toss of rounding.
  const double u = tvec.dot(pvec) * inv;
  if (u < -kBarycentricSlack || u > 1 + kBarycentricSlack) return false;
  const Eigen::Vector3d qvec = tvec.cross(e1);
  const double v = dir.dot(qvec) * inv;
  if (v < -kBarycentricSlack || u + v > 1 + kBarycentricSlack) return false;
  const double tt = e2.dot(qvec) * inv;
  if (!(tt > 0 && tt <= t_max)) return false;
  *t = tt;
  return true;
}

double NormalReach(const DetectedShape& shape) {
  double d = 0;
  for (const double x : shape.deviation) d = std::max(d, std::abs(x));
  return d + kNormalReachMargin;
}

namespace {

void TrySegmentTriangle(const DetectedShape& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max,
                        int i, ShapeHit& best) {
  const Face& f = s.triangles[static_cast<std::size_t>(i)];
  double t = 0;
  if (!SegmentTriangle(origin, dir, s.vertices_c[static_cast<std::size_t>(f[0])],
                       s.vertices_c[static_cast<std::size_t>(f[1])], s.vertices_c[static_cast<std::size_t>(f[2])],
                       t_max, &t)) {
    return;
  }
  if (!best.hit || t < best.t || (t == best.t && i < best.triangle)) best = {true, t, i};
}

void TryTriangle(const DetectedShape& s, const Eigen::Vector3d& dir, int i, ShapeHit& best) {
  const Face& f = s.triangles[static_cast<std::size_t>(i)];
  double t = 0;
  if (!RayTriangleFromOrigin(dir, s.vertices_c[static_cast<std::size_t>(f[0])],
                             s.vertices_c[static_cast<std::size_t>(f[1])], s.vertices_c[static_cast<std::size_t>(f[2])],
                             &t)) {
    return;
  }
  if (!best.hit || t < best.t) best = {true, t, i};
}

}  // namespace

ShapeHit FirstShapeHit(const DetectedShape& shape, const Eigen::Vector3d& dir) {
  ShapeHit best;
  for (int i = 0; i < static_cast<int>(shape.triangles.size()); ++i) TryTriangle(shape, dir, i, best);
  return best;
}

ShapeHit FirstShapeHitOnSegment(const DetectedShape& shape, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                double t_max) {
  ShapeHit best;
  for (int i = 0; i < static_cast<int>(shape.triangles.size()); ++i) {
    TrySegmentTriangle(shape, origin, dir, t_max, i, best);
  }
  return best;
}

ShapeFootprint::ShapeFootprint(const DetectedShape& shape) : shape_(shape) {
  const int nt = static_cast<int>(shape.triangles.size());
  if (nt == 0) return;
  // Bounding cone of the vertex directions (it holds their convex hull, so
  // every ray through a triangle).
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& v : shape.vertices_c) sum += v.normalized();
  if (sum.norm() > 1e-12) {
    axis_ = sum.normalized();
    double min_cos = 1;
    for (const auto& v : shape.vertices_c) min_cos = std::min(min_cos, axis_.dot(v.normalized()));
    const double half = std::acos(std::clamp(min_cos, -1.0, 1.0)) + kConeMargin;
    if (half < kMaxConeHalfAngle) {
      narrow_ = true;
      cos_ = std::cos(half);
      sin_ = std::sin(half);
    }
  }
  // Projected triangles' boxes and the grid over them.
  std::vector<Eigen::Vector2d> q(shape.vertices_c.size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = shape.vertices_c[i].head<2>() / shape.vertices_c[i].z();
  std::vector<Eigen::AlignedBox2d> boxes(static_cast<std::size_t>(nt));
  Eigen::AlignedBox2d all;
  for (int i = 0; i < nt; ++i) {
    Eigen::AlignedBox2d b;
    for (const int v : shape.triangles[static_cast<std::size_t>(i)]) b.extend(q[static_cast<std::size_t>(v)]);
    b.min().array() -= kFootprintMargin;
    b.max().array() += kFootprintMargin;
    boxes[static_cast<std::size_t>(i)] = b;
    all.extend(b);
  }
  lo_ = all.min();
  const Eigen::Vector2d size = all.sizes();
  const double side = std::sqrt(std::max(size.x() * size.y(), 1e-24) / std::max(nt, 1));
  cell_ = std::max({side, size.x() / 256.0, size.y() / 256.0, 1e-12});
  nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_)));
  std::vector<int> count(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
  auto range = [&](const Eigen::AlignedBox2d& b, int& x0, int& x1, int& y0, int& y1) {
    x0 = std::clamp(static_cast<int>(std::floor((b.min().x() - lo_.x()) / cell_)), 0, nx_ - 1);
    x1 = std::clamp(static_cast<int>(std::floor((b.max().x() - lo_.x()) / cell_)), 0, nx_ - 1);
    y0 = std::clamp(static_cast<int>(std::floor((b.min().y() - lo_.y()) / cell_)), 0, ny_ - 1);
    y1 = std::clamp(static_cast<int>(std::floor((b.max().y() - lo_.y()) / cell_)), 0, ny_ - 1);
  };
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      cell_start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
      for (int i = 0; i < nx_ * ny_; ++i) cell_start_[static_cast<std::size_t>(i) + 1] = cell_start_[i] + count[i];
      tri_.assign(static_cast<std::size_t>(cell_start_.back()), 0);
      std::fill(count.begin(), count.end(), 0);
    }
    for (int i = 0; i < nt; ++i) {
      int x0, x1, y0, y1;
      range(boxes[static_cast<std::size_t>(i)], x0, x1, y0, y1);
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const std::size_t c =
              static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
          if (pass == 1) tri_[static_cast<std::size_t>(cell_start_[c]) + static_cast<std::size_t>(count[c])] = i;
          ++count[c];
        }
      }
    }
  }
}

ShapeHit ShapeFootprint::Hit(const Eigen::Vector3d& dir) const {
  ShapeHit best;
  if (tri_.empty() || !(dir.z() > 0)) return best;  // every triangle lies in front of the camera
  const double a = dir.x() / dir.z(), b = dir.y() / dir.z();
  const double fx = std::floor((a - lo_.x()) / cell_), fy = std::floor((b - lo_.y()) / cell_);
  if (!(fx >= 0 && fy >= 0 && fx < nx_ && fy < ny_)) return best;
  const int c = static_cast<int>(fy) * nx_ + static_cast<int>(fx);
  for (int k = cell_start_[static_cast<std::size_t>(c)]; k < cell_start_[static_cast<std::size_t>(c) + 1]; ++k) {
    TryTriangle(shape_, dir, tri_[static_cast<std::size_t>(k)], best);
  }
  return best;
}

ShapeHit ShapeFootprint::SegmentHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max) const {
  if (tri_.empty()) return {};
  const Eigen::Vector3d end = origin + t_max * dir;
  // A segment not wholly in front of the camera does not project onto a 2-D
  // segment; it is tried against every triangle (the camera would have to
  // lie within a vertex's reach of the hull).
  if (!(origin.z() > 0 && end.z() > 0)) return FirstShapeHitOnSegment(shape_, origin, dir, t_max);
  Eigen::AlignedBox2d box;
  box.extend(origin.head<2>() / origin.z());
  box.extend(end.head<2>() / end.z());
  box.min().array() -= kFootprintMargin;
  box.max().array() += kFootprintMargin;
  const double fx0 = std::floor((box.min().x() - lo_.x()) / cell_), fx1 = std::floor((box.max().x() - lo_.x()) / cell_);
  const double fy0 = std::floor((box.min().y() - lo_.y()) / cell_), fy1 = std::floor((box.max().y() - lo_.y()) / cell_);
  if (!(fx1 >= 0 && fy1 >= 0 && fx0 < nx_ && fy0 < ny_)) return {};  // misses the grid (or NaN)
  const int x0 = static_cast<int>(std::max(fx0, 0.0)), x1 = static_cast<int>(std::min(fx1, nx_ - 1.0));
  const int y0 = static_cast<int>(std::max(fy0, 0.0)), y1 = static_cast<int>(std::min(fy1, ny_ - 1.0));
  thread_local std::vector<int> candidates;
  candidates.clear();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
      candidates.insert(candidates.end(), tri_.begin() + cell_start_[c], tri_.begin() + cell_start_[c + 1]);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  ShapeHit best;
  for (const int i : candidates) TrySegmentTriangle(shape_, origin, dir, t_max, i, best);
  return best;
}

}  // namespace hull
