// Cross-sections of the hull for the profile view (the paper's Figs. 14 and
// 15): a slab across or along the hull, in the model frame M, and what lies
// in it — the mesh cut by the slab's mid-plane, the DVL returns and the
// features of an adjustment — as 2-D points of the plane. Qt- and VTK-free.
//
// The slab's frame follows the hull's axes (the survey's model_axes; M's x
// forward and z up without them). The plane is seen looking along its
// normal, v (the hull's up) up and u = normal x v to the right: a transverse
// slab's normal is the forward axis (seen from astern, starboard to the
// right), a longitudinal slab's normal points to port (seen from starboard,
// bow to the right).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "survey/survey.h"
#include "ui/session/inspection_results.h"

namespace hull::ui {

enum class SlabDirection { kTransverse, kLongitudinal };

struct SlabSpec {
  SlabDirection direction = SlabDirection::kTransverse;
  double position = 0;  // m: the mid-plane's offset along the normal from M's origin
  double width = 0.3;   // m: the slab's thickness
  bool operator==(const SlabSpec& o) const {
    return direction == o.direction && position == o.position && width == o.width;
  }
  bool operator!=(const SlabSpec& o) const { return !(*this == o); }
};

// The slab's axes in M (unit; u = normal x v).
struct SlabFrame {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  Eigen::Vector3d u = Eigen::Vector3d::UnitY();
  Eigen::Vector3d v = Eigen::Vector3d::UnitZ();
  double position = 0;
  double half_width = 0.15;

  // Signed distance of a point of M from the mid-plane, and its (u, v).
  double Offset(const Eigen::Vector3d& p_M) const { return normal.dot(p_M) - position; }
  Eigen::Vector2d Project(const Eigen::Vector3d& p_M) const { return {u.dot(p_M), v.dot(p_M)}; }
  bool Contains(const Eigen::Vector3d& p_M) const { return std::abs(Offset(p_M)) <= half_width; }
};

SlabFrame MakeSlabFrame(const std::optional<ModelAxes>& axes, const SlabSpec& spec);

// The range of positions worth offering for a direction: the extent of the
// points (in M) along the normal; [0, 0] without points.
std::pair<double, double> SlabRange(const std::optional<ModelAxes>& axes, SlabDirection direction,
                                    const std::vector<Eigen::Vector3d>& points_M);

struct ProfileSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
};

// The mesh (in M) cut by the slab's mid-plane: one segment per triangle the
// plane crosses.
std::vector<ProfileSegment> MeshSection(const TriangleMesh& mesh_M, const SlabFrame& frame);

struct ProfilePoint {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  int label = 1;         // features: lambda (1 on the hull)
  double deviation = 0;  // features: estimated deviation (m)
  std::int64_t id = 0;   // features: landmark id; DVL: keyframe
};

// What one adjustment puts in the slab, in M (placed by its own x_gM, so the
// three models' profiles share the CAD section).
struct ModelProfile {
  SurfaceModel model = SurfaceModel::kMaxMixture;
  std::vector<ProfilePoint> features;
  std::vector<ProfilePoint> dvl;
};
ModelProfile ComputeModelProfile(const AdjustmentRun& run, const SlabFrame& frame);

// The slab as a box in g for the 3-D view: centre, axes (columns normal, u,
// v) and half extents along them; `extent` bounds the box in the plane
// (u and v ranges in M).
struct SlabBox {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half_extents = Eigen::Vector3d::Ones();
};
SlabBox MakeSlabBox(const SlabFrame& frame, const Eigen::AlignedBox2d& extent, const Pose& x_gM);

}  // namespace hull::ui
