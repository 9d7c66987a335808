// An acoustic sequence run through the sonar EKF (Mai et al.), as the sonar
// dock plays it: the core's per-step records plus what the views draw —
// each feature's first estimate (where it entered the filter), the truth
// when the sequence has it, and 3-sigma ellipsoids of the covariances.
// Computed in a job (RunSonarJob), Qt- and VTK-free.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "base/progress.h"
#include "sonar/sonar_runner.h"
#include "survey/acoustic_sequence.h"

namespace hull::ui {

struct SonarRun {
  std::string name;  // the sequence's name, or the demo preset
  std::shared_ptr<const AcousticSequence> sequence;
  SonarRunResult result;
  // Per feature id seen: its first estimate (the initialisation).
  std::vector<std::int64_t> feature_ids;
  std::vector<Eigen::Vector3d> initial;
  std::vector<std::int64_t> first_step;
  Eigen::AlignedBox3d bounds;  // poses, truth and estimates

  int steps() const { return static_cast<int>(result.steps.size()); }
};

// Runs the EKF over the sequence (every step's features kept).
SonarRun RunSonarJob(std::shared_ptr<const AcousticSequence> sequence, std::string name, SonarInit init,
                     Progress& progress);

// A 3-sigma ellipsoid of a 3x3 covariance: centre, axes as columns (unit)
// and semi-axis lengths (3 sqrt(eigenvalue)).
struct Ellipsoid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d radii = Eigen::Vector3d::Zero();
};
Ellipsoid ThreeSigmaEllipsoid(const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance);

}  // namespace hull::ui
