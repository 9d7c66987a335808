// hullinspect-cli sonar --smoother: the batch smoother's results beside the
// filter's (smoother_poses.csv, smoother_features.csv) and its part of
// summary.json.
#pragma once

#include <string>

#include "base/json.h"
#include "sonar/sonar_smoother_run.h"

namespace hull::cli {

// smoother_poses.csv: per step the smoothed pose, its standard deviations and
// the 21 terms of its covariance (the columns of poses.csv) and, with truth,
// the position and rotation errors and the pose NEES.
void WriteSmootherPoses(const SonarSmootherRun& run, const AcousticSequence& seq, const std::string& path);
// smoother_features.csv: per feature (the last step's) the estimate and the 6
// covariance terms (the columns of features.csv, smoothed in place of
// in_state: 0 when held out with the EKF's estimate), the views, the sigma of
// the weakest direction of its views and, with truth, the error.
void WriteSmootherFeatures(const SonarSmootherRun& run, std::int64_t last_step, const std::string& path);
// Options, counts, costs, timing and, with truth, the errors and NEES.
Json SonarSmootherSummary(const SonarSmootherRun& run, const SonarSmootherOptions& options);

}  // namespace hull::cli
