#include "sonar/sonar_smoother.h"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "base/error.h"
#include "sonar/acoustic_camera.h"

namespace hull {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <typename T>
T WrapAngle(const T& a) {
  using std::atan2;
  using std::cos;
  using std::sin;
  return atan2(sin(a), cos(a));
}

double WrapAngleValue(double a) { return std::atan2(std::sin(a), std::cos(a)); }

// Range and azimuth of one measurement, normalised by its sigmas; Jacobians
// in closed form from the acoustic camera's (SonarMeasureJacobians).
class MeasurementFactor final : public ceres::SizedCostFunction<2, 6, 3> {
 public:
  MeasurementFactor(double range, double azimuth, const Eigen::Vector2d& sigma)
      : range_(range), azimuth_(azimuth), sigma_(sigma) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Vector6d> pose(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> point(parameters[1]);
    Eigen::Matrix<double, 2, 6> Jx;
    Eigen::Matrix<double, 2, 3> Jp;
    const bool want = jacobians && (jacobians[0] || jacobians[1]);
    const Eigen::Vector2d r =
        SonarMeasurementResidual(pose, point, range_, azimuth_, sigma_, want ? &Jx : nullptr, want ? &Jp : nullptr);
    if (!r.allFinite()) return false;
    residuals[0] = r[0];
    residuals[1] = r[1];
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> J(jacobians[0]);
      J = Jx;
    }
    if (jacobians && jacobians[1]) {
      Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> J(jacobians[1]);
      J = Jp;
    }
    return true;
  }

 private:
  double range_, azimuth_;
  Eigen::Vector2d sigma_;
};

// (-)a (+) b against the control, angles wrapped, per component over its sigma.
struct MotionFactor {
  MotionFactor(const Vector6d& u, const Vector6d& sigma) : u_(u), sigma_(sigma) {}
  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    const Eigen::Matrix<T, 6, 1> xa = Eigen::Map<const Eigen::Matrix<T, 6, 1>>(a);
    const Eigen::Matrix<T, 6, 1> xb = Eigen::Map<const Eigen::Matrix<T, 6, 1>>(b);
    const Eigen::Matrix<T, 6, 1> rel = OplusEuler<T>(OminusEuler<T>(xa), xb);
    for (int i = 0; i < 6; ++i) {
      const T d = rel[i] - T(u_[i]);
      residual[i] = (i < 3 ? d : WrapAngle(d)) / T(sigma_[i]);
    }
    return true;
  }
  Vector6d u_, sigma_;
};

// The first pose against the sequence's initial pose.
struct PosePrior {
  PosePrior(const Vector6d& mean, const Vector6d& sigma) : mean_(mean), sigma_(sigma) {}
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int i = 0; i < 6; ++i) {
      const T d = x[i] - T(mean_[i]);
      residual[i] = (i < 3 ? d : WrapAngle(d)) / T(sigma_[i]);
    }
    return true;
  }
  Vector6d mean_, sigma_;
};

class Observer final : public ceres::IterationCallback {
 public:
  Observer(Progress& progress, int max_iterations) : progress_(progress), max_(max_iterations) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    char msg[96];
    std::snprintf(msg, sizeof(msg), "sonar smoother: iteration %d, cost %.6g", it.iteration, it.cost);
    progress_.Update(0.05 + 0.75 * std::min(1.0, static_cast<double>(it.iteration) / max_), msg);
    return progress_.Cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  Progress& progress_;
  int max_;
};

Eigen::Vector2d SigmaOf(const SonarSensor& sensor, const SonarMeasurement& m) {
  return {m.range_sigma > 0 ? m.range_sigma : sensor.range_sigma,
          m.azimuth_sigma > 0 ? m.azimuth_sigma : sensor.azimuth_sigma};
}

void CheckInput(const SonarSmootherInput& in) {
  const std::size_t T = in.poses.size();
  if (T == 0) throw std::invalid_argument("SmoothSonar: no poses");
  if (in.controls.size() + 1 != T) {
    throw std::invalid_argument("SmoothSonar: " + std::to_string(in.controls.size()) + " controls for " +
                                std::to_string(T) + " poses");
  }
  for (std::size_t k = 0; k < in.controls.size(); ++k) {
    if (in.controls[k].step != static_cast<std::int64_t>(k + 1)) {
      throw std::invalid_argument("SmoothSonar: control " + std::to_string(k) + " is of step " +
                                  std::to_string(in.controls[k].step) + ", expected " + std::to_string(k + 1));
    }
  }
  if (in.features.size() != in.feature_ids.size() ||
      (!in.feature_covariances.empty() && in.feature_covariances.size() != in.feature_ids.size())) {
    throw std::invalid_argument("SmoothSonar: feature ids, positions and covariances differ in number");
  }
  for (const SonarMeasurement& m : in.measurements) {
    if (m.step < 0 || m.step >= static_cast<std::int64_t>(T)) {
      throw std::invalid_argument("SmoothSonar: measurement at step " + std::to_string(m.step) + " outside 0.." +
                                  std::to_string(T - 1));
    }
  }
  if ((in.initial_pose_sigma.array() <= 0).any()) {
    throw std::invalid_argument("SmoothSonar: initial pose sigmas must be positive");
  }
}

}  // namespace

