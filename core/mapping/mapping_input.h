// What model-assisted mapping needs from a survey: the top camera's pose at
// every keyframe, the landmarks each keyframe observed, each landmark's
// position and its deviation from the CAD surface, the model pose and the
// hull axes. Built from an adjustment (the normal case) or, for simulated
// surveys, from the truth (true poses and landmarks with their true
// deviation, as if adjusted perfectly).
//
// "g" here is the survey's local frame, g moved to LocalOrigin(bundle)
// (survey_origin.h), as in the estimators: a survey in UTM-scale
// coordinates is mapped with the same numbers as the same survey near g's
// origin. Nothing the mapping writes is in g (objects, zones and the model
// are in M, shapes per keyframe).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "geometry/pose.h"
#include "survey/survey.h"

namespace hull {

struct MappingLandmark {
  std::int64_t id = 0;
  Eigen::Vector3d p_g = Eigen::Vector3d::Zero();  // position in (the local) g
  double deviation = 0;                           // signed distance to the CAD surface (m, positive outside)
  double sigma_h = std::nan("");                  // its standard deviation from the adjustment (m); NaN: unknown
};

struct MappingKeyframe {
  std::int64_t id = 0;
  Pose x_g_cT;                 // top camera in g: x_gv (+) x_vs(theta) (+) x_s_cT
  std::vector<int> landmarks;  // indices into MappingInput::landmarks it observed, ascending
};

struct MappingInput {
  std::string source;  // where it came from, e.g. "adjustment" or "truth"
  Pose x_gM;           // the CAD model in (the local) g
  CameraRig camera;    // intrinsics and image size of the top camera
  std::optional<ModelAxes> model_axes;
  std::vector<MappingKeyframe> keyframes;  // in the adjustment's (time) order
  std::vector<MappingLandmark> landmarks;
};

// From an adjustment of `bundle`: adjusted poses, servo angles, camera
// extrinsic, model pose and landmarks (with the deviation the adjustment
// computed); observations from the bundle's features.csv. Observations of
// landmarks or keyframes the adjustment left out are skipped. Throws
// InputError when the result and the bundle do not belong together (a
// keyframe of the result is not in the bundle).
MappingInput MappingInputFromAdjustment(const AdjustmentResult& result, const SurveyBundle& bundle);

// From a simulated bundle's truth/: true poses, servo angles, extrinsic and
// model pose, true landmark positions and deviations. Throws InputError
// when the bundle has no truth.
MappingInput MappingInputFromTruth(const SurveyBundle& bundle);

}  // namespace hull
