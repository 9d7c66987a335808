#include "sonar/acoustic_camera.h"

#include <ceres/jet.h>

#include <algorithm>

namespace hull {

Eigen::Vector3d SonarPolar(const Eigen::Vector3d& q) {
  const double r = q.norm();
  return {r, std::atan2(q.y(), q.x()), r > 0 ? std::asin(std::clamp(q.z() / r, -1.0, 1.0)) : 0.0};
}

Eigen::Vector3d SonarPolarOf(const Vector6d& pose, const Eigen::Vector3d& p) {
  return SonarPolar(WorldToSonar<double>(pose, p));
}

bool InSonarView(const SonarSensor& s, const Eigen::Vector3d& polar) {
  return polar[0] >= s.range_min && polar[0] <= s.range_max && std::fabs(polar[1]) <= s.azimuth_fov / 2 &&
         std::fabs(polar[2]) <= s.elevation_fov / 2;
}

Eigen::Vector2d SonarMeasureJacobians(const Vector6d& pose, const Eigen::Vector3d& p,
                                      Eigen::Matrix<double, 2, 6>* H_pose, Eigen::Matrix<double, 2, 3>* H_point) {
  const double cr = std::cos(pose[3]), sr = std::sin(pose[3]);
  const double cp = std::cos(pose[4]), sp = std::sin(pose[4]);
  const double cy = std::cos(pose[5]), sy = std::sin(pose[5]);
  Eigen::Matrix3d Rx, Ry, Rz, dRx, dRy, dRz;
  Rx << 1, 0, 0, 0, cr, -sr, 0, sr, cr;
  Ry << cp, 0, sp, 0, 1, 0, -sp, 0, cp;
  Rz << cy, -sy, 0, sy, cy, 0, 0, 0, 1;
  dRx << 0, 0, 0, 0, -sr, -cr, 0, cr, -sr;
  dRy << -sp, 0, cp, 0, 0, 0, -cp, 0, -sp;
  dRz << -sy, -cy, 0, cy, -sy, 0, 0, 0, 0;
  const Eigen::Matrix3d R = Rz * Ry * Rx;
  const Eigen::Vector3d d = p - pose.head<3>();
  const Eigen::Vector3d q = R.transpose() * d;
  const double r = q.norm();
  const double rho2 = q.x() * q.x() + q.y() * q.y();
  // dh/dq: rows (range, azimuth).
  Eigen::Matrix<double, 2, 3> dh_dq;
  dh_dq.row(0) = q.transpose() / r;
  dh_dq.row(1) << -q.y() / rho2, q.x() / rho2, 0.0;
  const Eigen::Matrix<double, 2, 3> dh_dp = dh_dq * R.transpose();
  if (H_point) *H_point = dh_dp;
  if (H_pose) {
    H_pose->leftCols<3>() = -dh_dp;
    // dq/dalpha = (dR/dalpha)^T d.
    H_pose->col(3) = dh_dq * ((Rz * Ry * dRx).transpose() * d);
    H_pose->col(4) = dh_dq * ((Rz * dRy * Rx).transpose() * d);
    H_pose->col(5) = dh_dq * ((dRz * Ry * Rx).transpose() * d);
  }
  return {r, std::atan2(q.y(), q.x())};
}

Eigen::Vector3d SonarBackProjectJacobians(const Vector6d& pose, double r, double theta, double phi,
                                          Eigen::Matrix<double, 3, 6>* J_pose, Eigen::Matrix3d* J_polar) {
  using Jet = ceres::Jet<double, 9>;
  Eigen::Matrix<Jet, 6, 1> x;
  for (int i = 0; i < 6; ++i) x[i] = Jet(pose[i], i);
  const Eigen::Matrix<Jet, 3, 1> p = SonarBackProject<Jet>(x, Jet(r, 6), Jet(theta, 7), Jet(phi, 8));
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    out[i] = p[i].a;
    if (J_pose) J_pose->row(i) = p[i].v.head<6>().transpose();
    if (J_polar) J_polar->row(i) = p[i].v.tail<3>().transpose();
  }
  return out;
}

Vector6d SonarMotion(const Vector6d& pose, const Vector6d& u, Matrix6d* G_pose, Matrix6d* G_control) {
  if (G_pose || G_control) OplusJacobians(pose, u, G_pose, G_control);
  return OplusEuler<double>(pose, u);
}

Vector6d ControlSigma(const SonarMotionNoise& noise, const Vector6d& u) {
  Vector6d s;
  for (int i = 0; i < 3; ++i) s[i] = std::max(noise.translation_floor, noise.translation_per_metre * std::fabs(u[i]));
  for (int i = 3; i < 6; ++i) s[i] = std::max(noise.rotation_floor, noise.rotation_per_radian * std::fabs(u[i]));
  return s;
}

}  // namespace hull
