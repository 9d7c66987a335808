// Rigid poses in the survey contract's convention (Smith, Self and Cheeseman).
//
// A pose x_ab = [x, y, z, roll, pitch, yaw] places frame b in frame a:
//   p_a = R_ab p_b + t_ab,  R_ab = Rz(yaw) Ry(pitch) Rx(roll)  (intrinsic Z-Y-X).
// Composition x_ac = x_ab (+) x_bc:  R_ac = R_ab R_bc,  t_ac = R_ab t_bc + t_ab.
// (-)x_ab is the inverse. Internally a Pose keeps a unit quaternion (SO(3)),
// so composition never meets gimbal lock; the Euler vector is only the file
// format. The templated free functions work with ceres::Jet for autodiff.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace hull {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Wraps an angle into (-pi, pi].
double WrapAngle(double a);

// R = Rz(yaw) Ry(pitch) Rx(roll), closed form; T may be a ceres::Jet.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationFromEuler(const T& roll, const T& pitch, const T& yaw) {
  using std::cos;
  using std::sin;
  const T cr = cos(roll), sr = sin(roll), cp = cos(pitch), sp = sin(pitch), cy = cos(yaw), sy = sin(yaw);
  Eigen::Matrix<T, 3, 3> R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}

// (roll, pitch, yaw) of a rotation matrix with pitch in [-pi/2, pi/2]; at
// gimbal lock (|pitch| = pi/2) roll is set to 0 and yaw absorbs the rest.
template <typename T>
Eigen::Matrix<T, 3, 1> EulerFromRotation(const Eigen::Matrix<T, 3, 3>& R) {
  using std::atan2;
  using std::sqrt;
  const T c = sqrt(R(0, 0) * R(0, 0) + R(1, 0) * R(1, 0));
  Eigen::Matrix<T, 3, 1> e;
  e[1] = atan2(-R(2, 0), c);
  if (c > T(1e-10)) {
    e[0] = atan2(R(2, 1), R(2, 2));
    e[2] = atan2(R(1, 0), R(0, 0));
  } else {
    e[0] = T(0);
    e[2] = atan2(-R(0, 1), R(1, 1));
  }
  return e;
}

// Euler-vector (+) and (-), templated for autodiff (the EKF's Jacobians).
template <typename T>
Eigen::Matrix<T, 6, 1> OplusEuler(const Eigen::Matrix<T, 6, 1>& a, const Eigen::Matrix<T, 6, 1>& b) {
  const Eigen::Matrix<T, 3, 3> Ra = RotationFromEuler(a[3], a[4], a[5]);
  const Eigen::Matrix<T, 3, 3> Rb = RotationFromEuler(b[3], b[4], b[5]);
  Eigen::Matrix<T, 6, 1> c;
  c.template head<3>() = Ra * b.template head<3>() + a.template head<3>();
  c.template tail<3>() = EulerFromRotation<T>(Ra * Rb);
  return c;
}

template <typename T>
Eigen::Matrix<T, 6, 1> OminusEuler(const Eigen::Matrix<T, 6, 1>& a) {
  const Eigen::Matrix<T, 3, 3> Rt = RotationFromEuler(a[3], a[4], a[5]).transpose();
  Eigen::Matrix<T, 6, 1> c;
  c.template head<3>() = -(Rt * a.template head<3>());
  c.template tail<3>() = EulerFromRotation<T>(Eigen::Matrix<T, 3, 3>(Rt));
  return c;
}

class Pose {
 public:
  Pose() : q_(Eigen::Quaterniond::Identity()), t_(Eigen::Vector3d::Zero()) {}
  Pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) : q_(q.normalized()), t_(t) {}
  Pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) : q_(Eigen::Quaterniond(R).normalized()), t_(t) {}

  // From / to the contract's [x, y, z, roll, pitch, yaw].
  static Pose FromVector(const Vector6d& x);
  static Pose FromArray(const double* x);
  static Pose FromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw);
  static Pose FromMatrix(const Eigen::Matrix4d& T);
  static Pose Identity() { return Pose(); }
  Vector6d ToVector() const;

  const Eigen::Quaterniond& quaternion() const { return q_; }
  Eigen::Matrix3d rotation() const { return q_.toRotationMatrix(); }
  const Eigen::Vector3d& translation() const { return t_; }
  Eigen::Matrix4d Matrix() const;

  // x_ab (+) x_bc
  Pose operator*(const Pose& other) const { return Pose(q_ * other.q_, q_ * other.t_ + t_); }
  // (-)x_ab = x_ba
  Pose Inverse() const {
    const Eigen::Quaterniond qi = q_.conjugate();
    return Pose(qi, -(qi * t_));
  }
  // p_a = x_ab applied to p_b
  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return q_ * p + t_; }
  Eigen::Vector3d Rotate(const Eigen::Vector3d& v) const { return q_ * v; }

  // Rotation angle (rad) and translation distance between two poses.
  static double AngleBetween(const Pose& a, const Pose& b);
  static double DistanceBetween(const Pose& a, const Pose& b) { return (a.t_ - b.t_).norm(); }

 private:
  Eigen::Quaterniond q_;
  Eigen::Vector3d t_;
};

// Named operators as in the papers.
inline Pose Oplus(const Pose& a, const Pose& b) { return a * b; }
inline Pose Ominus(const Pose& a) { return a.Inverse(); }
Vector6d Oplus(const Vector6d& a, const Vector6d& b);
Vector6d Ominus(const Vector6d& a);
// Difference of two Euler vectors with the angles wrapped: a - b.
Vector6d PoseVectorDifference(const Vector6d& a, const Vector6d& b);

// Jacobians of the Euler-vector operators (Smith, Self and Cheeseman),
// computed exactly by forward-mode differentiation of the templates above.
void OplusJacobians(const Vector6d& a, const Vector6d& b, Matrix6d* J_a, Matrix6d* J_b);
Matrix6d OminusJacobian(const Vector6d& a);

}  // namespace hull