bool SonarSmootherOptions::Check(std::string* why) const {
  const auto fail = [&](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (max_iterations < 1) return fail("max_iterations: must be at least 1");
  if (!(function_tolerance > 0)) return fail("function_tolerance: must be positive");
  if (min_views < 2) return fail("min_views: must be at least 2 (one view leaves the elevation free)");
  if (!(max_weak_sigma_fraction > 0)) return fail("max_weak_sigma_fraction: must be positive");
  if (max_joint_features < 0) return fail("max_joint_features: must not be negative");
  if (threads < 1) return fail("threads: must be at least 1");
  return true;
}

Eigen::Vector2d SonarMeasurementResidual(const Vector6d& pose, const Eigen::Vector3d& point, double range,
                                         double azimuth, const Eigen::Vector2d& sigma,
                                         Eigen::Matrix<double, 2, 6>* J_pose, Eigen::Matrix<double, 2, 3>* J_point) {
  const Eigen::Vector2d h = SonarMeasureJacobians(pose, point, J_pose, J_point);
  const Eigen::Vector2d w = sigma.cwiseInverse();
  if (J_pose) *J_pose = w.asDiagonal() * *J_pose;
  if (J_point) *J_point = w.asDiagonal() * *J_point;
  return {(h[0] - range) * w[0], WrapAngleValue(h[1] - azimuth) * w[1]};
}

Vector6d SonarMotionResidual(const Vector6d& a, const Vector6d& b, const Vector6d& u, const Vector6d& sigma) {
  Vector6d r;
  MotionFactor(u, sigma)(a.data(), b.data(), r.data());
  return r;
}

SonarSmootherResult SmoothSonar(const SonarSmootherInput& in, const SonarSmootherOptions& options, Progress* progress) {
  std::string why;
  if (!options.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  CheckInput(in);
  const int T = static_cast<int>(in.poses.size());
  const std::size_t n = in.feature_ids.size();
  SonarSmootherResult result;
  result.poses = in.poses;
  result.pose_covariances.assign(static_cast<std::size_t>(T), Matrix6d::Constant(kNaN));
  result.features.resize(n);
  std::unordered_map<std::int64_t, std::size_t> index;
  for (std::size_t i = 0; i < n; ++i) {
    if (!index.emplace(in.feature_ids[i], i).second) {
      throw std::invalid_argument("SmoothSonar: feature " + std::to_string(in.feature_ids[i]) + " given twice");
    }
    SonarSmoothedFeature& f = result.features[i];
    f.id = in.feature_ids[i];
    f.position = in.features[i];
    f.covariance = in.feature_covariances.empty() ? Eigen::Matrix3d::Constant(kNaN) : in.feature_covariances[i];
  }

  // Which points the views determine (poses at the start).
  std::vector<Eigen::Matrix3d> info(n, Eigen::Matrix3d::Zero());
  std::vector<double> range_sum(n, 0.0);
  std::vector<const SonarMeasurement*> used;
  for (const SonarMeasurement& m : in.measurements) {
    auto it = index.find(m.feature);
    if (it == index.end()) continue;  // a feature not estimated (e.g. dropped by the tracker)
    Eigen::Matrix<double, 2, 3> Jp;
    SonarMeasurementResidual(in.poses[static_cast<std::size_t>(m.step)], in.features[it->second], m.range, m.azimuth,
                             SigmaOf(in.sensor, m), nullptr, &Jp);
    info[it->second] += Jp.transpose() * Jp;
    range_sum[it->second] += m.range;
    ++result.features[it->second].views;
    used.push_back(&m);
  }
  for (std::size_t i = 0; i < n; ++i) {
    SonarSmoothedFeature& f = result.features[i];
    const double lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(info[i], Eigen::EigenvaluesOnly).eigenvalues()[0];
    f.weak_sigma = lambda > 0 ? 1 / std::sqrt(lambda) : std::numeric_limits<double>::infinity();
    const double half_fan = f.views > 0 ? range_sum[i] / f.views * in.sensor.elevation_fov / 2 : 0.0;
    f.smoothed = f.views >= options.min_views && f.weak_sigma <= options.max_weak_sigma_fraction * half_fan;
  }

  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (int k = 0; k < T; ++k) problem.AddParameterBlock(result.poses[static_cast<std::size_t>(k)].data(), 6);
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<PosePrior, 6, 6>(new PosePrior(in.initial_pose, in.initial_pose_sigma)), nullptr,
      result.poses[0].data());
  for (int k = 1; k < T; ++k) {
    const Vector6d& u = in.controls[static_cast<std::size_t>(k - 1)].u;
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<MotionFactor, 6, 6, 6>(new MotionFactor(u, ControlSigma(in.motion_noise, u))),
        nullptr, result.poses[static_cast<std::size_t>(k - 1)].data(),
        result.poses[static_cast<std::size_t>(k)].data());
  }
  for (const SonarMeasurement* m : used) {
    SonarSmoothedFeature& f = result.features[index.at(m->feature)];
    if (!f.smoothed) continue;
    problem.AddResidualBlock(new MeasurementFactor(m->range, m->azimuth, SigmaOf(in.sensor, *m)), nullptr,
                             result.poses[static_cast<std::size_t>(m->step)].data(), f.position.data());
    ++result.measurements_used;
  }
  result.residual_blocks = problem.NumResidualBlocks();

  ceres::Solver::Options so;
  so.max_num_iterations = options.max_iterations;
  so.function_tolerance = options.function_tolerance;
  so.num_threads = options.threads;
  const bool sparse = T > 50 && ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE);
  so.linear_solver_type = sparse ? ceres::SPARSE_SCHUR : ceres::DENSE_SCHUR;
  std::optional<Observer> observer;
  if (progress) {
    observer.emplace(*progress, options.max_iterations);
    so.callbacks.push_back(&*observer);
    progress->Update(0.05, "sonar smoother: " + std::to_string(result.measurements_used) + " measurements");
  }
  ceres::Solver::Summary summary;
  auto t0 = std::chrono::steady_clock::now();
  ceres::Solve(so, &problem, &summary);
  result.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress && summary.termination_type == ceres::USER_FAILURE) throw Cancelled();
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.report = summary.BriefReport();
  if (!options.covariances) return result;

  // Covariances: every pose, every smoothed point, and the joint block of the last pose and the points.
  if (progress) progress->Update(0.85, "sonar smoother: covariances");
  t0 = std::chrono::steady_clock::now();
  std::vector<std::size_t> smoothed;
  for (std::size_t i = 0; i < n; ++i) {
    if (result.features[i].smoothed) smoothed.push_back(i);
  }
  const bool joint = static_cast<int>(smoothed.size()) <= options.max_joint_features;
  std::vector<std::pair<const double*, const double*>> blocks;
  for (const Vector6d& x : result.poses) blocks.emplace_back(x.data(), x.data());
  const double* last = result.poses.back().data();
  for (std::size_t a = 0; a < smoothed.size(); ++a) {
    const double* pa = result.features[smoothed[a]].position.data();
    blocks.emplace_back(pa, pa);
    if (!joint) continue;
    blocks.emplace_back(last, pa);
    for (std::size_t b = a + 1; b < smoothed.size(); ++b) {
      blocks.emplace_back(pa, result.features[smoothed[b]].position.data());
    }
  }
  ceres::Covariance::Options co;
  co.num_threads = options.threads;
  ceres::Covariance covariance(co);
  result.covariance_ok = covariance.Compute(blocks, &problem);
  if (result.covariance_ok) {
    for (Vector6d& x : result.poses) {
      Matrix6d C;
      covariance.GetCovarianceBlock(x.data(), x.data(), C.data());
      result.pose_covariances[static_cast<std::size_t>(&x - result.poses.data())] = C;
    }
    const int m = static_cast<int>(smoothed.size());
    if (joint) result.joint_covariance.resize(6 + 3 * m, 6 + 3 * m);
    if (joint) result.joint_covariance.topLeftCorner<6, 6>() = result.pose_covariances.back();
    for (int a = 0; a < m; ++a) {
      SonarSmoothedFeature& fa = result.features[smoothed[static_cast<std::size_t>(a)]];
      Eigen::Matrix3d C;
      covariance.GetCovarianceBlock(fa.position.data(), fa.position.data(), C.data());
      fa.covariance = C;
      if (!joint) continue;
      Eigen::Matrix<double, 6, 3, Eigen::RowMajor> X;
      covariance.GetCovarianceBlock(last, fa.position.data(), X.data());
      result.joint_covariance.block<6, 3>(0, 6 + 3 * a) = X;
      result.joint_covariance.block<3, 6>(6 + 3 * a, 0) = X.transpose();
      result.joint_covariance.block<3, 3>(6 + 3 * a, 6 + 3 * a) = C;
      for (int b = a + 1; b < m; ++b) {
        const double* pb = result.features[smoothed[static_cast<std::size_t>(b)]].position.data();
        Eigen::Matrix<double, 3, 3, Eigen::RowMajor> Y;
        covariance.GetCovarianceBlock(fa.position.data(), pb, Y.data());
        result.joint_covariance.block<3, 3>(6 + 3 * a, 6 + 3 * b) = Y;
        result.joint_covariance.block<3, 3>(6 + 3 * b, 6 + 3 * a) = Y.transpose();
      }
    }
  } else {
    for (std::size_t i : smoothed) result.features[i].covariance = Eigen::Matrix3d::Constant(kNaN);
  }
  result.covariance_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) progress->Update(1.0, "sonar smoother done");
  return result;
}

}  // namespace hull
