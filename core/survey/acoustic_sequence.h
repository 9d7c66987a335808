// Acoustic sequence (imaging sonar), versions 1 and 2 of the survey contract
// (../shared/survey-format.md, "Acoustic sequence" and "Acoustic images"): the
// model, its reader, writer and validator. Version 2 adds one polar image per
// step (images/<step>.png, read with survey/sonar_image.h) and makes
// measurements.csv optional.
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

// The "image" block of sonar.json (version 2): polar intensity images, row i
// the range bin centred at
//   range_min + (i + 0.5) (range_max - range_min) / range_bins   (row 0 nearest),
// column j the beam centred at azimuth
//   -azimuth_fov / 2 + (j + 0.5) azimuth_fov / beams             (column 0 on the left, -y),
// pixel values 8- or 16-bit grey echo intensity (larger is stronger), each
// integrating the returns over the whole elevation aperture.
struct SonarImageFormat {
  int range_bins = 512;  // image rows
  int beams = 128;       // image columns
  double gain_db = 0;    // receiver gain applied before the intensities were stored (informational)

  double RangeBin(const SonarSensor& s) const { return (s.range_max - s.range_min) / range_bins; }  // m per row
  double BeamWidth(const SonarSensor& s) const { return s.azimuth_fov / beams; }                    // rad per column
  // Range of the centre of (fractional) row `row`, and back.
  double RowToRange(const SonarSensor& s, double row) const { return s.range_min + (row + 0.5) * RangeBin(s); }
  double RangeToRow(const SonarSensor& s, double range) const { return (range - s.range_min) / RangeBin(s) - 0.5; }
  // Azimuth of the centre of (fractional) column `col`, and back.
  double ColumnToAzimuth(const SonarSensor& s, double col) const {
    return -s.azimuth_fov / 2 + (col + 0.5) * BeamWidth(s);
  }
  double AzimuthToColumn(const SonarSensor& s, double azimuth) const {
    return (azimuth + s.azimuth_fov / 2) / BeamWidth(s) - 0.5;
  }
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
  // Standard deviations of this measurement (e.g. a detection's, from the
  // image's bin sizes); 0 takes the sensor's. Not part of measurements.csv.
  double range_sigma = 0;    // m
  double azimuth_sigma = 0;  // rad
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
  // Version 2: the image block (images/<step>.png for every step); absent in version 1.
  std::optional<SonarImageFormat> image;
  // False when a version 2 sequence has no measurements.csv (features come
  // from the images); always true in version 1.
  bool has_measurements = true;

  int num_steps() const { return static_cast<int>(controls.size()) + 1; }
};

// Reads sonar.json, controls.csv, measurements.csv and the optional truth/
// from a folder; for version 2 it checks that images/<step>.png exists for
// every step and is a complete grey PNG of the image block's size (the
// pixels are read with ReadSonarImage). Throws
// InputError (file, line, column, field) on the first problem.
AcousticSequence ReadAcousticSequence(const std::string& dir);
// Collects every problem instead of stopping at the first; also decodes every
// image of a version 2 sequence (size, depth, truncation).
std::vector<Problem> ValidateAcousticSequence(const std::string& dir);
// Writes the folder (atomically per file; version 2 when seq.image is set,
// the images themselves with WriteSonarImage); reading it back gives an
// identical sequence.
void WriteAcousticSequence(const AcousticSequence& seq, const std::string& dir);

}  // namespace hull
