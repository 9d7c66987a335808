#include "survey/survey_plausibility.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "base/csv.h"

namespace hull {
namespace plausible {

std::vector<SigmaBound> NoiseBounds(double image) {
  return {
      {"pixel_sigma", 1e-3, 0.05 * image, "a feature's pixel error, from a thousandth of a pixel to 5 % of the image"},
      {"dvl_range_sigma", 1e-5, 10, "a DVL range error (m), from 10 um to 10 m"},
      {"depth_sigma", 1e-5, 100, "a depth sensor's error (m), from 10 um to 100 m"},
      {"roll_pitch_sigma", 1e-7, M_PI, "an attitude error (rad), at most half a turn"},
      {"servo_sigma", 1e-7, M_PI, "a servo angle error (rad), at most half a turn"},
      {"odometry_translation_rate", 1e-7, 10, "an odometry drift rate (m/s), at most 10 m/s"},
      {"odometry_rotation_rate", 1e-9, M_PI, "an odometry heading drift rate (rad/s), at most half a turn a second"},
      {"model_pose_sigma", 1e-6, 1000, "a prior on the model pose (m, rad); one broader than 1 km is no prior"},
  };
}

double& NoiseField(NoiseModel& n, std::string_view key) {
  if (key == "pixel_sigma") return n.pixel_sigma;
  if (key == "dvl_range_sigma") return n.dvl_range_sigma;
  if (key == "depth_sigma") return n.depth_sigma;
  if (key == "roll_pitch_sigma") return n.roll_pitch_sigma;
  if (key == "servo_sigma") return n.servo_sigma;
  if (key == "odometry_translation_rate") return n.odometry_translation_rate;
  if (key == "odometry_rotation_rate") return n.odometry_rotation_rate;
  return n.model_pose_sigma;
}

}  // namespace plausible

void CsvRowPlaces::Add(const CsvReader& r, const int* cols) {
  lines_.push_back(r.line());
  for (std::size_t i = 0; i < fields_.size(); ++i) columns_.push_back(r.Where(cols[i]).column);
}

SourceLocation CsvRowPlaces::Where(std::size_t row, int field) const {
  const auto f = static_cast<std::size_t>(field);
  if (f >= fields_.size()) return {file_, 0, 0, ""};
  if (row >= lines_.size()) return {file_, 0, 0, fields_[f] + " of row " + std::to_string(row + 1)};
  return {file_, lines_[row], columns_[row * fields_.size() + static_cast<std::size_t>(field)],
          fields_[static_cast<std::size_t>(field)]};
}

SurveyPlaces SurveyPlaces::ForBundle(const std::string& dir) {
  auto at = [&dir](const char* file) { return (std::filesystem::path(dir) / file).string(); };
  SurveyPlaces p;
  p.nav = CsvRowPlaces(at("nav.csv"),
                       {"t", "x", "y", "z", "roll", "pitch", "yaw", "depth", "roll_meas", "pitch_meas", "servo"});
  p.odometry = CsvRowPlaces(at("odometry.csv"), {"from", "to", "dx", "dy", "dz", "droll", "dpitch", "dyaw"});
  p.dvl = CsvRowPlaces(at("dvl.csv"), {"r1", "r2", "r3", "r4"});
  p.landmarks = CsvRowPlaces(at("landmarks.csv"), {"x", "y", "z"});
  p.model_pose_guess = {at("survey.json"), 0, 0, "model_pose_guess"};
  return p;
}

namespace {

using plausible::kMaxCoordinate;

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

std::string F(double v) { return FormatDouble(v); }
std::string Fixed(double v, int digits = 1) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
  return buf;
}

// The DVL returns' plausible limit: kDvlRangeFactor times the median return.
double DvlLimit(const SurveyBundle& b) {
  std::vector<double> all;
  for (const auto& d : b.dvl) {
    for (double r : d.range) {
      if (DvlRecord::HasReturn(r)) all.push_back(r);
    }
  }
  return std::max(plausible::kDvlRangeFactor * Quantile(all, 0.5), plausible::kDvlMinReach);
}

class Checker {
 public:
  Checker(const SurveyBundle& b, const SurveyPlaces& places, std::vector<Problem>& out)
      : b_(b), at_(places), out_(out), extent_(ComputeSurveyExtent(b)) {}

  void Run() {
    Nav();
    Dvl();
    Odometry();
    Landmarks();
    ModelPose();
  }

 private:
  void Error(const SourceLocation& where, const std::string& message) {
    out_.push_back({where, message, Severity::kError});
  }

  std::string BoundReason() const {
    return "the keyframes lie within " + Fixed(extent_.spread) + " m of their median position (90 %) and the DVL " +
           "reaches " + Fixed(extent_.dvl_reach) + " m, which bounds plausible positions at " + Fixed(extent_.radius) +
           " m from it";
  }

