// A small survey over a textured plane or cylinder for the vision tests:
// a 640x512 stereo (or mono) rig, keyframes along vehicle x, the true
// navigation and a prior with errors, images rendered from the truth.
#pragma once

#include <cmath>
#include <filesystem>
#include <optional>
#include <vector>

#include "image/image_file.h"
#include "support/test_scenes.h"
#include "survey/survey.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"
#include "vision/camera_geometry.h"

namespace hull::testing {

struct VisionScene {
  SurveyManifest manifest;
  TexturedSurface surface;
  std::vector<NavRecord> truth, nav;  // true poses; the prior (with errors)

  Eigen::Matrix3d K(bool bottom = false) const {
    return CameraMatrix(bottom ? manifest.camera.bottom : manifest.camera.top);
  }
  Pose TruePose(std::size_t i, bool bottom = false) const { return CameraPoseFromNav(manifest, truth[i], bottom); }
  cv::Mat Render(std::size_t i, bool bottom = false) const {
    RenderOptions o;
    o.seed = static_cast<int>(2 * i + (bottom ? 1 : 0));
    return RenderSurface(surface, TruePose(i, bottom), K(bottom), manifest.camera.width, manifest.camera.height, o);
  }
  // Where the surface point seen at top pixel uv of keyframe i appears in
  // keyframe j's top (or bottom) image; nothing when the pixel misses.
  std::optional<Eigen::Vector2d> Transfer(std::size_t i, const Eigen::Vector2d& uv, std::size_t j,
                                          bool bottom = false) const {
    const auto p = BackProject(surface, TruePose(i), K(), uv);
    if (!p) return std::nullopt;
    return (K(bottom) * (TruePose(j, bottom).Inverse() * *p)).hnormalized();
  }
  std::optional<Eigen::Vector3d> SurfacePoint(std::size_t i, const Eigen::Vector2d& uv) const {
    return BackProject(surface, TruePose(i), K(), uv);
  }
};

// `keyframes` keyframes `step` m apart along vehicle x, the camera looking
// up (servo pi/2) at the surface 1.5 m away.
inline VisionScene MakeVisionScene(bool stereo, bool cylinder, int keyframes, double step = 0.15) {
  VisionScene s;
  CameraRig& rig = s.manifest.camera;
  rig.type = stereo ? CameraType::kStereo : CameraType::kMono;
  rig.width = 640;
  rig.height = 512;
  rig.top = rig.bottom = PinholeIntrinsics{560, 560, 319.5, 255.5};
  s.manifest.version = 2;
  for (int i = 0; i < keyframes; ++i) {
    NavRecord n;
    n.keyframe = 10 + 3 * i;  // ids that are not indices
    n.t = i;
    n.x_gv << step * i, 0.02 * std::sin(i), 0, 0, 0, 0.01 * i;
    n.servo = M_PI / 2;
    s.truth.push_back(n);
    // The prior: dead-reckoning drift and servo slop (a few pixels to ~20 px).
    NavRecord p = n;
    p.x_gv[0] += 0.006 * i;
    p.x_gv[1] -= 0.004 * i;
    p.x_gv[5] += 0.003 * (i % 2 ? 1 : -1);
    p.servo += 0.004;
    s.nav.push_back(p);
  }
  const Pose c0 = CameraPoseFromNav(s.manifest, s.truth[0]);
  const Eigen::Vector3d z0 = c0.rotation().col(2);
  s.surface.texture = RandomTexture(1024, 7);
  if (cylinder) {
    s.surface.kind = TexturedSurface::Kind::kCylinder;
    s.surface.radius = 1.2;
    s.surface.origin = c0.translation() + (1.5 + s.surface.radius) * z0;
    s.surface.axis_u = Eigen::Vector3d::UnitX();  // along the vehicle's track
    s.surface.axis_v = (-z0 + z0.x() * Eigen::Vector3d::UnitX()).normalized();
  } else {
    s.surface.origin = c0.translation() + 1.5 * z0;
    s.surface.axis_u = c0.rotation().col(0);
    s.surface.axis_v = c0.rotation().col(1);
  }
  return s;
}

// A two-track lawnmower over a textured plane 1.5 m from a 640x512 stereo
// (or mono) camera looking up: `per_track` keyframes `step` m apart along
// vehicle x, then the same number back along -x, `spacing` m over in y (the
// vehicle keeps its heading, as a hovering vehicle does). The prior drifts
// on the way back by `drift` m per keyframe (x) and half of it (y), on top of
// MakeVisionScene's errors, so a revisit is off by decimetres; keyframes are
// 1 s apart and survey.json's odometry_translation_rate is 0.03 m/s, so the
// drift model covers it.
inline VisionScene MakeTwoTrackScene(bool stereo, int per_track = 8, double step = 0.3, double spacing = 0.6,
                                     double drift = 0.03) {
  VisionScene s = MakeVisionScene(stereo, false, 2 * per_track, step);
  s.manifest.noise.odometry_translation_rate = 0.03;
  for (int i = 0; i < 2 * per_track; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    const bool back = i >= per_track;
    const Vector6d error = s.nav[k].x_gv - s.truth[k].x_gv;
    s.truth[k].x_gv << (back ? step * (2 * per_track - 1 - i) : step * i), (back ? spacing : 0.0) + 0.02 * std::sin(i),
        0, 0, 0, 0.003 * std::cos(i);
    s.nav[k].x_gv = s.truth[k].x_gv + error;
    if (back) {
      s.nav[k].x_gv[0] += drift * (i - per_track + 1);
      s.nav[k].x_gv[1] += 0.5 * drift * (i - per_track + 1);
    }
  }
  // A texture that does not repeat within the surveyed patch (2048 texels at
  // 400 per metre: 5 m).
  s.surface.texture = RandomTexture(2048, 11);
  return s;
}

// Writes the scene as a version 2 bundle without features.csv; keyframe
// `drop_bottom` (an index) loses its bottom image (a dropped frame).
inline void WriteSceneBundle(const VisionScene& s, const std::string& dir, int drop_bottom = -1) {
  SurveyBundle b;
  b.manifest = s.manifest;
  b.manifest.name = "vision";
  b.nav = s.nav;
  for (std::size_t k = 0; k < s.nav.size(); ++k) {
    // The DVL's true ranges to the surface (the front end's loop footprints
    // and track check place the hull with them).
    DvlRecord d;
    d.keyframe = s.nav[k].keyframe;
    const Pose x_g_d = s.TruePose(k) * Pose::FromVector(s.manifest.camera.servo_to_top).Inverse() *
                       Pose::FromVector(s.manifest.servo_to_dvl);
    for (int beam = 0; beam < 4; ++beam) {
      const auto hit = s.surface.Intersect(x_g_d.translation(), x_g_d.rotation() * s.manifest.BeamDirection(beam));
      d.range[static_cast<std::size_t>(beam)] = hit ? (*hit - x_g_d.translation()).norm() : std::nan("");
    }
    b.dvl.push_back(d);
    if (k > 0) b.odometry.push_back({s.nav[k - 1].keyframe, s.nav[k].keyframe, Vector6d::Zero()});
  }
  b.images = SurveyImages{};
  WriteSurveyBundle(b, dir);
  std::filesystem::create_directories(std::filesystem::path(dir) / "images");
  for (std::size_t k = 0; k < s.nav.size(); ++k) {
    WriteImageFile(dir + "/images/" + SurveyImageName(s.nav[k].keyframe, false), s.Render(k));
    if (s.manifest.camera.stereo() && static_cast<int>(k) != drop_bottom)
      WriteImageFile(dir + "/images/" + SurveyImageName(s.nav[k].keyframe, true), s.Render(k, true));
  }
}

}  // namespace hull::testing
