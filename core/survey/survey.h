// Survey bundle, versions 1 and 2 (../shared/survey-format.md): the in-memory
// model. Version 2 adds camera images (images/), listed here by path only:
// the pixels are read when needed (survey/survey_images.h).
// Ids are the file's own integers; vectors keep the files' row order (nav is
// sorted by time, which the contract requires).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/pose.h"
#include "survey/acoustic_sequence.h"

namespace hull {

struct PinholeIntrinsics {
  double fx = 1150, fy = 1150, cx = 680, cy = 512;
  // u = fx X / Z + cx, v = fy Y / Z + cy (rectified, undistorted).
  Eigen::Vector2d Project(const Eigen::Vector3d& p_c) const {
    return {fx * p_c.x() / p_c.z() + cx, fy * p_c.y() / p_c.z() + cy};
  }
  // Unit-depth ray through a pixel.
  Eigen::Vector3d Unproject(const Eigen::Vector2d& uv) const { return {(uv.x() - cx) / fx, (uv.y() - cy) / fy, 1.0}; }
};

enum class CameraType { kStereo, kMono };

struct CameraRig {
  CameraType type = CameraType::kStereo;
  int width = 1360, height = 1024;
  PinholeIntrinsics top, bottom;
  Vector6d top_to_bottom = (Vector6d() << 0, 0.10, 0, 0, 0, 0).finished();               // x_cT_cB (fixed)
  Vector6d servo_to_top = (Vector6d() << 0.30, 0, 0, M_PI / 2, 0, M_PI / 2).finished();  // nominal x_s_cT
  bool stereo() const { return type == CameraType::kStereo; }
  // Inside the image, origin at the centre of the top-left pixel.
  bool InImage(const Eigen::Vector2d& uv) const {
    return uv.x() > -0.5 && uv.y() > -0.5 && uv.x() < width - 0.5 && uv.y() < height - 0.5;
  }
};

struct NoiseModel {
  double pixel_sigma = 2.0;                  // px
  double dvl_range_sigma = 0.003;            // m
  double depth_sigma = 0.1;                  // m
  double roll_pitch_sigma = 0.001745;        // rad (0.1 deg)
  double servo_sigma = 0.0873;               // rad (5 deg)
  double odometry_translation_rate = 0.005;  // m/s
  double odometry_rotation_rate = 0.000388;  // rad/s (80 deg/h)
  double model_pose_sigma = 1.0;             // Sigma = I6 on x_gM
  Vector6d servo_to_top_sigma = (Vector6d() << 0.01, 0.01, 0.01, 0.0175, 0.0175, 0.0175).finished();
};

struct ModelAxes {
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX();  // toward the bow, in M
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
};

// The optional "images" block of a version 2 survey.json (informational).
struct ImagingNote {
  std::optional<double> exposure_s;         // exposure time (s)
  std::optional<std::string> illumination;  // e.g. "strobe"
};

struct SurveyManifest {
  int version = 1;  // 1, or 2 (camera images in images/)
  std::string name;
  std::string vehicle;
  std::optional<std::string> model_hint;  // mesh path relative to the bundle
  CameraRig camera;
  Vector6d servo_mount = (Vector6d() << 0.4, 0, 0.2, 0, 0, 0).finished();
  Vector6d servo_to_dvl = (Vector6d() << 0.22, 0.12, 0.05, M_PI / 2, 0, M_PI / 2).finished();
  std::array<Eigen::Vector3d, 4> beams = {Eigen::Vector3d(0.5, 0, 0.866), Eigen::Vector3d(-0.5, 0, 0.866),
                                          Eigen::Vector3d(0, 0.5, 0.866), Eigen::Vector3d(0, -0.5, 0.866)};
  std::optional<Vector6d> model_pose_guess;  // initial x_gM
  std::optional<ModelAxes> model_axes;
  NoiseModel noise;
  std::optional<ImagingNote> imaging;  // version 2 "images" block

