// The acoustic camera (imaging sonar) model of Mai et al. (eq. 9-10) in the
// contract's conventions: sonar frame x along the boresight, y to the right,
// z down; with the sonar at pose x_ws = [c, R_ws] a world point p is at
//   p' = R_ws^T (p - c),   r = |p'|,   theta = atan2(y', x'),
// and its elevation phi = asin(z'/r) is lost. The templates work with
// ceres::Jet, the analytic Jacobians are checked against both in the tests.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "geometry/pose.h"
#include "survey/acoustic_sequence.h"

namespace hull {

// p' = R_ws^T (p - c) for a pose vector [x, y, z, roll, pitch, yaw].
template <typename T>
Eigen::Matrix<T, 3, 1> WorldToSonar(const Eigen::Matrix<T, 6, 1>& pose, const Eigen::Matrix<T, 3, 1>& p) {
  const Eigen::Matrix<T, 3, 3> R = RotationFromEuler(pose[3], pose[4], pose[5]);
  return R.transpose() * (p - pose.template head<3>());
}

// The measurement h = (range, azimuth) of eq. 10.
template <typename T>
Eigen::Matrix<T, 2, 1> SonarMeasure(const Eigen::Matrix<T, 6, 1>& pose, const Eigen::Matrix<T, 3, 1>& p) {
  using std::atan2;
  using std::sqrt;
  const Eigen::Matrix<T, 3, 1> q = WorldToSonar(pose, p);
  return Eigen::Matrix<T, 2, 1>(sqrt(q.squaredNorm()), atan2(q[1], q[0]));
}

// The inverse model: the world point at range r, azimuth theta and elevation
// phi seen from the pose: p = c + R_ws r [cos phi cos theta, cos phi sin theta, sin phi].
template <typename T>
Eigen::Matrix<T, 3, 1> SonarBackProject(const Eigen::Matrix<T, 6, 1>& pose, const T& r, const T& theta, const T& phi) {
  using std::cos;
  using std::sin;
  const Eigen::Matrix<T, 3, 3> R = RotationFromEuler(pose[3], pose[4], pose[5]);
  const Eigen::Matrix<T, 3, 1> q(r * cos(phi) * cos(theta), r * cos(phi) * sin(theta), r * sin(phi));
  return R * q + pose.template head<3>();
}

// Range, azimuth and elevation of a sonar-frame point.
Eigen::Vector3d SonarPolar(const Eigen::Vector3d& p_sonar);
// Range, azimuth and elevation of a world point seen from a pose.
Eigen::Vector3d SonarPolarOf(const Vector6d& pose, const Eigen::Vector3d& p);

// Inside the field of view and range limits of the contract:
// range_min <= r <= range_max, |theta| <= azimuth_fov/2, |phi| <= elevation_fov/2.
bool InSonarView(const SonarSensor& sensor, const Eigen::Vector3d& polar);

// The Jacobians of h (eq. 10) with respect to the pose (2x6, Euler angles as
// in the state) and the point (2x3), in closed form. Returns h.
Eigen::Vector2d SonarMeasureJacobians(const Vector6d& pose, const Eigen::Vector3d& p,
                                      Eigen::Matrix<double, 2, 6>* H_pose, Eigen::Matrix<double, 2, 3>* H_point);

// The inverse model and its Jacobians with respect to the pose (3x6) and to
// (r, theta, phi) (3x3), exact by forward-mode differentiation.
Eigen::Vector3d SonarBackProjectJacobians(const Vector6d& pose, double r, double theta, double phi,
                                          Eigen::Matrix<double, 3, 6>* J_pose, Eigen::Matrix3d* J_polar);

// The motion model g of the prediction (eq. 6): the pose after the control,
// x (+) u, and its Jacobians G = dg/dx and dg/du (6x6 each).
Vector6d SonarMotion(const Vector6d& pose, const Vector6d& u, Matrix6d* G_pose, Matrix6d* G_control);

// The control's noise as the contract defines it: independent per component,
// sigma = max(floor, rate * |u_i|) (translation per metre, rotation per radian).
Vector6d ControlSigma(const SonarMotionNoise& noise, const Vector6d& u);

}  // namespace hull
