// Templated rigid-body algebra for the cost functors (doubles or ceres::Jet).
//
// A pose parameter block holds 7 numbers [qx, qy, qz, qw, tx, ty, tz]: an
// Eigen-ordered unit quaternion (on the EigenQuaternionManifold, i.e. SO(3))
// and a translation, with the contract's meaning x_ab: p_a = R_ab p_b + t_ab.
#pragma once

#include <ceres/jet.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "geometry/pose.h"

namespace hull::adjust {

constexpr int kPoseSize = 7;

template <typename T>
struct PoseT {
  Eigen::Quaternion<T> q;
  Eigen::Matrix<T, 3, 1> t;

  PoseT operator*(const PoseT& o) const { return {q * o.q, q * o.t + t}; }
  PoseT Inverse() const {
    const Eigen::Quaternion<T> qi = q.conjugate();
    return {qi, -(qi * t)};
  }
  Eigen::Matrix<T, 3, 1> operator*(const Eigen::Matrix<T, 3, 1>& p) const { return q * p + t; }
};

// A pose parameter block as a PoseT.
template <typename T>
PoseT<T> PoseFromBlock(const T* block) {
  return {Eigen::Quaternion<T>(block[3], block[0], block[1], block[2]),
          Eigen::Matrix<T, 3, 1>(block[4], block[5], block[6])};
}

// A constant pose (double) lifted into T.
template <typename T>
PoseT<T> PoseConstant(const Pose& p) {
  const Eigen::Quaterniond& q = p.quaternion();
  return {Eigen::Quaternion<T>(T(q.w()), T(q.x()), T(q.y()), T(q.z())), p.translation().template cast<T>()};
}

// Rotation about y by theta (the servo), as a pose with zero translation.
template <typename T>
PoseT<T> ServoRotation(const T& theta) {
  using std::cos;
  using std::sin;
  const T h = theta * T(0.5);
  return {Eigen::Quaternion<T>(cos(h), T(0), sin(h), T(0)), Eigen::Matrix<T, 3, 1>::Zero()};
}

// Pose <-> parameter block.
inline void PoseToBlock(const Pose& p, double* block) {
  const Eigen::Quaterniond& q = p.quaternion();
  block[0] = q.x();
  block[1] = q.y();
  block[2] = q.z();
  block[3] = q.w();
  block[4] = p.translation().x();
  block[5] = p.translation().y();
  block[6] = p.translation().z();
}
inline Pose BlockToPose(const double* block) {
  return Pose(Eigen::Quaterniond(block[3], block[0], block[1], block[2]),
              Eigen::Vector3d(block[4], block[5], block[6]));
}

// The scalar part of a double or a Jet (for data association inside a functor).
inline double ScalarOf(double x) { return x; }
template <int N>
double ScalarOf(const ceres::Jet<double, N>& x) {
  return x.a;
}
template <typename T>
Eigen::Vector3d ScalarOf(const Eigen::Matrix<T, 3, 1>& v) {
  return {ScalarOf(v[0]), ScalarOf(v[1]), ScalarOf(v[2])};
}

// Wraps an angle difference into (-pi, pi] (a constant shift: exact derivative).
template <typename T>
T WrapDifference(const T& a) {
  const double k = std::round(ScalarOf(a) / (2.0 * M_PI));
  return a - T(2.0 * M_PI * k);
}

// (roll, pitch, yaw) of a quaternion (away from pitch = +-90 deg, where a
// hovering vehicle never is).
template <typename T>
Eigen::Matrix<T, 3, 1> EulerOf(const Eigen::Quaternion<T>& q) {
  const Eigen::Matrix<T, 3, 3> R = q.toRotationMatrix();
  return EulerFromRotation<T>(R);
}

// Tangent-space difference of two orientations: 2 vec(q_ref^-1 q), the
// rotation vector for small errors (sign-safe: the shorter way round).
template <typename T>
Eigen::Matrix<T, 3, 1> RotationError(const Eigen::Quaternion<T>& q_ref, const Eigen::Quaternion<T>& q) {
  Eigen::Quaternion<T> d = q_ref.conjugate() * q;
  if (ScalarOf(d.w()) < 0) d.coeffs() = -d.coeffs();
  return T(2.0) * d.vec();
}

}  // namespace hull::adjust
