// The survey simulator: writes a survey bundle with ground truth for a
// hull (the built-in parametric hull or any mesh file) carrying foreign
// structure, surveyed by an HAUV with a servoed stereo or monocular camera
// and a four-beam Janus DVL. Deterministic from the seed. Version 1 (feature
// tracks); with `images`, version 2: the same bundle plus the camera images
// rendered from the truth (simulate/survey_imaging.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "simulate/fouling_changes.h"
#include "simulate/hull_forms.h"
#include "simulate/image_renderer.h"
#include "simulate/survey_plan.h"
#include "survey/survey.h"

namespace hull {

enum class ObjectSet {
  kNone,
  kDemo,       // centreline fouling strip, the 0.15 x 0.11 m cylinder, a box, a few patches (in the surveyed stretch)
  kScattered,  // the demo set plus `scattered_patches` random patches over the survey
};

struct SurveySimulationOptions {
  std::string name = "Simulated survey";
  std::uint64_t seed = 1;

  // Hull: the parametric hull when mesh_path is empty, else the mesh file
  // scaled by mesh_scale; axes and waterline in the mesh's own frame.
  std::string mesh_path;
  double mesh_scale = 1.0;
  HullFormOptions hull_form;
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  double waterline = -1;      // along `up`; < 0: the hull form's draft, or 60 % of a mesh's height
  double heading_deg = 20.0;  // ship heading in g

  // Where and how the vehicle flies (start/end < 0: the middle 12 m of the hull).
  LawnmowerOptions plan;

  // Sensors.
  CameraType camera = CameraType::kStereo;
  double camera_scale = 1.0;     // scales the cameras' pixel grid (1360x1024 at 1; 0.25: 340x256 for quick tests)
  NoiseModel noise;              // also written to survey.json
  double servo_bias_deg = 2.0;   // servo slop: a constant bias of random sign ...
  double servo_noise_deg = 0.3;  // ... plus noise
  double dvl_max_range = 30.0;   // no return beyond
  double dvl_dropout = 0.005;    // probability that a beam with a hit returns nothing

  // Features.
  double hull_feature_density = 25.0;     // per m^2 of salient hull
  double object_feature_density = 300.0;  // per m^2 of foreign structure (textured)
  double non_salient_fraction = 0.2;      // share of the hull with no features at all
  double detection_probability = 0.85;
  double max_feature_range = 4.0;      // m
  double min_view_cosine = 0.5;        // features are detected up to 60 deg off the surface normal
  double wrong_match_fraction = 0.03;  // monocular only
  double image_margin = 8.0;           // px kept clear at the image border

  // Errors of the initial guesses.
  double model_pose_error_m = 0.3, model_pose_error_deg = 2.0;
  // The camera extrinsic is miscalibrated mostly along the optical axis (the
  // housing standoff is the hardest part to measure), which the survey
  // geometry barely observes without the surface constraint.
  double extrinsic_error_m = 0.015, extrinsic_error_deg = 1.0;
  double start_pose_error_m = 0.05, start_pose_error_deg = 0.2;
  // Where nav.csv's initial poses come from. Dead reckoning composes the
  // noisy odometry (exactly what odometry.csv says; its drift grows without
  // bound, fine for minutes of survey). Online SLAM, as on the HAUV for hours
  // of survey (Ozog et al. use SLAM-corrected poses), gives the truth plus
  // a slowly wandering bounded error of about slam_error_m / slam_error_deg
  // (odometry.csv stays the same noisy relative measurements).
  enum class NavSource { kDeadReckoning, kOnlineSlam };
  NavSource nav_source = NavSource::kDeadReckoning;
  double slam_error_m = 0.3, slam_error_deg = 0.5;
  double slam_correlation_s = 600.0;  // time constant of the SLAM error

  ObjectSet objects = ObjectSet::kDemo;
  int scattered_patches = 0;
  // The second survey of a pair: the placed objects changed (fouling_changes.h).
  FoulingChanges changes;
  bool write_landmarks = false;  // landmarks.csv with noisy initial positions
  // The frame g moved: every position in g (nav, landmarks.csv, the model
  // pose guess, the truth) this far from where the survey is simulated (m;
  // x east, y north, z 0: depth keeps its meaning), as surveys in UTM
  // coordinates arrive (ShiftSurvey, survey_origin.h). Not with images.
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();

  // Camera images (bundle version 2): rendered when the bundle is written.
  bool images = false;
  UnderwaterImagingOptions imaging;  // water, strobe, sensor; image_dropout drops frames

  void Check() const;  // throws OptionError
};

// "demo" (stereo, ~300 keyframes around the keel), "mono" (the same,
// monocular), "curtiss" (full bottom and sides of the 183 m hull, >= 10,000
// keyframes). Throws OptionError for another name.
SurveySimulationOptions SurveyPreset(const std::string& name);
std::vector<std::string> SurveyPresetNames();

struct SimulatedSurvey {
  SurveyBundle bundle;                                               // with truth; model_hint = "hull.ply"
  TriangleMesh cad;                                                  // the CAD hull in M
  std::vector<TriangleMesh> object_meshes;                           // true shapes in M, one per truth object
  std::vector<std::pair<std::int64_t, std::int64_t>> wrong_matches;  // (keyframe, landmark)
  std::vector<std::pair<std::int64_t, int>> dvl_dropouts;            // (keyframe, beam 1..4)
  std::uint64_t albedo_seed = 1;                                     // the true albedo's seed
  std::optional<UnderwaterImagingOptions> imaging;                   // set: images to render (bundle.images lists them)
};

SimulatedSurvey SimulateSurvey(const SurveySimulationOptions& options, Progress& progress);

// Writes the bundle and its mesh (hull.ply, double precision). With
// generator_extras, also DIR.gen/ (generator.json, objects_mesh.json,
// wrong_matches.csv, dvl_dropouts.csv) for ../shared/tools/check-bundle.py.
// With imaging, also renders the images (images/, truth/scene.ply,
// truth/albedo.json; progress and cancellation between images).
void WriteSimulatedSurvey(const SimulatedSurvey& survey, const std::string& dir, bool generator_extras,
                          Progress& progress);
void WriteSimulatedSurvey(const SimulatedSurvey& survey, const std::string& dir, bool generator_extras = false);

}  // namespace hull
