// Runs the sonar EKF over an acoustic sequence read from files (or
// simulated): per-step pose and feature estimates with covariances, dead
// reckoning for comparison and, when the sequence carries truth, the errors
// and the normalised estimation error squared (NEES) at every step.
#pragma once

#include <optional>
#include <vector>

#include "base/progress.h"
#include "sonar/sonar_ekf.h"
#include "survey/acoustic_sequence.h"

namespace hull {

struct SonarRunOptions {
  SonarEkfOptions ekf;
  // Keep every feature's estimate at every step (the CLI's per-step output);
  // false keeps only the final ones.
  bool keep_features = true;
  // The joint feature NEES needs a factorisation of the features' covariance
  // block: skipped (NaN) above this many features in the state.
  int max_joint_nees_features = 400;

  bool Check(std::string* why = nullptr) const;
};

// Errors against the sequence's truth after one step.
struct SonarStepErrors {
  double position = 0;     // |c - c_true| (m)
  double rotation = 0;     // angle between the estimated and true orientation (rad)
  double dr_position = 0;  // the same for dead reckoning (controls only)
  double dr_rotation = 0;
  double pose_nees = 0;           // 6 degrees of freedom
  int features = 0;               // in-state features with truth
  double mean_feature_error = 0;  // over those (m)
  double max_feature_error = 0;
  double feature_nees = 0;  // joint over those features (3 per feature), NaN when skipped
  int feature_nees_dof = 0;
  double joint_nees = 0;  // pose and those features (the pose alone without features), NaN when skipped
  int joint_nees_dof = 0;
};

struct SonarStepRecord {
  SonarStepEstimate estimate;
  Vector6d dead_reckoning = Vector6d::Zero();  // initial pose (+) controls
  // Every feature seen so far (when keep_features), by id, and its error
  // against the truth (NaN without truth for it).
  std::vector<SonarFeatureEstimate> features;
  std::vector<double> feature_errors;
  std::optional<SonarStepErrors> errors;  // when the sequence has truth
};

struct SonarRunResult {
  SonarEkfOptions options;
  std::vector<SonarStepRecord> steps;
  std::vector<SonarFeatureEstimate> final_features;
  std::vector<double> final_feature_errors;  // parallel to final_features (NaN without truth)
  bool has_truth = false;
  double filter_seconds = 0;  // time spent in SonarEkf::Step
};

// What feeds the filter at each step: the sequence's measurements (given
// correspondences) by default, or e.g. features found in its images.
class SonarStepSource {
 public:
  virtual ~SonarStepSource() = default;
  // Runs step k on the filter (control: nullptr at k = 0) and returns its estimate.
  virtual SonarStepEstimate Step(SonarEkf& ekf, const SonarControl* control, int k) = 0;
  // The truth feature a filter feature stands for (-1: none); with given
  // correspondences the feature itself.
  virtual std::int64_t TruthId(std::int64_t feature) const { return feature; }
};

// Throws OptionError when options.Check() fails and hull::Cancelled when the
// progress asks to stop.
SonarRunResult RunSonarSequence(const AcousticSequence& seq, const SonarRunOptions& options = {},
                                Progress* progress = nullptr);
// The same with another source of measurements.
SonarRunResult RunSonarSequence(const AcousticSequence& seq, const SonarRunOptions& options, SonarStepSource& source,
                                Progress* progress = nullptr);

// Splits a sequence's measurements by step (index = step).
std::vector<std::vector<SonarMeasurement>> MeasurementsByStep(const AcousticSequence& seq);

}  // namespace hull
