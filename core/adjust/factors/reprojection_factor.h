// Camera reprojection (eqs. 12 and 13): a landmark l (in g) projected through
//   x_g,cT = x_gv (+) x_vs(theta) (+) x_s_cT,   x_vs(theta) = mount (+) Ry(theta)
// into the top pinhole, and for a stereo observation also through
//   x_g,cB = x_g,cT (+) x_cT_cB   (fixed stereo calibration)
// into the bottom pinhole. Residuals are whitened by the pixel sigma; the
// problem wraps them in a Huber loss at 2 sigma.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "adjust/factors/pose_math.h"
#include "survey/survey.h"

namespace hull::adjust {

struct CameraModel {
  Pose mount;          // servo.mount
  Pose top_to_bottom;  // x_cT_cB
  PinholeIntrinsics top, bottom;
};

template <typename T>
Eigen::Matrix<T, 2, 1> ProjectPinhole(const PinholeIntrinsics& k, const Eigen::Matrix<T, 3, 1>& p) {
  return {T(k.fx) * p[0] / p[2] + T(k.cx), T(k.fy) * p[1] / p[2] + T(k.cy)};
}

// Landmark in the top-camera frame: p_cT = (x_gv (+) mount (+) Ry(theta) (+) x_s_cT)^-1 l,
// applied step by step to the point (two quaternion rotations instead of
// composing four poses: a third of the arithmetic under autodiff).
template <typename T>
Eigen::Matrix<T, 3, 1> LandmarkInTopCamera(const CameraModel& cam, const T* pose, const T* servo, const T* extrinsic,
                                           const T* landmark) {
  using std::cos;
  using std::sin;
  const Eigen::Quaternion<T> q_v(pose[3], pose[0], pose[1], pose[2]);
  const Eigen::Matrix<T, 3, 1> l_v =
      q_v.conjugate() * Eigen::Matrix<T, 3, 1>(landmark[0] - pose[4], landmark[1] - pose[5], landmark[2] - pose[6]);
  // Into the servo mount (constant).
  const Eigen::Matrix3d Rm_t = cam.mount.rotation().transpose();
  const Eigen::Matrix<T, 3, 1> l_m = Rm_t.cast<T>() * (l_v - cam.mount.translation().cast<T>());
  // Undo the servo rotation about y: Ry(theta)^T.
  const T c = cos(servo[0]), s = sin(servo[0]);
  const Eigen::Matrix<T, 3, 1> l_s(c * l_m[0] - s * l_m[2], l_m[1], s * l_m[0] + c * l_m[2]);
  // Into the top camera.
  const Eigen::Quaternion<T> q_c(extrinsic[3], extrinsic[0], extrinsic[1], extrinsic[2]);
  return q_c.conjugate() * Eigen::Matrix<T, 3, 1>(l_s[0] - extrinsic[4], l_s[1] - extrinsic[5], l_s[2] - extrinsic[6]);
}

class StereoReprojectionFactor {
 public:
  StereoReprojectionFactor(const CameraModel* cam, const Eigen::Vector2d& top, const Eigen::Vector2d& bottom,
                           double sigma)
      : cam_(cam), top_(top), bottom_(bottom), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* pose, const T* servo, const T* extrinsic, const T* landmark, T* residual) const {
    const Eigen::Matrix<T, 3, 1> pt = LandmarkInTopCamera(*cam_, pose, servo, extrinsic, landmark);
    const Eigen::Matrix<T, 3, 1> pb = PoseConstant<T>(cam_->top_to_bottom).Inverse() * pt;
    if (ScalarOf(pt[2]) <= 1e-6 || ScalarOf(pb[2]) <= 1e-6) return false;  // behind the camera
    const Eigen::Matrix<T, 2, 1> ut = ProjectPinhole(cam_->top, pt), ub = ProjectPinhole(cam_->bottom, pb);
    residual[0] = (ut[0] - T(top_.x())) * T(inv_sigma_);
    residual[1] = (ut[1] - T(top_.y())) * T(inv_sigma_);
    residual[2] = (ub[0] - T(bottom_.x())) * T(inv_sigma_);
    residual[3] = (ub[1] - T(bottom_.y())) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const CameraModel* cam, const Eigen::Vector2d& top, const Eigen::Vector2d& bottom,
                                     double sigma) {
    return new ceres::AutoDiffCostFunction<StereoReprojectionFactor, 4, kPoseSize, 1, kPoseSize, 3>(
        new StereoReprojectionFactor(cam, top, bottom, sigma));
  }

 private:
  const CameraModel* cam_;
  const Eigen::Vector2d top_, bottom_;
  const double inv_sigma_;
};

class MonoReprojectionFactor {
 public:
  MonoReprojectionFactor(const CameraModel* cam, const Eigen::Vector2d& top, double sigma)
      : cam_(cam), top_(top), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* pose, const T* servo, const T* extrinsic, const T* landmark, T* residual) const {
    const Eigen::Matrix<T, 3, 1> pt = LandmarkInTopCamera(*cam_, pose, servo, extrinsic, landmark);
    if (ScalarOf(pt[2]) <= 1e-6) return false;
    const Eigen::Matrix<T, 2, 1> ut = ProjectPinhole(cam_->top, pt);
    residual[0] = (ut[0] - T(top_.x())) * T(inv_sigma_);
    residual[1] = (ut[1] - T(top_.y())) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const CameraModel* cam, const Eigen::Vector2d& top, double sigma) {
    return new ceres::AutoDiffCostFunction<MonoReprojectionFactor, 2, kPoseSize, 1, kPoseSize, 3>(
        new MonoReprojectionFactor(cam, top, sigma));
  }

 private:
  const CameraModel* cam_;
  const Eigen::Vector2d top_;
  const double inv_sigma_;
};

}  // namespace hull::adjust