  // Unit beam directions in the DVL frame d.
  Eigen::Vector3d BeamDirection(int i) const { return beams[i].normalized(); }
  // x_vs(theta) = mount (+) [0,0,0, 0,theta,0].
  Pose VehicleToServo(double theta) const {
    return Pose::FromVector(servo_mount) * Pose::FromXyzRpy(0, 0, 0, 0, theta, 0);
  }
};

struct NavRecord {
  std::int64_t keyframe = 0;
  double t = 0;
  Vector6d x_gv = Vector6d::Zero();  // initial estimate (dead reckoning)
  double depth = 0, roll_meas = 0, pitch_meas = 0;
  double servo = 0;  // instrumented servo angle (rad)
};

struct OdometryRecord {
  std::int64_t from = 0, to = 0;
  Vector6d z = Vector6d::Zero();  // (-)x_g,from (+) x_g,to
};

constexpr double kNoReturn = std::numeric_limits<double>::quiet_NaN();

struct DvlRecord {
  std::int64_t keyframe = 0;
  std::array<double, 4> range = {kNoReturn, kNoReturn, kNoReturn, kNoReturn};  // NaN: no return
  static bool HasReturn(double r) { return r == r; }
};

struct FeatureObservation {
  std::int64_t keyframe = 0;
  std::int64_t landmark = 0;
  Eigen::Vector2d top = Eigen::Vector2d::Zero();
  Eigen::Vector2d bottom = Eigen::Vector2d::Zero();
  bool has_bottom = false;
};

struct LandmarkRecord {
  std::int64_t landmark = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // in g
};

enum class ObjectKind { kCylinder, kBox, kPatch };
const char* ObjectKindName(ObjectKind k);

struct TrueObject {
  std::string id;
  ObjectKind kind = ObjectKind::kCylinder;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();   // base centre on the CAD surface, in M
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward surface normal there
  double radius = 0;                                  // cylinder, patch
  double height = 0;                                  // cylinder, patch (box: size[2])
  Eigen::Vector3d size = Eigen::Vector3d::Zero();     // box: [a, b, height]
  double Height() const { return kind == ObjectKind::kBox ? size.z() : height; }
};

struct TruePose {
  std::int64_t keyframe = 0;
  Vector6d x_gv = Vector6d::Zero();
  double servo = 0;
};

struct TrueLandmark {
  std::int64_t landmark = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // in g
  double deviation = 0;                         // signed distance to the CAD surface
  std::string object;                           // "" on the nominal hull
};

struct SurveyTruth {
  std::vector<TruePose> poses;
  std::vector<TrueLandmark> landmarks;
  std::vector<TrueObject> objects;
  Vector6d x_gM = Vector6d::Zero();
  Vector6d x_s_cT = Vector6d::Zero();
};

// The camera images of a version 2 bundle: which keyframes have which
// image. Paths are relative to the bundle ("images/12_top.png").
struct KeyframeImages {
  std::int64_t keyframe = 0;
  std::string top, bottom;  // empty: no image (a dropped frame; bottom always empty for mono)
};
struct SurveyImages {
  std::vector<KeyframeImages> frames;  // one per keyframe, in nav.csv order
  int expected = 0;                    // images the keyframes call for (1 or 2 per keyframe)
  int dropped = 0;                     // of which missing (dropped frames)
  int present() const { return expected - dropped; }
};

struct SurveyBundle {
  std::string directory;  // where it was read from (empty when built in memory)
  SurveyManifest manifest;
  std::vector<NavRecord> nav;
  std::vector<OdometryRecord> odometry;
  std::vector<DvlRecord> dvl;
  std::vector<FeatureObservation> features;
  std::optional<std::vector<LandmarkRecord>> landmarks;
  std::optional<SurveyTruth> truth;
  std::optional<AcousticSequence> sonar;
  std::optional<SurveyImages> images;  // version 2 with an images/ folder
  // The feature tracks were made by the visual front end from the images
  // (in this process, or on disk: features.csv with the front end's
  // match-graph.csv beside it). Their landmark ids are the front end's own,
  // so landmarks.csv and truth/landmarks.csv, keyed by the ids of the tracks
  // the survey came with, do not describe them and are not kept.
  bool features_from_images = false;

  // Absolute path of a keyframe's image, or "" when it has none.
  std::string ImagePath(std::int64_t keyframe, bool bottom_camera = false) const;

  // keyframe id -> index into nav.
  std::unordered_map<std::int64_t, int> KeyframeIndex() const;
  // Absolute path of the model hint, or "" when none.
  std::string ModelHintPath() const;
  // Number of distinct landmarks observed.
  std::size_t CountLandmarks() const;
  // Takes feature tracks made by the visual front end: sets features and
  // features_from_images, drops landmarks.csv's initial positions and the
  // truth landmarks (other ids; simulate/image_track_truth.h derives theirs).
  void AdoptImageFeatureTracks(std::vector<FeatureObservation> tracks);
};

}  // namespace hull
