// One camera of one keyframe as the photomosaic sees it: the adjusted
// vehicle pose, servo angle, camera extrinsic and model pose, projecting a
// point of the model frame M with the bundle adjustment's own reprojection
// code (adjust/factors/reprojection_factor.h: LandmarkInTopCamera, the fixed
// stereo calibration for the bottom camera, ProjectPinhole), so a texel
// lands exactly where the adjustment says the point is seen.
#pragma once

#include <Eigen/Core>
#include <array>

#include "adjust/factors/reprojection_factor.h"
#include "geometry/pose.h"
#include "survey/survey.h"

namespace hull {

class MosaicCamera {
 public:
  MosaicCamera(const SurveyManifest& manifest, const Vector6d& x_gv, double servo, const Vector6d& x_s_cT,
               const Vector6d& x_gM, bool bottom);

  // p (in M) in this camera's frame; false when not in front of it.
  bool ToCamera(const Eigen::Vector3d& p_M, Eigen::Vector3d* p_c) const;
  // Pixel position of p (in M); false when not in front of the camera.
  bool Project(const Eigen::Vector3d& p_M, Eigen::Vector2d* uv, Eigen::Vector3d* p_c = nullptr) const;

  // The camera in M: x_gM^-1 (+) x_gv (+) x_vs(servo) (+) x_s_cT [(+) x_cT_cB].
  const Pose& x_Mc() const { return x_Mc_; }
  Eigen::Vector3d centre() const { return x_Mc_.translation(); }
  const PinholeIntrinsics& intrinsics() const { return bottom_ ? cam_.bottom : cam_.top; }
  bool bottom() const { return bottom_; }

 private:
  adjust::CameraModel cam_;
  std::array<double, adjust::kPoseSize> pose_{}, extrinsic_{};
  double servo_ = 0;
  Pose x_gM_, x_Mc_;
  adjust::PoseT<double> bottom_in_top_inv_;
  bool bottom_ = false;
};

}  // namespace hull