  // A position (or its coordinates) beyond the survey's bound; returns
  // whether it was refused. fields: the place fields of x, y, z.
  bool CheckPosition(const CsvRowPlaces& places, std::size_t row, const int* fields, const Eigen::Vector3d& p,
                     const std::string& what) {
    for (int k = 0; k < 3; ++k) {
      if (!(std::abs(p[k]) <= kMaxCoordinate)) {
        Error(places.Where(row, fields[k]), F(p[k]) + " m is not a plausible coordinate of " + what +
                                                ": expected at most " + F(kMaxCoordinate) +
                                                " m in magnitude (no survey spans more; the libraries work in float)");
        return true;
      }
    }
    const Eigen::Vector3d d = p - extent_.centre;
    if (d.norm() <= extent_.radius) return false;
    int k = 0;
    d.cwiseAbs().maxCoeff(&k);
    Error(places.Where(row, fields[k]),
          "places " + what + " " + Fixed(d.norm()) + " m from the survey's median keyframe position; " + BoundReason());
    return true;
  }

  void Nav() {
    // Fields of places.nav: 0 t, 1 x, 2 y, 3 z, 4 roll, 5 pitch, 6 yaw, 7 depth, 8 roll_meas, 9 pitch_meas, 10 servo.
    static const int kXyz[3] = {1, 2, 3};
    bad_nav_.assign(b_.nav.size(), 0);
    for (std::size_t i = 0; i < b_.nav.size(); ++i) {
      const NavRecord& n = b_.nav[i];
      const std::string what = "keyframe " + std::to_string(n.keyframe);
      bool bad = false;
      if (!(std::abs(n.t) <= plausible::kMaxTime)) {
        Error(at_.nav.Where(i, 0), F(n.t) + " s is not a plausible time: expected at most " + F(plausible::kMaxTime) +
                                       " s in magnitude (Unix time reaches that in 2286)");
        bad = true;
      }
      bad = CheckPosition(at_.nav, i, kXyz, n.x_gv.head<3>(), what) || bad;
      const double angle_limits[3] = {plausible::kMaxFixedAngle, plausible::kMaxFixedAngle,
                                      plausible::kMaxUnwrappedYaw};
      for (int k = 0; k < 3; ++k) {
        if (!(std::abs(n.x_gv[3 + k]) <= angle_limits[k])) {
          Error(at_.nav.Where(i, 4 + k), F(n.x_gv[3 + k]) + " rad is not a plausible angle: expected at most " +
                                             F(angle_limits[k]) + (k == 2 ? " (32 turns of unwrapped heading)" : "") +
                                             " in magnitude; angles are radians");
          bad = true;
        }
      }
      if (!(std::abs(n.depth) <= plausible::kMaxDepth)) {
        Error(at_.nav.Where(i, 7), F(n.depth) + " m is not a plausible depth: expected at most " +
                                       F(plausible::kMaxDepth) + " m in magnitude (the deepest ocean)");
        bad = true;
      }
      const double meas[3] = {n.roll_meas, n.pitch_meas, n.servo};
      for (int k = 0; k < 3; ++k) {
        if (!(std::abs(meas[k]) <= plausible::kMaxFixedAngle)) {
          Error(at_.nav.Where(i, 8 + k), F(meas[k]) +
                                             " rad is not a plausible angle: expected at most 2 pi in "
                                             "magnitude; angles are radians");
          bad = true;
        }
      }
      bad_nav_[i] = bad;
    }
  }

  void Dvl() {
    const double limit = DvlLimit(b_);
    for (std::size_t i = 0; i < b_.dvl.size(); ++i) {
      for (int k = 0; k < 4; ++k) {
        const double r = b_.dvl[i].range[static_cast<std::size_t>(k)];
        if (!DvlRecord::HasReturn(r) || r <= limit) continue;
        Error(at_.dvl.Where(i, k), F(r) +
                                       " m is not a plausible DVL range: the survey's median return bounds them at " +
                                       Fixed(limit) + " m (" + F(plausible::kDvlRangeFactor) + " times the median, " +
                                       "at least " + F(plausible::kDvlMinReach) + " m)");
      }
    }
  }

