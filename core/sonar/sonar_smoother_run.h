// The batch smoother (sonar_smoother.h) after a run of the EKF over a
// sequence: its input from the sequence and the EKF's result, and, when the
// sequence has truth, its errors and NEES, measured as the runner measures
// the filter's (sonar_runner.h) so the two compare directly.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "sonar/sonar_image_runner.h"
#include "sonar/sonar_runner.h"
#include "sonar/sonar_smoother.h"

namespace hull {

// The smoother's input: the sequence's sensor, noise, initial pose and
// controls, the given measurements, the EKF's pose at every step and its
// final features (in the state or waiting) as the starting point.
SonarSmootherInput SonarSmootherInputFrom(const AcousticSequence& seq, const SonarRunResult& ekf,
                                          const std::vector<SonarMeasurement>& measurements);
// The measurements of an image run: every detection with the feature it
// measured or started, its range, azimuth and sigmas (the detection's own).
std::vector<SonarMeasurement> AssociatedMeasurements(const SonarImageRunResult& images);

// Against the truth, the smoother's estimate (final: the last pose).
struct SonarSmootherErrors {
  double position = 0;            // last pose: |c - c_true| (m)
  double rotation = 0;            // last pose: rotation error (rad)
  double mean_position = 0;       // over all poses (m)
  double pose_nees = 0;           // last pose, 6 dof
  double mean_pose_nees = 0;      // over all poses, 6 dof each
  int features = 0;               // smoothed features with truth
  double mean_feature_error = 0;  // over those (m)
  double max_feature_error = 0;
  double shape_error = 0;      // over those, after the best rigid alignment to the truth (m; 0 below 3 points)
  double predicted_error = 0;  // over those, sqrt(trace) of each point's covariance (m)
  double mean_point_nees = 0;  // mean over those of each point's own NEES (3 dof)
  double feature_nees = 0;     // joint over those points (3 per point), NaN without the joint covariance
  int feature_nees_dof = 0;
  double joint_nees = 0;  // the last pose and those points, NaN without the joint covariance
  int joint_nees_dof = 0;
};

struct SonarSmootherRun {
  SonarSmootherResult result;
  std::vector<double> feature_errors;         // parallel to result.features (NaN without truth for it)
  std::vector<double> pose_position_errors;   // per step, with truth
  std::vector<double> pose_rotation_errors;   // per step, with truth (rad)
  std::vector<double> pose_nees;              // per step, with truth
  std::optional<SonarSmootherErrors> errors;  // when the sequence has truth
};

// The mean distance between estimated points and their truth after the
// rigid motion that best aligns them (Umeyama, no scale): the error of the
// shape, without that of the map's frame. 0 for fewer than 3 points.
double MeanAlignedError(const std::vector<Eigen::Vector3d>& estimate, const std::vector<Eigen::Vector3d>& truth);

// Smooths and, with truth, scores. truth_of maps a feature to the true
// feature it stands for (an image run's; nullptr: the same id). Throws as
// SmoothSonar.
SonarSmootherRun RunSonarSmoother(const AcousticSequence& seq, const SonarRunResult& ekf,
                                  const std::vector<SonarMeasurement>& measurements,
                                  const SonarSmootherOptions& options = {},
                                  const std::map<std::int64_t, std::int64_t>* truth_of = nullptr,
                                  Progress* progress = nullptr);

}  // namespace hull
