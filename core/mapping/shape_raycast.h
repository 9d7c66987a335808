// Rays from the top camera's centre against a 2.5-D shape of Algorithm 1,
// in the camera frame (the ray starts at the origin). ShapeFootprint
// answers the same question as FirstShapeHit without trying every
// triangle: a ray from the origin meets a triangle (in front of the camera)
// exactly when its direction, projected onto the normalised image plane
// z = 1, falls inside the triangle's projection, so a 2-D grid over the
// projected triangles names the few candidates, and a circular cone around
// the shape bounds every ray that can meet it.
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

struct ShapeHit {
  bool hit = false;
  double t = 0;       // the point is t * dir
  int triangle = -1;  // the triangle met first (smallest t; ties: smallest index)
};

// The first hit of the ray t * dir (t > 0) over all the shape's triangles.
ShapeHit FirstShapeHit(const DetectedShape& shape, const Eigen::Vector3d& dir);

class ShapeFootprint {
 public:
  explicit ShapeFootprint(const DetectedShape& shape);

  // Bit-identical to FirstShapeHit(shape, dir) for every dir.
  ShapeHit Hit(const Eigen::Vector3d& dir) const;

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
