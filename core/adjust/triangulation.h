// Initial landmark positions from the initial poses (the contract: "without
// landmarks.csv the application triangulates landmarks from the initial
// poses"): linear multi-ray triangulation with outlier rejection, falling
// back to the first ray's intersection with the prior mesh when the rays are
// too close to parallel (a monocular landmark seen from one spot).
#pragma once

#include <optional>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/pose.h"

namespace hull {

struct ViewRay {
  Eigen::Vector3d origin;  // camera centre in g
  Eigen::Vector3d dir;     // unit direction in g
  // For reprojection checks: camera pose (g <- c) and pixel and focal length.
  Pose g_c;
  Eigen::Vector2d pixel;
  double fx = 1, fy = 1, cx = 0, cy = 0;
};

struct TriangulationOptions {
  double min_parallax_deg = 1.5;    // below: not triangulable from rays alone
  double max_reprojection_px = 25;  // rays worse than this are dropped (wrong matches)
  double min_depth = 0.1;           // m in front of every kept camera
};

struct Triangulated {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::vector<int> inliers;  // indices into the rays
  bool from_mesh = false;    // placed on the prior mesh instead of triangulated
};

// mesh and x_gM may be null / ignored when no fallback is wanted.
std::optional<Triangulated> TriangulateLandmark(const std::vector<ViewRay>& rays, const TriangulationOptions& options,
                                                const MeshIndex* mesh, const Pose& x_gM);

}  // namespace hull
