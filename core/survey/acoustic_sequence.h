// Acoustic sequence (imaging sonar), version 1 of the survey contract
// (../shared/survey-format.md, "Acoustic sequence"): the model, its reader,
// writer and validator.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "geometry/pose.h"

namespace hull {

struct SonarSensor {
  double range_min = 0.7;         // m
  double range_max = 5.0;         // m
  double azimuth_fov = 0.5585;    // full field of view, rad (32 deg)
  double elevation_fov = 0.2443;  // full field of view, rad (14 deg)
  double range_sigma = 0.01;      // m
  double azimuth_sigma = 0.0044;  // rad
};

struct SonarMotionNoise {
  double translation_per_metre = 0.05;
  double rotation_per_radian = 0.05;
  double translation_floor = 1e-4;  // m
  double rotation_floor = 1e-4;     // rad
};

// One control row: the commanded motion from step-1 to step, in the frame of step-1.
struct SonarControl {
  std::int64_t step = 0;
  Vector6d u = Vector6d::Zero();
};

struct SonarMeasurement {
  std::int64_t step = 0;
  std::int64_t feature = 0;
  double range = 0;    // m
  double azimuth = 0;  // rad
};

struct SonarTruth {
  std::vector<Vector6d> poses;  // per step 0..T-1
  std::vector<std::int64_t> feature_ids;
  std::vector<Eigen::Vector3d> features;
};

struct AcousticSequence {
  std::string name;
  SonarSensor sensor;
  Vector6d initial_pose = Vector6d::Zero();
  Vector6d initial_pose_sigma = Vector6d::Constant(1e-3);
  SonarMotionNoise motion_noise;
  std::vector<SonarControl> controls;          // steps 1..T-1, in order
  std::vector<SonarMeasurement> measurements;  // sorted by step
  std::optional<SonarTruth> truth;

  int num_steps() const { return static_cast<int>(controls.size()) + 1; }
};

// Reads sonar.json, controls.csv, measurements.csv and the optional truth/
// from a folder. Throws InputError (file, line, column, field) on the first
// problem.
AcousticSequence ReadAcousticSequence(const std::string& dir);
// Collects every problem instead of stopping at the first.
std::vector<Problem> ValidateAcousticSequence(const std::string& dir);
// Writes the folder (atomically per file); reading it back gives an identical sequence.
void WriteAcousticSequence(const AcousticSequence& seq, const std::string& dir);

}  // namespace hull
