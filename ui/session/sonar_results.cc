#include "ui/session/sonar_results.h"

#include <Eigen/Eigenvalues>
#include <map>
#include <utility>

namespace hull::ui {

SonarRun RunSonarJob(std::shared_ptr<const AcousticSequence> sequence, std::string name, SonarInit init,
                     Progress& progress) {
  SonarRun run;
  run.name = std::move(name);
  SonarRunOptions options;
  options.ekf.init = init;
  options.keep_features = true;
  run.result = RunSonarSequence(*sequence, options, &progress);
  std::map<std::int64_t, std::pair<Eigen::Vector3d, std::int64_t>> first;
  for (const SonarStepRecord& step : run.result.steps) {
    run.bounds.extend(step.estimate.pose.head<3>());
    run.bounds.extend(step.dead_reckoning.head<3>());
    for (const SonarFeatureEstimate& f : step.features) {
      run.bounds.extend(f.position);
      if (!first.count(f.id)) first[f.id] = {f.position, step.estimate.step};
    }
  }
  for (const auto& [id, value] : first) {
    run.feature_ids.push_back(id);
    run.initial.push_back(value.first);
    run.first_step.push_back(value.second);
  }
  if (sequence->truth) {
    for (const Vector6d& p : sequence->truth->poses) run.bounds.extend(p.head<3>());
    for (const Eigen::Vector3d& p : sequence->truth->features) run.bounds.extend(p);
  }
  run.sequence = std::move(sequence);
  return run;
}

Ellipsoid ThreeSigmaEllipsoid(const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance) {
  Ellipsoid e;
  e.centre = mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 * (covariance + covariance.transpose()));
  e.axes = solver.eigenvectors();
  for (int i = 0; i < 3; ++i) e.radii[i] = 3.0 * std::sqrt(std::max(0.0, solver.eigenvalues()[i]));
  return e;
}

}  // namespace hull::ui
