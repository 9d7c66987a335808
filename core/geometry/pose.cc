#include "geometry/pose.h"

#include <ceres/jet.h>

namespace hull {

double WrapAngle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  if (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

Pose Pose::FromVector(const Vector6d& x) {
  return Pose(Eigen::Matrix3d(RotationFromEuler(x[3], x[4], x[5])), x.head<3>());
}

Pose Pose::FromArray(const double* x) { return FromVector(Eigen::Map<const Vector6d>(x)); }

Pose Pose::FromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw) {
  Vector6d v;
  v << x, y, z, roll, pitch, yaw;
  return FromVector(v);
}

Pose Pose::FromMatrix(const Eigen::Matrix4d& T) {
  return Pose(Eigen::Matrix3d(T.topLeftCorner<3, 3>()), Eigen::Vector3d(T.topRightCorner<3, 1>()));
}

Vector6d Pose::ToVector() const {
  Vector6d x;
  x.head<3>() = t_;
  x.tail<3>() = EulerFromRotation<double>(rotation());
  return x;
}

Eigen::Matrix4d Pose::Matrix() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = rotation();
  T.topRightCorner<3, 1>() = t_;
  return T;
}

double Pose::AngleBetween(const Pose& a, const Pose& b) { return a.q_.angularDistance(b.q_); }

Vector6d Oplus(const Vector6d& a, const Vector6d& b) { return OplusEuler<double>(a, b); }
Vector6d Ominus(const Vector6d& a) { return OminusEuler<double>(a); }

Vector6d PoseVectorDifference(const Vector6d& a, const Vector6d& b) {
  Vector6d d = a - b;
  for (int i = 3; i < 6; ++i) d[i] = WrapAngle(d[i]);
  return d;
}

namespace {
using Jet12 = ceres::Jet<double, 12>;
using Jet6 = ceres::Jet<double, 6>;
}  // namespace

void OplusJacobians(const Vector6d& a, const Vector6d& b, Matrix6d* J_a, Matrix6d* J_b) {
  Eigen::Matrix<Jet12, 6, 1> ja, jb;
  for (int i = 0; i < 6; ++i) {
    ja[i] = Jet12(a[i], i);
    jb[i] = Jet12(b[i], 6 + i);
  }
  const Eigen::Matrix<Jet12, 6, 1> c = OplusEuler<Jet12>(ja, jb);
  for (int r = 0; r < 6; ++r) {
    if (J_a) J_a->row(r) = c[r].v.head<6>().transpose();
    if (J_b) J_b->row(r) = c[r].v.tail<6>().transpose();
  }
}

Matrix6d OminusJacobian(const Vector6d& a) {
  Eigen::Matrix<Jet6, 6, 1> ja;
  for (int i = 0; i < 6; ++i) ja[i] = Jet6(a[i], i);
  const Eigen::Matrix<Jet6, 6, 1> c = OminusEuler<Jet6>(ja);
  Matrix6d J;
  for (int r = 0; r < 6; ++r) J.row(r) = c[r].v.transpose();
  return J;
}

}  // namespace hull
