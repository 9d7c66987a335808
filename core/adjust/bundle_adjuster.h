// Model-assisted bundle adjustment (Ozog, Johnson-Roberson and Eustice,
// Section 2): vehicle poses, servo angles, the top-camera extrinsic, the
// model pose and the landmarks, with odometry, depth/pitch/roll, servo,
// full-pose prior, stereo or monocular reprojection, DVL raycast and surface
// (naive, all-on-surface or Gaussian max-mixture) factors, solved by
// Levenberg-Marquardt with a sparse Schur complement (landmarks eliminated
// first) on all cores.
#pragma once

#include "adjust/adjust_options.h"
#include "adjust/adjust_result.h"
#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "survey/survey.h"

namespace hull {

// mesh: the prior (CAD) mesh in its own frame M; x_gM_initial: the initial
// alignment (also the prior of eq. 8). warm_start (optional): a previous
// result for the same survey whose states start this run (e.g. after a
// change of sigma). Throws OptionError when options fail Check(), InputError
// when the survey cannot be adjusted (no keyframes, no landmarks), and
// hull::Cancelled when progress.Cancelled() became true (the caller keeps
// its last good result).
AdjustmentResult RunAdjustment(const SurveyBundle& bundle, const TriangleMesh& mesh, const Pose& x_gM_initial,
                               const AdjustmentOptions& options, Progress& progress,
                               const AdjustmentResult* warm_start = nullptr);

// The progress estimate of the solve (bundle_adjuster.cc): its share of the
// solve's progress range after `iterations` Levenberg-Marquardt iterations
// counted over every outlier-rejection round. Rises with every iteration, by
// at most 3 % of the range, and stays below 1.
double SolveFraction(int iterations, int max_iterations);

}  // namespace hull
