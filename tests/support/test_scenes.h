// Textured surfaces with analytic ray casting, rendered from known pinhole
// cameras, for the visual front end's tests and benchmark: every pixel's 3-D
// point is known, so true correspondences between any two views are too.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "geometry/pose.h"

namespace hull::testing {

// Multi-octave value noise (non-repeating blobs at 4..64 texels, as SIFT
// finds on painted, stained steel), CV_32F in [0, 1], size x size texels.
cv::Mat RandomTexture(int size, int seed);

struct TexturedSurface {
  enum class Kind { kPlane, kCylinder };
  Kind kind = Kind::kPlane;
  // Plane: a point on it and two unit in-plane axes (texture s and t).
  // Cylinder: a point on the axis, the unit axis direction (texture s) and
  // the unit direction of angle 0 (texture t runs along the arc).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX(), axis_v = Eigen::Vector3d::UnitY();
  double radius = 1.0;  // cylinder (seen from outside)
  cv::Mat texture;      // RandomTexture
  double texels_per_metre = 400;

  // The nearest hit along o + t d, t > 0.
  std::optional<Eigen::Vector3d> Intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const;
  // Albedo in [0, 1] at a surface point (bilinear; the texture repeats).
  float Albedo(const Eigen::Vector3d& p) const;
};

// The 3-D point (frame w) seen at pixel uv by a camera at x_w_c with matrix K.
std::optional<Eigen::Vector3d> BackProject(const TexturedSurface& s, const Pose& x_w_c, const Eigen::Matrix3d& K,
                                           const Eigen::Vector2d& uv);

struct RenderOptions {
  bool strobe = true;  // uneven lighting: bright centre, dark corners (x0.25)
  double noise = 2.0;  // Gaussian sensor noise (grey levels)
  int seed = 1;        // noise seed
};

// An 8-bit grey image of the surface from a camera at x_w_c (OpenCV camera
// frame) with matrix K; pixels that miss the surface are black.
cv::Mat RenderSurface(const TexturedSurface& s, const Pose& x_w_c, const Eigen::Matrix3d& K, int width, int height,
                      const RenderOptions& options = {});

}  // namespace hull::testing
