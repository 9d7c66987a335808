// Odometry between consecutive keyframes (eq. 11): the relative pose
// z = (-)x_gi (+) x_g(i+1), compared component by component in the
// contract's [x, y, z, roll, pitch, yaw] with a diagonal sigma that grows
// with the time between the keyframes (5 mm/s and 80 deg/h by default).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "adjust/factors/pose_math.h"

namespace hull::adjust {

class OdometryFactor {
 public:
  OdometryFactor(const Vector6d& z, const Vector6d& sigma) : z_(z), inv_sigma_(sigma.cwiseInverse()) {}

  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, T* residual) const {
    const PoseT<T> rel = PoseFromBlock(pose_i).Inverse() * PoseFromBlock(pose_j);
    const Eigen::Matrix<T, 3, 1> e = EulerOf(rel.q);
    for (int k = 0; k < 3; ++k) {
      residual[k] = (rel.t[k] - T(z_[k])) * T(inv_sigma_[k]);
      residual[3 + k] = WrapDifference(e[k] - T(z_[3 + k])) * T(inv_sigma_[3 + k]);
    }
    return true;
  }

  static ceres::CostFunction* Create(const Vector6d& z, const Vector6d& sigma) {
    return new ceres::AutoDiffCostFunction<OdometryFactor, 6, kPoseSize, kPoseSize>(new OdometryFactor(z, sigma));
  }

 private:
  const Vector6d z_;
  const Vector6d inv_sigma_;
};

}  // namespace hull::adjust
