#include "mosaic/mosaic_camera.h"

namespace hull {

MosaicCamera::MosaicCamera(const SurveyManifest& manifest, const Vector6d& x_gv, double servo, const Vector6d& x_s_cT,
                           const Vector6d& x_gM, bool bottom)
    : servo_(servo), x_gM_(Pose::FromVector(x_gM)), bottom_(bottom) {
  // The camera model exactly as the adjustment builds it (bundle_adjuster.cc).
  cam_.mount = Pose::FromVector(manifest.servo_mount);
  cam_.top_to_bottom = Pose::FromVector(manifest.camera.top_to_bottom);
  cam_.top = manifest.camera.top;
  cam_.bottom = manifest.camera.bottom;
  adjust::PoseToBlock(Pose::FromVector(x_gv), pose_.data());
  adjust::PoseToBlock(Pose::FromVector(x_s_cT), extrinsic_.data());
  bottom_in_top_inv_ = adjust::PoseConstant<double>(cam_.top_to_bottom).Inverse();
  const Pose g_cT = Pose::FromVector(x_gv) * manifest.VehicleToServo(servo) * Pose::FromVector(x_s_cT);
  x_Mc_ = x_gM_.Inverse() * (bottom ? g_cT * cam_.top_to_bottom : g_cT);
}

bool MosaicCamera::ToCamera(const Eigen::Vector3d& p_M, Eigen::Vector3d* p_c) const {
  const Eigen::Vector3d l = x_gM_ * p_M;
  const Eigen::Vector3d pt =
      adjust::LandmarkInTopCamera<double>(cam_, pose_.data(), &servo_, extrinsic_.data(), l.data());
  *p_c = bottom_ ? Eigen::Vector3d(bottom_in_top_inv_ * pt) : pt;
  return p_c->z() > 1e-6;  // the reprojection factors' "behind the camera"
}

bool MosaicCamera::Project(const Eigen::Vector3d& p_M, Eigen::Vector2d* uv, Eigen::Vector3d* p_c) const {
  Eigen::Vector3d pc;
  if (!ToCamera(p_M, &pc)) return false;
  *uv = adjust::ProjectPinhole<double>(intrinsics(), pc);
  if (p_c) *p_c = pc;
  return true;
}

}  // namespace hull
