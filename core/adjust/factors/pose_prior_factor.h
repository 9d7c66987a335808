// Full 6-DOF prior on a pose (eq. 8 of Ozog et al.): used for the model pose
// x_gM (from the initial alignment, Sigma = I6 by default) and for the camera
// extrinsic x_s_cT at its nominal value.
//
//   r = [ (t - t0) / sigma_t ;  2 vec(q0^-1 q) / sigma_r ]   (rotation error in the body frame)
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "adjust/factors/pose_math.h"

namespace hull::adjust {

class PosePriorFactor {
 public:
  PosePriorFactor(const Pose& prior, const Vector6d& sigma) : prior_(prior), inv_sigma_(sigma.cwiseInverse()) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const PoseT<T> x = PoseFromBlock(pose);
    const PoseT<T> x0 = PoseConstant<T>(prior_);
    const Eigen::Matrix<T, 3, 1> dt = x.t - x0.t;
    const Eigen::Matrix<T, 3, 1> dr = RotationError(x0.q, x.q);
    for (int i = 0; i < 3; ++i) {
      residual[i] = dt[i] * T(inv_sigma_[i]);
      residual[3 + i] = dr[i] * T(inv_sigma_[3 + i]);
    }
    return true;
  }

  static ceres::CostFunction* Create(const Pose& prior, const Vector6d& sigma) {
    return new ceres::AutoDiffCostFunction<PosePriorFactor, 6, kPoseSize>(new PosePriorFactor(prior, sigma));
  }

 private:
  const Pose prior_;
  const Vector6d inv_sigma_;
};

// Gauge prior on x, y and yaw of one vehicle pose (depth, pitch and roll are
// observed by the zpr factors; the rest of the survey is tied to it by odometry).
class GaugePriorFactor {
 public:
  GaugePriorFactor(const Vector6d& x0, double sigma_xy, double sigma_yaw)
      : x0_(x0), inv_xy_(1.0 / sigma_xy), inv_yaw_(1.0 / sigma_yaw) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const PoseT<T> x = PoseFromBlock(pose);
    residual[0] = (x.t[0] - T(x0_[0])) * T(inv_xy_);
    residual[1] = (x.t[1] - T(x0_[1])) * T(inv_xy_);
    residual[2] = WrapDifference(EulerOf(x.q)[2] - T(x0_[5])) * T(inv_yaw_);
    return true;
  }

  static ceres::CostFunction* Create(const Vector6d& x0, double sigma_xy, double sigma_yaw) {
    return new ceres::AutoDiffCostFunction<GaugePriorFactor, 3, kPoseSize>(
        new GaugePriorFactor(x0, sigma_xy, sigma_yaw));
  }

 private:
  const Vector6d x0_;
  const double inv_xy_, inv_yaw_;
};

}  // namespace hull::adjust
