// The pipeline's results as the Session holds them: an adjustment run (the
// core's AdjustmentResult with its evaluation against truth and what the
// views draw of it) and a mapping run (the core's MappingResult with the
// outlines of its objects and the centres of its zones), both computed in
// their jobs, off the GUI thread. Qt-free.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "adjust/evaluation.h"
#include "mapping/mapping_input.h"
#include "mapping/mapping_result.h"
#include "survey/survey.h"
#include "ui/session/survey_overlays.h"

namespace hull::ui {

struct AdjustedLandmark {
  std::int64_t id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // in g
  int label = 1;                                       // lambda: 1 on the hull, 0 foreign
  double deviation = 0;                                // estimated signed distance to the CAD surface (m)
  int observations = 0;
  // From the survey's truth, when it has the landmark.
  bool has_truth = false;
  double true_deviation = 0;
  std::string object;  // the true object it lies on ("" on the hull)
};

// What the views draw of an adjustment, in g.
struct AdjustedOverlays {
  std::vector<std::int64_t> keyframes;      // the adjustment's keyframes, in order
  std::vector<Eigen::Vector3d> trajectory;  // adjusted vehicle positions
  std::vector<DvlHit> dvl_hits;             // from the adjusted poses and servo angles (nav_index: into keyframes)
  std::vector<AdjustedLandmark> landmarks;
  double min_deviation = 0, max_deviation = 0;
  Eigen::AlignedBox3d bounds;
};

AdjustedOverlays ComputeAdjustedOverlays(const SurveyBundle& bundle, const AdjustmentResult& result);

// The DVL returns of one adjustment placed in g (as in ComputeDvlHits, from
// the adjusted poses and servo angles).
std::vector<DvlHit> AdjustedDvlHits(const SurveyBundle& bundle, const AdjustmentResult& result);

struct AdjustmentRun {
  std::string key;  // AdjustmentKey of the parameters it was run with
  std::shared_ptr<const AdjustmentResult> result;
  std::optional<AdjustmentEvaluation> evaluation;  // when the survey has truth
  std::shared_ptr<const AdjustedOverlays> overlays;
  bool warm_started = false;  // from a previous result (a change of sigma)

  SurfaceModel model() const { return result->options.model; }
  Pose x_gM() const { return Pose::FromVector(result->x_gM); }
};

// What the views draw of a mapping result besides the result itself.
struct MappingOverlays {
  // Per detected object (as MappingResult::objects): the outline of its
  // footprint on the fused model (segments in M: the boundary of the faces
  // touching its vertices) and the radius of a sphere about its centroid
  // holding the footprint (m).
  std::vector<std::vector<std::array<Eigen::Vector3d, 2>>> object_outlines;
  std::vector<double> object_radius;
  // Per zone (HullFrame::ZoneIndex): the area-weighted centre of its CAD
  // surface in M, and the radius holding it (NaN centre: no surface).
  std::vector<Eigen::Vector3d> zone_centres;
  std::vector<double> zone_radius;
  double min_deviation = 0, max_deviation = 0;  // over the fused model's vertices
  std::size_t shape_triangles = 0;              // alpha-shape triangles of every keyframe
};

MappingOverlays ComputeMappingOverlays(const MappingResult& result, const TriangleMesh& cad);

struct MappingRun {
  std::string key;  // MappingKey of the parameters it was run with
  std::string adjustment_key;
  std::shared_ptr<const MappingResult> result;
  std::shared_ptr<const MappingInput> input;  // the adjusted survey it mapped
  std::shared_ptr<const MappingOverlays> overlays;

  Pose x_gM() const { return input->x_gM; }
};

}  // namespace hull::ui
