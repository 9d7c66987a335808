// Rays from the top camera's centre against a 2.5-D shape of Algorithm 1,
// in the camera frame (the ray starts at the origin). ShapeFootprint
// answers the same question as FirstShapeHit without trying every
// triangle: a ray from the origin meets a triangle (in front of the camera)
// exactly when its direction, projected onto the normalised image plane
// z = 1, falls inside the triangle's projection, so a 2-D grid over the
// projected triangles names the few candidates, and a circular cone around
// the shape bounds every ray that can meet it.
//
// The same grid answers the fusion along vertex normals: a segment in front
// of the camera projects onto z = 1 as the 2-D segment between its ends'
// projections, so the triangles it meets are among those of the cells that
// 2-D segment's box covers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "mapping/shape_detection.h"

namespace hull {

// Moeller-Trumbore for the ray t * dir (t > 0) from the origin against the
// triangle (a, b, c), both faces. On a hit, *t is the ray parameter (in
// units of |dir|).
bool RayTriangleFromOrigin(const Eigen::Vector3d& dir, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, double* t);

// Moeller-Trumbore for the segment origin + t * dir, 0 < t <= t_max,
// against the triangle (a, b, c), both faces. On a hit, *t is the segment
// parameter (in units of |dir|).
bool SegmentTriangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, const Eigen::Vector3d& c, double t_max, double* t);

struct ShapeHit {
  bool hit = false;
  double t = 0;       // the point is t * dir
  int triangle = -1;  // the triangle met first (smallest t; ties: smallest index)
};

// The first hit of the ray t * dir (t > 0) over all the shape's triangles.
ShapeHit FirstShapeHit(const DetectedShape& shape, const Eigen::Vector3d& dir);

// The first hit of the segment origin + t * dir (0 < t <= t_max, in the
// camera frame) over all the shape's triangles: smallest t, ties the
// smallest triangle index.
ShapeHit FirstShapeHitOnSegment(const DetectedShape& shape, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                double t_max);

// How far along a model vertex's normal the fusion looks for a shape (m):
// the shape's largest |deviation| from the CAD plus a margin for the hull's
// curvature under it. A point of the shape lies no higher above the CAD than
// its highest vertex (up to that curvature), so no hit over a vertex is
// farther from it.
double NormalReach(const DetectedShape& shape);

class ShapeFootprint {
 public:
  explicit ShapeFootprint(const DetectedShape& shape);

  // Bit-identical to FirstShapeHit(shape, dir) for every dir.
  ShapeHit Hit(const Eigen::Vector3d& dir) const;

  // Bit-identical to FirstShapeHitOnSegment(shape, origin, dir, t_max).
  ShapeHit SegmentHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max) const;

  // A circular cone from the camera centre holding every ray that can meet
  // the shape: unit axis and the cosine and sine of its half-angle. `narrow`
  // is false when the cone is too wide to bound anything (half-angle near
  // 90 degrees); then every direction must be tried.
  const Eigen::Vector3d& axis() const { return axis_; }
  double cos_half_angle() const { return cos_; }
  double sin_half_angle() const { return sin_; }
  bool narrow() const { return narrow_; }

 private:
  const DetectedShape& shape_;
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();
  double cos_ = -1, sin_ = 0;
  bool narrow_ = false;
  // Grid over the projected triangles' bounding boxes on z = 1.
  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  double cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_;  // CSR: triangles of cell i are tri_[cell_start_[i] .. cell_start_[i+1])
  std::vector<int> tri_;
};

}  // namespace hull
