#include "sonar/sonar_runner.h"

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "base/error.h"

namespace hull {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Nees(const Eigen::VectorXd& e, const Eigen::MatrixXd& P) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(P);
  if (ldlt.info() != Eigen::Success) return kNaN;
  return e.dot(ldlt.solve(e));
}

}  // namespace

bool SonarRunOptions::Check(std::string* why) const {
  if (!ekf.Check(why)) return false;
  if (max_joint_nees_features < 0) {
    if (why) *why = "max_joint_nees_features: must not be negative";
    return false;
  }
  return true;
}

std::vector<std::vector<SonarMeasurement>> MeasurementsByStep(const AcousticSequence& seq) {
  std::vector<std::vector<SonarMeasurement>> by_step(static_cast<std::size_t>(seq.num_steps()));
  for (const SonarMeasurement& m : seq.measurements) {
    if (m.step < 0 || m.step >= seq.num_steps()) {
      throw std::invalid_argument("MeasurementsByStep: measurement at step " + std::to_string(m.step) +
                                  " outside the sequence");
    }
    by_step[static_cast<std::size_t>(m.step)].push_back(m);
  }
  return by_step;
}

namespace {

class MeasurementSource final : public SonarStepSource {
 public:
  explicit MeasurementSource(const AcousticSequence& seq) : by_step_(MeasurementsByStep(seq)) {}
  SonarStepEstimate Step(SonarEkf& ekf, const SonarControl* control, int k) override {
    return ekf.Step(control, by_step_[static_cast<std::size_t>(k)]);
  }

 private:
  std::vector<std::vector<SonarMeasurement>> by_step_;
};

}  // namespace

SonarRunResult RunSonarSequence(const AcousticSequence& seq, const SonarRunOptions& options, Progress* progress) {
  MeasurementSource source(seq);
  return RunSonarSequence(seq, options, source, progress);
}

SonarRunResult RunSonarSequence(const AcousticSequence& seq, const SonarRunOptions& options, SonarStepSource& source,
                                Progress* progress) {
  std::string why;
  if (!options.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  const int T = seq.num_steps();
  const bool truth_poses = seq.truth && static_cast<int>(seq.truth->poses.size()) == T;
  std::unordered_map<std::int64_t, Eigen::Vector3d> truth_features;
  if (seq.truth) {
    for (std::size_t i = 0; i < seq.truth->feature_ids.size(); ++i) {
      truth_features[seq.truth->feature_ids[i]] = seq.truth->features[i];
    }
  }
  SonarRunResult result;
  result.options = options.ekf;
  result.has_truth = truth_poses;
  SonarEkf ekf(seq, options.ekf);
  Vector6d dr = seq.initial_pose;
  const auto feature_errors = [&](const std::vector<SonarFeatureEstimate>& fs) {
    std::vector<double> e;
    for (const SonarFeatureEstimate& f : fs) {
      auto it = truth_features.find(source.TruthId(f.id));
      e.push_back(it == truth_features.end() ? kNaN : (f.position - it->second).norm());
    }
    return e;
  };
  for (int k = 0; k < T; ++k) {
    if (progress) {
      progress->ThrowIfCancelled();
      if (k % 16 == 0) progress->Update(static_cast<double>(k) / T, "sonar EKF step " + std::to_string(k));
    }
    const SonarControl* control = k > 0 ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr;
    if (control) dr = OplusEuler<double>(dr, control->u);
    const auto t0 = std::chrono::steady_clock::now();
    SonarStepRecord rec;
    rec.estimate = source.Step(ekf, control, k);
    result.filter_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rec.dead_reckoning = dr;
    const bool last = k == T - 1;
    std::vector<SonarFeatureEstimate> features;
    if (options.keep_features || last || truth_poses) features = ekf.Features();
    if (truth_poses) {
      const Vector6d& xt = seq.truth->poses[static_cast<std::size_t>(k)];
      SonarStepErrors e;
      const Pose est = Pose::FromVector(rec.estimate.pose), tru = Pose::FromVector(xt);
      e.position = Pose::DistanceBetween(est, tru);
      e.rotation = Pose::AngleBetween(est, tru);
      e.dr_position = Pose::DistanceBetween(Pose::FromVector(dr), tru);
      e.dr_rotation = Pose::AngleBetween(Pose::FromVector(dr), tru);
      const Vector6d ep = PoseVectorDifference(rec.estimate.pose, xt);
      e.pose_nees = Nees(ep, rec.estimate.pose_covariance);
      // In-state features with truth: errors and joint NEES from the state's covariance.
      std::vector<int> offsets;
      std::vector<Eigen::Vector3d> err;
      for (const SonarFeatureEstimate& f : features) {
        auto it = truth_features.find(source.TruthId(f.id));
        if (!f.in_state || it == truth_features.end()) continue;
        offsets.push_back(ekf.FeatureOffset(f.id));
        err.push_back(f.position - it->second);
        e.mean_feature_error += err.back().norm();
        e.max_feature_error = std::max(e.max_feature_error, err.back().norm());
      }
      e.features = static_cast<int>(offsets.size());
      if (e.features > 0) e.mean_feature_error /= e.features;
      e.feature_nees = kNaN;
      e.feature_nees_dof = 3 * e.features;
      e.joint_nees = e.features == 0 ? e.pose_nees : kNaN;
      e.joint_nees_dof = 6 + 3 * e.features;
      if (e.features > 0 && e.features <= options.max_joint_nees_features) {
        const int n = 3 * e.features;
        const Eigen::MatrixXd& P = ekf.covariance();
        Eigen::MatrixXd J(6 + n, 6 + n);
        Eigen::VectorXd ej(6 + n);
        std::vector<int> idx = {0, 1, 2, 3, 4, 5};
        for (int o : offsets) {
          for (int a = 0; a < 3; ++a) idx.push_back(o + a);
        }
        for (int i = 0; i < 6 + n; ++i) {
          for (int j = 0; j < 6 + n; ++j)
            J(i, j) = P(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
        }
        ej.head<6>() = ep;
        for (int f = 0; f < e.features; ++f) ej.segment<3>(6 + 3 * f) = err[static_cast<std::size_t>(f)];
        e.feature_nees = Nees(ej.tail(n), J.bottomRightCorner(n, n));
        e.joint_nees = Nees(ej, J);
      }
      rec.errors = e;
    }
    if (options.keep_features) {
      rec.feature_errors = feature_errors(features);
      rec.features = features;
    }
    if (last) {
      result.final_feature_errors = feature_errors(features);
      result.final_features = std::move(features);
    }
    result.steps.push_back(std::move(rec));
  }
  if (progress) progress->Update(1.0, "sonar EKF done");
  return result;
}

}  // namespace hull
