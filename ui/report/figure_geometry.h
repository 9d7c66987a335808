// The geometry the report's figures draw, Qt-free: orthographic views of a
// mesh in hull axes (triangles sorted back to front), the cut of a mesh by a
// plane across the hull, the features and DVL returns of each adjusted model
// inside a slab, and histogram bins. Drawings of results only: nothing here
// estimates anything.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "geometry/triangle_mesh.h"
#include "mapping/hull_zones.h"
#include "survey/survey.h"
#include "ui/report/report_inputs.h"

namespace hull::report {

// The hull axes of a report: mapping's when it ran, else made from the CAD
// and the survey's model_axes as mapping would.
HullFrame ReportHullFrame(const ReportInputs& inputs);

// Where an orthographic view looks from.
enum class HullView {
  kBottom,     // from below, looking up; bow to the right, starboard up
  kPort,       // from the port side; bow to the left, up up
  kStarboard,  // from the starboard side; bow to the right, up up
};
const char* HullViewName(HullView v);  // "bottom", "port", "starboard"

// Screen axes of a view in M: a point p lands at (p.right, p.up); larger
// p.toward_viewer is nearer the viewer.
struct ViewBasis {
  Eigen::Vector3d right, up, toward_viewer;
  Eigen::Vector2d Project(const Eigen::Vector3d& p) const { return {p.dot(right), p.dot(up)}; }
  double Depth(const Eigen::Vector3d& p) const { return p.dot(toward_viewer); }
};
ViewBasis MakeViewBasis(const HullFrame& hull, HullView view);

struct ProjectedTriangle {
  std::array<Eigen::Vector2d, 3> corner;
  double depth = 0;     // of the centroid (larger: nearer)
  double facing = 0;    // cosine between the face normal and the direction to the viewer
  double value = 0;     // mean of the corners' values
  bool valued = false;  // false: no value to colour by (plain CAD)
  int face = -1;        // of the mesh
};

// The mesh as seen in `view`, back to front (painter's algorithm). values:
// per-vertex values or null; valued_mask: per-vertex weights (e.g. mapping's
// "fusions"), a face is valued when every corner's weight is > 0 (null: all
// valued when values are given). Faces whose projection misses `window`
// (when given) are left out.
std::vector<ProjectedTriangle> ProjectMesh(const TriangleMesh& mesh, const ViewBasis& view,
                                           const std::vector<double>* values, const std::vector<double>* valued_mask,
                                           const std::optional<Eigen::AlignedBox2d>& window = std::nullopt);

// Boxes for labels beside anchors (2-D page units, y down): for each anchor
// in order, the nearest free spot right or left of it, above or below,
// stepping outwards by the label's height (a row of touching lumps along
// the keel puts many labels side by side). A spot is free when it lies in
// `bounds`, keeps 2 units from every label placed before it and covers no
// anchor; with none free within eight steps, the spot that overlaps least.
// sizes: each label's width and height.
std::vector<Eigen::AlignedBox2d> PlaceLabels(const Eigen::AlignedBox2d& bounds,
                                             const std::vector<Eigen::Vector2d>& anchors,
                                             const std::vector<Eigen::Vector2d>& sizes);

// The 2-D bounds of a mesh's projection.
Eigen::AlignedBox2d ProjectedBounds(const TriangleMesh& mesh, const ViewBasis& view);

// A landmark of an adjustment placed in M by that adjustment's x_gM.
struct PlacedLandmark {
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  double deviation = 0;
  int label = 1;
};
std::vector<PlacedLandmark> LandmarksInModel(const AdjustmentResult& result);

// The DVL returns of a survey placed by an adjustment (its vehicle poses,
// servo angles and model pose), in M. Keyframes the adjustment lacks keep
// their initial navigation.
std::vector<Eigen::Vector3d> DvlReturnsInModel(const SurveyBundle& bundle, const AdjustmentResult& result);

// ---- cross-section ----------------------------------------------------------

// Section coordinates: x toward port, y up (a section seen looking aft, from
// starboard on the left to port on the right, as in the paper's Fig. 14).
struct Segment2 {
  Eigen::Vector2d a, b;
};
Eigen::Vector2d SectionCoordinates(const HullFrame& hull, const Eigen::Vector3d& p_m);

// The mesh cut by the plane across the hull at from_bow (m from the bow).
std::vector<Segment2> SliceMesh(const TriangleMesh& mesh, const HullFrame& hull, double from_bow);

struct SectionFeature {
  Eigen::Vector2d p;
  double deviation = 0;
  bool off_hull = false;  // labelled off (max-mixture); the baselines: |deviation| beyond its decision boundary
};

struct SectionModel {
  SurfaceModel model = SurfaceModel::kMaxMixture;
  std::vector<SectionFeature> features;  // in the slab
  std::vector<Eigen::Vector2d> dvl;      // in the slab
  std::vector<Segment2> fused;           // the fused model's profile (mapping ran on this model)
};

struct CrossSection {
  double from_bow = 0;  // slab centre (m from the bow)
  double width = 0;     // slab width (m)
  double decision_boundary = 0;
  std::string focus;                                      // what the close-up shows (an object id, or "")
  Eigen::Vector2d focus_point = Eigen::Vector2d::Zero();  // section coordinates of the close-up's centre
  std::vector<Segment2> cad;                              // the prior mesh's profile
  Eigen::AlignedBox2d hull_box;                           // bounds of that profile
  Eigen::AlignedBox2d data_box;                           // bounds of the features and returns in the slab
  std::vector<SectionModel> models;                       // naive, all-on-surface, max-mixture (those that ran)
};

// The slab at options.slab_from_bow (or chosen as ReportOptions says), with
// every model of the pipeline result.
CrossSection BuildCrossSection(const ReportInputs& inputs, const HullFrame& hull, const ReportOptions& options);

// ---- histograms ---------------------------------------------------------------

struct Histogram {
  double lo = 0, hi = 0;
  std::vector<int> counts;
  int below = 0, above = 0;  // outside [lo, hi)
  int total = 0;             // finite values
  int Max() const;
};
Histogram MakeHistogram(const std::vector<double>& values, double lo, double hi, int bins);

// The adjustments of a pipeline result in the paper's order (naive,
// all-on-surface, max-mixture), those that ran.
std::vector<const AdjustmentResult*> ModelsInOrder(const PipelineResult& result);

}  // namespace hull::report