  void Odometry() {
    // Fields of places.odometry: 0 from, 1 to, 2 dx .. 7 dyaw.
    const auto index = b_.KeyframeIndex();
    std::map<std::pair<std::int64_t, std::int64_t>, std::size_t> seen;
    const NoiseModel& nz = b_.manifest.noise;
    for (std::size_t e = 0; e < b_.odometry.size(); ++e) {
      const OdometryRecord& o = b_.odometry[e];
      const auto key = std::minmax(o.from, o.to);
      auto [it, fresh] = seen.emplace(key, e);
      if (!fresh) {
        Error(at_.odometry.Where(e, 1), "the odometry edge " + std::to_string(o.from) + " -> " + std::to_string(o.to) +
                                            " duplicates line " + std::to_string(at_.odometry.Line(it->second)) +
                                            " (the same pair of keyframes); a measurement counted twice weighs "
                                            "double, so each pair may appear once");
        continue;
      }
      bool bad = false;
      for (int k = 0; k < 3 && !bad; ++k) {
        if (!(std::abs(o.z[k]) <= 2 * extent_.radius + plausible::kSpreadMargin)) {
          Error(at_.odometry.Where(e, 2 + k),
                F(o.z[k]) + " m is not a plausible motion between two keyframes; " + BoundReason());
          bad = true;
        }
        if (!(std::abs(o.z[3 + k]) <= plausible::kMaxUnwrappedYaw)) {
          Error(at_.odometry.Where(e, 5 + k), F(o.z[3 + k]) +
                                                  " rad is not a plausible rotation between two "
                                                  "keyframes; angles are radians");
          bad = true;
        }
      }
      const auto fi = index.find(o.from), ti = index.find(o.to);
      if (bad || fi == index.end() || ti == index.end()) continue;
      const std::size_t i = static_cast<std::size_t>(fi->second), j = static_cast<std::size_t>(ti->second);
      const std::size_t lo = std::min(i, j), hi = std::max(i, j);
      if (hi != lo + 1 || bad_nav_[i] || bad_nav_[j]) continue;  // consecutive poses, both plausible
      const NavRecord &a = b_.nav[i], &c = b_.nav[j];
      const Pose predicted = Pose::FromVector(a.x_gv).Inverse() * Pose::FromVector(c.x_gv);
      const Pose measured = Pose::FromVector(o.z);
      const double dt = std::abs(c.t - a.t);
      const double moved = (predicted.translation() - measured.translation()).norm();
      const double turned = Pose::AngleBetween(predicted, measured);
      const double tol_m =
          std::max(plausible::kOdometryFloorM, plausible::kOdometrySigmas * nz.odometry_translation_rate * dt);
      const double tol_rad =
          std::max(plausible::kOdometryFloorRad, plausible::kOdometrySigmas * nz.odometry_rotation_rate * dt);
      if (moved <= tol_m && turned <= tol_rad) continue;
      const bool by_translation = moved / tol_m >= turned / tol_rad;
      Error(at_.odometry.Where(e, by_translation ? 2 : 7),
            "odometry " + std::to_string(o.from) + " -> " + std::to_string(o.to) + " disagrees with nav.csv lines " +
                std::to_string(at_.nav.Line(i)) + " and " + std::to_string(at_.nav.Line(j)) + " by " +
                (by_translation ? Fixed(moved, 3) + " m" : Fixed(turned * 180 / M_PI, 2) + " deg") +
                "; consecutive poses must agree with their odometry within " + F(plausible::kOdometrySigmas) +
                " sigmas of the noise block's drift rates over " + Fixed(dt, 3) + " s (at least " +
                (by_translation ? F(plausible::kOdometryFloorM) + " m" : "20 deg") +
                "); one of the two files is wrong");
    }
  }

  void Landmarks() {
    if (!b_.landmarks) return;
    static const int kXyz[3] = {0, 1, 2};
    for (std::size_t i = 0; i < b_.landmarks->size(); ++i) {
      const LandmarkRecord& l = (*b_.landmarks)[i];
      CheckPosition(at_.landmarks, i, kXyz, l.p, "landmark " + std::to_string(l.landmark));
    }
  }

  void ModelPose() {
    if (!b_.manifest.model_pose_guess || b_.nav.empty()) return;
    // The model frame's origin may lie anywhere on the hull (often the
    // stern), so the bound widens by the longest hull afloat.
    constexpr double kLongestHull = 500;
    const Eigen::Vector3d t = b_.manifest.model_pose_guess->head<3>();
    const double d = (t - extent_.centre).norm();
    if (d <= extent_.radius + kLongestHull) return;
    Error(at_.model_pose_guess, "places the model " + Fixed(d) + " m from the survey's median keyframe position; " +
                                    BoundReason() + ", and the model's origin may lie up to " + F(kLongestHull) +
                                    " m (the longest hull) beyond");
  }

  const SurveyBundle& b_;
  const SurveyPlaces& at_;
  std::vector<Problem>& out_;
  SurveyExtent extent_;
  std::vector<char> bad_nav_;
};

}  // namespace

SurveyExtent ComputeSurveyExtent(const SurveyBundle& b) {
  SurveyExtent e;
  if (b.nav.empty()) return e;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> c;
    c.reserve(b.nav.size());
    for (const auto& n : b.nav) c.push_back(n.x_gv[k]);
    e.centre[k] = Quantile(std::move(c), 0.5);
  }
  std::vector<double> d;
  d.reserve(b.nav.size());
  for (const auto& n : b.nav) d.push_back((n.x_gv.head<3>() - e.centre).norm());
  e.spread = Quantile(std::move(d), 0.9);
  // The reach: the largest plausible return.
  const double limit = DvlLimit(b);
  for (const auto& r : b.dvl) {
    for (double v : r.range) {
      if (DvlRecord::HasReturn(v) && v <= limit) e.dvl_reach = std::max(e.dvl_reach, v);
    }
  }
  e.radius = plausible::kSpreadFactor * e.spread + 2 * e.dvl_reach + plausible::kSpreadMargin;
  return e;
}

void CheckSurveyPlausibility(const SurveyBundle& bundle, const SurveyPlaces& places, std::vector<Problem>& out) {
  Checker(bundle, places, out).Run();
}

}  // namespace hull
