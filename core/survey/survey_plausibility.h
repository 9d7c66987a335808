// Plausibility rules of the survey validator (issue 14): values that are
// finite and well-formed yet absurd (a position of 1e30 m, a focal length of
// 2e9 px, a sigma of 2e9, a duplicated odometry edge) are refused with the
// reason, so that nothing absurd reaches GICP, the mesh index or the solver.
// Every rule and its reason is listed in docs/validation.md.
//
// The survey.json rules are checked while parsing (survey_io.cc); the rules
// that need the whole survey (bounds derived from the keyframes' spread and
// the DVL's reach, odometry against nav) run here after reading, and name
// the file, line, column and field through the row places the reader kept.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "survey/survey.h"

namespace hull {

class CsvReader;

namespace plausible {

// survey.json
constexpr std::int64_t kMaxImageSide = 100000;       // px: no camera has a side of 100,000 pixels
constexpr std::int64_t kMaxImagePixels = 100000000;  // px: nor 100 megapixels (survey cameras have up to ~25)
// Acoustic images: range bins x beams of one frame (imaging sonars give up
// to a few thousand samples on up to 1,024 beams).
constexpr std::int64_t kMaxSonarImagePixels = std::int64_t{1} << 23;
constexpr double kMinFocalPerImage = 0.04;   // focal length / larger image side: a 175 deg fisheye
constexpr double kMaxFocalPerImage = 100;    // ... a 0.6 deg telephoto
constexpr double kMaxLeverArm = 50;          // m: sensor offsets on the vehicle
constexpr double kMaxFixedAngle = 2 * M_PI;  // rad: a fixed rotation needs at most one turn
// Positions: no survey coordinate beyond 1e7 m (UTM northings reach 1e7);
// PCL and Embree work in float, and squared distances of 1e30 overflow it.
constexpr double kMaxCoordinate = 1e7;
// nav.csv
constexpr double kMaxUnwrappedYaw = 64 * M_PI;  // rad: an unwrapped heading of up to 32 turns
constexpr double kMaxDepth = 11000;             // m: the deepest ocean
constexpr double kMaxTime = 1e10;               // s: Unix time reaches 1e10 s in the year 2286
// The position bound: |p - median| <= kSpreadFactor * (90th percentile of
// the keyframes' distances to their median) + 2 * DVL reach + kSpreadMargin.
constexpr double kSpreadFactor = 4;
constexpr double kSpreadMargin = 50;  // m
// The DVL's reach: a return is plausible up to max(kDvlRangeFactor * the
// median return, kDvlMinReach); the reach is the largest plausible return.
constexpr double kDvlRangeFactor = 20;
constexpr double kDvlMinReach = 50;  // m
// Odometry against consecutive nav poses: within kOdometrySigmas sigmas of
// the survey's odometry drift rates times the time between them, and never
// closer than these floors (nav may come from a SLAM filter, not the
// odometry itself).
constexpr double kOdometrySigmas = 100;
constexpr double kOdometryFloorM = 1.0;
constexpr double kOdometryFloorRad = 0.35;  // 20 deg

// A noise parameter's plausible range and why.
struct SigmaBound {
  const char* key;
  double lo, hi;
  std::string why;
};
// The bounds of survey.json's "noise" block; image: the larger image side (px).
std::vector<SigmaBound> NoiseBounds(double image);
// The field of NoiseModel named by a NoiseBounds key.
double& NoiseField(NoiseModel& n, std::string_view key);

}  // namespace plausible

// Where the rows of one CSV file were read: the plausibility rules name the
// file, line, column and field of the row at fault.
class CsvRowPlaces {
 public:
  CsvRowPlaces() = default;
  CsvRowPlaces(std::string file, std::vector<std::string> fields)
      : file_(std::move(file)), fields_(std::move(fields)) {}
  // Records the current row of r; cols[i] is the column index of fields[i].
  void Add(const CsvReader& r, const int* cols);
  std::size_t rows() const { return lines_.size(); }
  // Field i (an index into the fields given) of row `row`.
  SourceLocation Where(std::size_t row, int field) const;
  // The row's line, or 0 for a row not read from a file.
  int Line(std::size_t row) const { return row < lines_.size() ? lines_[row] : 0; }

 private:
  std::string file_;
  std::vector<std::string> fields_;
  std::vector<int> lines_;
  std::vector<int> columns_;  // rows x fields
};

// The places of the rows in SurveyBundle's vectors, in the same order.
struct SurveyPlaces {
  // The files and fields of a bundle folder, with no row yet (the reader
  // adds them; for a bundle built in memory, problems name file and field).
  static SurveyPlaces ForBundle(const std::string& dir);

  CsvRowPlaces nav;        // fields: t x y z roll pitch yaw depth roll_meas pitch_meas servo
  CsvRowPlaces odometry;   // fields: from to dx dy dz droll dpitch dyaw
  CsvRowPlaces dvl;        // fields: r1 r2 r3 r4
  CsvRowPlaces landmarks;  // fields: x y z
  SourceLocation model_pose_guess;
};

// The rules that need the whole survey; appends one Problem per finding.
void CheckSurveyPlausibility(const SurveyBundle& bundle, const SurveyPlaces& places, std::vector<Problem>& out);

// The position bound of the rules above: the median keyframe position and
// the radius about it (also used to bound landmarks and the model pose).
struct SurveyExtent {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double spread = 0;     // 90th percentile of the keyframes' distances to centre (m)
  double dvl_reach = 0;  // largest plausible DVL return (m)
  double radius = 0;     // the bound
};
SurveyExtent ComputeSurveyExtent(const SurveyBundle& bundle);

}  // namespace hull
