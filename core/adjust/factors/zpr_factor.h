// Depth, pitch and roll prior per vehicle pose (eq. 9): the pressure sensor
// and the IMU observe z, pitch and roll of x_gv directly.
//
//   r = [ (z - depth) / sigma_z ; (pitch - pitch_meas) / sigma_rp ; (roll - roll_meas) / sigma_rp ]
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "adjust/factors/pose_math.h"

namespace hull::adjust {

class ZprFactor {
 public:
  ZprFactor(double depth, double pitch, double roll, double sigma_z, double sigma_rp)
      : depth_(depth), pitch_(pitch), roll_(roll), inv_z_(1.0 / sigma_z), inv_rp_(1.0 / sigma_rp) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const PoseT<T> x = PoseFromBlock(pose);
    const Eigen::Matrix<T, 3, 1> e = EulerOf(x.q);
    residual[0] = (x.t[2] - T(depth_)) * T(inv_z_);
    residual[1] = WrapDifference(e[1] - T(pitch_)) * T(inv_rp_);
    residual[2] = WrapDifference(e[0] - T(roll_)) * T(inv_rp_);
    return true;
  }

  static ceres::CostFunction* Create(double depth, double pitch, double roll, double sigma_z, double sigma_rp) {
    return new ceres::AutoDiffCostFunction<ZprFactor, 3, kPoseSize>(
        new ZprFactor(depth, pitch, roll, sigma_z, sigma_rp));
  }

 private:
  const double depth_, pitch_, roll_, inv_z_, inv_rp_;
};

// Servo angle prior (eq. 10): the instrumented angle, sigma 5 deg by default.
class ServoPriorFactor {
 public:
  ServoPriorFactor(double measured, double sigma) : measured_(measured), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* theta, T* residual) const {
    residual[0] = (theta[0] - T(measured_)) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(double measured, double sigma) {
    return new ceres::AutoDiffCostFunction<ServoPriorFactor, 1, 1>(new ServoPriorFactor(measured, sigma));
  }

 private:
  const double measured_, inv_sigma_;
};

}  // namespace hull::adjust
