#include "sonar/sonar_smoother_run.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace hull {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Nees(const Eigen::VectorXd& e, const Eigen::MatrixXd& P) {
  if (!P.allFinite()) return kNaN;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(P);
  if (ldlt.info() != Eigen::Success) return kNaN;
  return e.dot(ldlt.solve(e));
}

}  // namespace

double MeanAlignedError(const std::vector<Eigen::Vector3d>& estimate, const std::vector<Eigen::Vector3d>& truth) {
  const std::size_t n = std::min(estimate.size(), truth.size());
  if (n < 3) return 0;
  Eigen::Matrix3Xd a(3, n), b(3, n);
  for (std::size_t i = 0; i < n; ++i) {
    a.col(static_cast<Eigen::Index>(i)) = estimate[i];
    b.col(static_cast<Eigen::Index>(i)) = truth[i];
  }
  const Eigen::Matrix4d M = Eigen::umeyama(a, b, false);
  const Eigen::Matrix3Xd aligned = (M.topLeftCorner<3, 3>() * a).colwise() + M.topRightCorner<3, 1>();
  return (aligned - b).colwise().norm().mean();
}

SonarSmootherInput SonarSmootherInputFrom(const AcousticSequence& seq, const SonarRunResult& ekf,
                                          const std::vector<SonarMeasurement>& measurements) {
  SonarSmootherInput in;
  in.sensor = seq.sensor;
  in.motion_noise = seq.motion_noise;
  in.initial_pose = seq.initial_pose;
  in.initial_pose_sigma = seq.initial_pose_sigma;
  in.controls = seq.controls;
  in.measurements = measurements;
  for (const SonarStepRecord& s : ekf.steps) in.poses.push_back(s.estimate.pose);
  for (const SonarFeatureEstimate& f : ekf.final_features) {
    in.feature_ids.push_back(f.id);
    in.features.push_back(f.position);
    in.feature_covariances.push_back(f.covariance);
  }
  return in;
}

std::vector<SonarMeasurement> AssociatedMeasurements(const SonarImageRunResult& images) {
  std::vector<SonarMeasurement> out;
  for (std::size_t k = 0; k < images.steps.size(); ++k) {
    const SonarImageStep& s = images.steps[k];
    for (std::size_t j = 0; j < s.detections.size() && j < s.track.feature.size(); ++j) {
      const SonarDetection& d = s.detections[j];
      SonarMeasurement m;
      m.step = s.track.estimate.step;
      m.feature = s.track.feature[j];
      m.range = d.range;
      m.azimuth = d.azimuth;
      m.range_sigma = std::sqrt(d.covariance(0, 0));
      m.azimuth_sigma = std::sqrt(d.covariance(1, 1));
      out.push_back(m);
    }
  }
  return out;
}

SonarSmootherRun RunSonarSmoother(const AcousticSequence& seq, const SonarRunResult& ekf,
                                  const std::vector<SonarMeasurement>& measurements,
                                  const SonarSmootherOptions& options,
                                  const std::map<std::int64_t, std::int64_t>* truth_of, Progress* progress) {
  SonarSmootherRun run;
  run.result = SmoothSonar(SonarSmootherInputFrom(seq, ekf, measurements), options, progress);
  const SonarSmootherResult& r = run.result;
  std::unordered_map<std::int64_t, Eigen::Vector3d> truth_features;
  if (seq.truth) {
    for (std::size_t i = 0; i < seq.truth->feature_ids.size(); ++i) {
      truth_features[seq.truth->feature_ids[i]] = seq.truth->features[i];
    }
  }
  std::vector<const Eigen::Vector3d*> truth(r.features.size(), nullptr);
  run.feature_errors.assign(r.features.size(), kNaN);
  for (std::size_t i = 0; i < r.features.size(); ++i) {
    std::int64_t id = r.features[i].id;
    if (truth_of) {
      auto t = truth_of->find(id);
      id = t == truth_of->end() ? -1 : t->second;
    }
    auto it = truth_features.find(id);
    if (it == truth_features.end()) continue;
    truth[i] = &it->second;
    run.feature_errors[i] = (r.features[i].position - it->second).norm();
  }
  const int T = static_cast<int>(r.poses.size());
  if (!seq.truth || static_cast<int>(seq.truth->poses.size()) != T) return run;

  SonarSmootherErrors e;
  for (int k = 0; k < T; ++k) {
    const Vector6d& xt = seq.truth->poses[static_cast<std::size_t>(k)];
    const Pose est = Pose::FromVector(r.poses[static_cast<std::size_t>(k)]), tru = Pose::FromVector(xt);
    run.pose_position_errors.push_back(Pose::DistanceBetween(est, tru));
    run.pose_rotation_errors.push_back(Pose::AngleBetween(est, tru));
    run.pose_nees.push_back(Nees(PoseVectorDifference(r.poses[static_cast<std::size_t>(k)], xt),
                                 r.pose_covariances[static_cast<std::size_t>(k)]));
    e.mean_position += run.pose_position_errors.back() / T;
    e.mean_pose_nees += run.pose_nees.back() / T;
    if (k == T - 1) {
      e.position = run.pose_position_errors.back();
      e.rotation = Pose::AngleBetween(est, tru);
      e.pose_nees = run.pose_nees.back();
    }
  }
  // Smoothed points with truth; the joint covariance lists the smoothed points in order.
  const Vector6d ep = PoseVectorDifference(r.poses.back(), seq.truth->poses.back());
  std::vector<int> rows;
  std::vector<Eigen::Vector3d> err, est, tru;
  int slot = 0;
  for (std::size_t i = 0; i < r.features.size(); ++i) {
    if (!r.features[i].smoothed) continue;
    const int offset = 6 + 3 * slot++;
    if (!truth[i]) continue;
    err.push_back(r.features[i].position - *truth[i]);
    est.push_back(r.features[i].position);
    tru.push_back(*truth[i]);
    e.predicted_error += std::sqrt(r.features[i].covariance.trace());
    rows.push_back(offset);
    e.mean_feature_error += err.back().norm();
    e.max_feature_error = std::max(e.max_feature_error, err.back().norm());
    e.mean_point_nees += Nees(err.back(), r.features[i].covariance);
  }
  e.features = static_cast<int>(err.size());
  if (e.features > 0) {
    e.mean_feature_error /= e.features;
    e.mean_point_nees /= e.features;
    e.predicted_error /= e.features;
  }
  e.shape_error = MeanAlignedError(est, tru);
  e.feature_nees_dof = 3 * e.features;
  e.joint_nees_dof = 6 + 3 * e.features;
  e.feature_nees = e.joint_nees = kNaN;
  if (r.joint_covariance.size() > 0) {
    const int n = 3 * e.features;
    std::vector<int> idx = {0, 1, 2, 3, 4, 5};
    for (int o : rows) {
      for (int a = 0; a < 3; ++a) idx.push_back(o + a);
    }
    Eigen::MatrixXd J(6 + n, 6 + n);
    for (int i = 0; i < 6 + n; ++i) {
      for (int j = 0; j < 6 + n; ++j) {
        J(i, j) = r.joint_covariance(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
      }
    }
    Eigen::VectorXd ej(6 + n);
    ej.head<6>() = ep;
    for (int f = 0; f < e.features; ++f) ej.segment<3>(6 + 3 * f) = err[static_cast<std::size_t>(f)];
    if (n > 0) e.feature_nees = Nees(ej.tail(n), J.bottomRightCorner(n, n));
    e.joint_nees = Nees(ej, J);
  }
  run.errors = e;
  return run;
}

}  // namespace hull
