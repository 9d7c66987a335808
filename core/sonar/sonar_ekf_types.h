// The sonar EKF's options and the estimates it reports (see sonar_ekf.h for
// the filter itself).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "geometry/pose.h"

namespace hull {

enum class SonarInit {
  kPaper,       // elevation 0, sigma_phi = elevation_fov / 4 (Mai et al.)
  kHypotheses,  // delayed multi-hypothesis elevation (ours)
};
// "paper" / "hypotheses"; ParseSonarInit throws OptionError on another name.
const char* SonarInitName(SonarInit init);
SonarInit ParseSonarInit(const std::string& name);

struct SonarEkfOptions {
  // How a feature enters the state when first seen.
  SonarInit init = SonarInit::kHypotheses;
  // kPaper: the elevation's initial standard deviation as a fraction of the
  // full elevation field of view (the paper's "fan": 1/4).
  double paper_elevation_sigma_fraction = 0.25;
  // kHypotheses: number of elevation hypotheses tiling the fan (>= 3); each
  // has a standard deviation of half the spacing, elevation_fov / hypotheses.
  int hypotheses = 9;
  // kHypotheses: a feature enters the state once the most probable hypothesis
  // and its two neighbours hold this share of the weight...
  double collapse_probability = 0.99;
  // ... and it has been seen in at least this many views after the first.
  int min_extra_views = 1;
  // kHypotheses: after this many steps since the first view a feature enters
  // with the whole fan as its elevation prior, however vague its weights.
  int max_delay_steps = 8;
  // kHypotheses: hypotheses whose weight falls below this fraction of the
  // best one's are dropped.
  double prune_ratio = 1e-4;
  // A feature enters the state only once it has been measured in this many
  // views; until then it waits (its elevation hypotheses weighed, as with
  // kHypotheses) and then enters from its first view with every view
  // replayed, kPaper at elevation 0. 1 with given correspondences; more when
  // features come from a detector, whose one-off false detections must not
  // enter the state.
  int confirm_views = 1;
  // Joseph-form covariance update (true) or the shorter P - M S^-1 M^T (false).
  bool joseph = true;
  // Measurements (features) per block of the update: the result is the batch
  // update whatever the block (up to rounding); blocks only bound the cost of
  // the innovation solves (O(N m_b^2) each instead of O(N m^2)).
  int update_block = 16;

  // True when every field is usable; otherwise false and, when why is given,
  // the field and the reason.
  bool Check(std::string* why = nullptr) const;
};

// One feature's estimate.
struct SonarFeatureEstimate {
  std::int64_t id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  // False while kHypotheses still weighs its elevation: position and
  // covariance are then the moments of the hypothesis mixture (not in the state).
  bool in_state = true;
  int observations = 0;         // measurements of it so far (the first included)
  std::int64_t first_step = 0;  // when it was first seen
};

// What one Step() did.
struct SonarStepEstimate {
  std::int64_t step = 0;
  Vector6d pose = Vector6d::Zero();
  Matrix6d pose_covariance = Matrix6d::Zero();
  int measurements = 0;  // measurements given at the step
  int updated = 0;       // of which used in the EKF update (in-state features)
  int initialised = 0;   // features that entered the state at the step
  int pending = 0;       // features still waiting for their elevation (kHypotheses)
  double nis = 0;        // normalised innovation squared of the update
  int nis_dof = 0;       // its degrees of freedom (2 per used measurement)
};

}  // namespace hull
