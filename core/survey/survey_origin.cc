#include "survey/survey_origin.h"

#include <cmath>

namespace hull {

Eigen::Vector3d LocalOrigin(const SurveyBundle& bundle) {
  if (bundle.nav.empty()) return Eigen::Vector3d::Zero();
  const Vector6d& x = bundle.nav.front().x_gv;
  auto grid = [](double v) { return std::isfinite(v) ? kLocalOriginGrid * std::round(v / kLocalOriginGrid) : 0.0; };
  return {grid(x[0]), grid(x[1]), 0.0};
}

Pose ShiftedFrame(const Pose& x_gX, const Eigen::Vector3d& delta) {
  return Pose(x_gX.quaternion(), x_gX.translation() + delta);
}

Vector6d ShiftedFrame(const Vector6d& x_gX, const Eigen::Vector3d& delta) {
  Vector6d out = x_gX;
  out.head<3>() += delta;
  return out;
}

void ShiftSurvey(SurveyBundle& b, const Eigen::Vector3d& delta) {
  for (NavRecord& n : b.nav) n.x_gv = ShiftedFrame(n.x_gv, delta);
  if (b.manifest.model_pose_guess) b.manifest.model_pose_guess = ShiftedFrame(*b.manifest.model_pose_guess, delta);
  if (b.landmarks) {
    for (LandmarkRecord& l : *b.landmarks) l.p += delta;
  }
  if (b.truth) {
    for (TruePose& p : b.truth->poses) p.x_gv = ShiftedFrame(p.x_gv, delta);
    for (TrueLandmark& l : b.truth->landmarks) l.p += delta;
    b.truth->x_gM = ShiftedFrame(b.truth->x_gM, delta);
  }
}

}  // namespace hull
