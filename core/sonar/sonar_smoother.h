// A batch smoother after the sonar EKF (issue 11): one Ceres adjustment over
// every sonar pose x_0 ... x_{T-1} (6-DOF, the EKF's Euler vector) and the
// 3-D feature points, with
//   - a range/azimuth factor per measurement (the acoustic camera of eq. 10:
//     the elevation is not measured), weighted by its sigmas (the sensor's or
//     the detection's own),
//   - a motion factor per control: the relative pose (-)x_{k-1} (+) x_k
//     against the control u, component by component, with the contract's
//     motion noise sigma = max(floor, rate |u_i|) (the EKF's process model:
//     the same noise on u, here without linearising it),
//   - a prior on the first pose (the sequence's initial pose and sigmas),
// started from the EKF's output (its pose at every step and its final
// feature estimates). Nothing is linearised once and kept, as in a filter:
// every measurement is relinearised at the joint optimum.
//
// The elevation is observable only through motion (a change of roll, or
// motion across the fan). A point whose own views do not pin it down, with
// the poses held at the EKF's, is left out of the adjustment: fewer than
// min_views views, or the weakest direction of its information matrix with
// a standard deviation above max_weak_sigma_fraction times the elevation
// fan's half-width at its range. It keeps the EKF's estimate, marked not
// smoothed; no prior is invented to make it look determined.
//
// Covariances come from ceres::Covariance (the inverse of the Gauss-Newton
// information at the optimum, the first pose's prior fixing the gauge): every
// pose's 6x6 block, every smoothed point's 3x3 block and, for up to
// max_joint_features points, the joint covariance of the last pose and the
// points (for the joint NEES).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "base/progress.h"
#include "geometry/pose.h"
#include "survey/acoustic_sequence.h"

namespace hull {

struct SonarSmootherOptions {
  // Levenberg-Marquardt iterations at most.
  int max_iterations = 50;
  // Ceres' relative cost decrease below which it stops.
  double function_tolerance = 1e-10;
  // A point needs this many views (measurements) to be smoothed.
  int min_views = 2;
  // A point is held out when the standard deviation along the weakest
  // direction of its views' information (poses fixed) exceeds this fraction
  // of the fan's half-width at its mean range, r elevation_fov / 2.
  double max_weak_sigma_fraction = 0.5;
  // Compute the covariances (ceres::Covariance).
  bool covariances = true;
  // The joint covariance of the last pose and the smoothed points only up
  // to this many points (it needs every pair of blocks).
  int max_joint_features = 64;
  // Threads for Ceres (residuals, Jacobians, linear solver, covariance).
  int threads = 1;

  // True when every field is usable; otherwise false and, when why is given,
  // the field and the reason ("field: reason").
  bool Check(std::string* why = nullptr) const;
};

// What the smoother adjusts: the sequence's sensor, noise, initial pose and
// controls; the measurements (with their feature ids; given correspondences
// or associated detections) and the starting point.
struct SonarSmootherInput {
  SonarSensor sensor;
  SonarMotionNoise motion_noise;
  Vector6d initial_pose = Vector6d::Zero();
  Vector6d initial_pose_sigma = Vector6d::Constant(1e-3);
  std::vector<SonarControl> controls;                // steps 1..T-1, in order
  std::vector<SonarMeasurement> measurements;        // any order; of steps 0..T-1
  std::vector<Vector6d> poses;                       // start: per step 0..T-1 (the EKF's)
  std::vector<std::int64_t> feature_ids;             // start: the features to estimate...
  std::vector<Eigen::Vector3d> features;             // ... and their positions (the EKF's)
  std::vector<Eigen::Matrix3d> feature_covariances;  // the EKF's, kept for held-out points
};

struct SonarSmoothedFeature {
  std::int64_t id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  // From ceres::Covariance when smoothed (NaN when it failed); the EKF's when held out.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  bool smoothed = true;   // false: held out (too few views or elevation not observable)
  int views = 0;          // measurements of it
  double weak_sigma = 0;  // sigma along the weakest direction of its views' information, poses fixed (m)
};

struct SonarSmootherResult {
  std::vector<Vector6d> poses;                 // per step
  std::vector<Matrix6d> pose_covariances;      // per step (NaN without covariances)
  std::vector<SonarSmoothedFeature> features;  // in the input's order
  bool covariance_ok = false;                  // ceres::Covariance succeeded
  // The last pose and the smoothed points (in the order of features,
  // skipping held-out ones): 6 + 3n square, empty above max_joint_features.
  Eigen::MatrixXd joint_covariance;
  int residual_blocks = 0;
  int measurements_used = 0;                // of smoothed points
  double initial_cost = 0, final_cost = 0;  // 1/2 sum of squared normalised residuals
  int iterations = 0;
  bool converged = false;  // Ceres reported convergence
  std::string report;      // Ceres' brief report
  double solve_seconds = 0, covariance_seconds = 0;
};

// Throws OptionError when options.Check() fails, std::invalid_argument on an
// inconsistent input (sizes, a measurement of an unknown step) and
// hull::Cancelled when the progress asks to stop.
SonarSmootherResult SmoothSonar(const SonarSmootherInput& input, const SonarSmootherOptions& options = {},
                                Progress* progress = nullptr);

// The normalised residual of a measurement factor, its Jacobians with
// respect to the pose (2x6) and the point (2x3) in closed form (the
// factor's own; checked numerically in the tests).
Eigen::Vector2d SonarMeasurementResidual(const Vector6d& pose, const Eigen::Vector3d& point, double range,
                                         double azimuth, const Eigen::Vector2d& sigma,
                                         Eigen::Matrix<double, 2, 6>* J_pose, Eigen::Matrix<double, 2, 3>* J_point);
// The motion factor's normalised residual ((-)a (+) b - u, angles wrapped) / sigma.
Vector6d SonarMotionResidual(const Vector6d& a, const Vector6d& b, const Vector6d& u, const Vector6d& sigma);

}  // namespace hull
