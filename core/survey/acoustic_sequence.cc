// Reader, validator and writer of the acoustic sequence, versions 1 and 2
// (../shared/survey-format.md, "Acoustic sequence" and "Acoustic images").
//
// One implementation serves both ReadAcousticSequence (stop at the first
// problem: throw InputError) and ValidateAcousticSequence (collect every
// problem): every rule reports through a ProblemSink that either throws or
// records. Row-level errors raised by CsvReader (bad numbers, NaN, short
// rows) are caught per row when collecting, so one bad line does not hide
// the next.
#include "survey/acoustic_sequence.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "survey/sonar_image.h"
#include "survey/survey_plausibility.h"

namespace hull {
namespace {

namespace fs = std::filesystem;

// Plausibility bounds of an acoustic sequence (issue 23): finite values that
// no imaging sonar or vehicle gives, refused with the reason before they
// reach the filter (a sigma of 1e19 or a turn of 1e308 rad per step broke
// its arithmetic). Listed in docs/validation.md.
constexpr double kMaxSonarRange = 1000;        // m: imaging sonars reach about 100 m
constexpr double kMaxPoseSigma = 1000;         // m: an initial position known to within a kilometre
constexpr double kMaxAngleSigma = 2 * M_PI;    // rad: one turn
constexpr double kMaxStepTranslation = 1000;   // m per step
constexpr double kMaxStepRotation = 2 * M_PI;  // rad per step
constexpr double kMaxNoiseRate = 10;           // motion noise per metre or radian: 1000 %
constexpr double kMaxTranslationFloor = 100;   // m per step
constexpr double kMaxPosition = 1e7;           // m: UTM northings reach 1e7
constexpr double kMaxAngle = 64 * M_PI;        // rad: an unwrapped angle of 32 turns

constexpr const char* kFormat = "hull-sonar";
constexpr int kVersion = 1;       // without images
constexpr int kImageVersion = 2;  // with the image block and images/
// Beyond this many problems per file the validator stops reading it.
constexpr int kMaxProblemsPerFile = 50;

class ProblemSink {
 public:
  explicit ProblemSink(std::vector<Problem>* collect) : collect_(collect) {}
  bool collecting() const { return collect_ != nullptr; }
  void Report(SourceLocation where, const std::string& message) {
    if (!collect_) throw InputError(std::move(where), message);
    ++per_file_[where.file];
    collect_->push_back({std::move(where), message, Severity::kError});
  }
  void Report(const InputError& e) { Report(e.where(), e.detail()); }
  bool TooMany(const std::string& file) const {
    auto it = per_file_.find(file);
    return it != per_file_.end() && it->second >= kMaxProblemsPerFile;
  }
  std::size_t count() const { return collect_ ? collect_->size() : 0; }

 private:
  std::vector<Problem>* collect_;
  std::map<std::string, int> per_file_;
};

std::string Join(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

// Runs fn(); when collecting, an InputError becomes a problem and false is returned.
template <typename Fn>
bool Guard(ProblemSink& sink, Fn&& fn) {
  if (!sink.collecting()) {
    fn();
    return true;
  }
  try {
    fn();
    return true;
  } catch (const InputError& e) {
    sink.Report(e);
    return false;
  }
}

// Reads a whole file; a missing required file is a problem naming it.
// max_bytes: what the file's rows can hold (kMaxFileBytes: no bound of its own).
std::optional<std::string> ReadRequired(ProblemSink& sink, const std::string& path,
                                        std::uint64_t max_bytes = kMaxFileBytes, const std::string& reason = "") {
  if (!fs::exists(path)) {
    sink.Report({path, 0, 0, ""}, "the file is missing; the acoustic sequence requires it");
    return std::nullopt;
  }
  std::optional<std::string> text;
  Guard(sink, [&] { text = ReadFileToString(path, max_bytes, reason); });
  return text;
}

// Iterates the rows of a CSV file; per-row errors are reported and the row skipped.
template <typename RowFn>
void ForEachRow(ProblemSink& sink, CsvReader& csv, RowFn&& row) {
  while (true) {
    if (sink.TooMany(csv.file())) {
      sink.Report({csv.file(), csv.line(), 0, ""}, "too many problems; the rest of the file was not checked");
      return;
    }
    bool more = false;
    if (!Guard(sink, [&] { more = csv.Next(); })) continue;
    if (!more) return;
    Guard(sink, [&] { row(); });
  }
}

// ---------------------------------------------------------------------------
// sonar.json

// format and version: false when the file is another format or version
// (its other keys then mean nothing here); version 2 gives seq.image.
bool ReadHeader(ProblemSink& sink, const JsonReader& r, AcousticSequence& seq) {
  bool header_ok = true;
  Guard(sink, [&] {
    const std::string format = r.String("format");
    if (format != kFormat) {
      header_ok = false;
      r.Fail(r.Required("format"), "format",
             "format is \"" + format + "\"; expected \"" + kFormat + "\" (an acoustic sequence)");
    }
  });
  Guard(sink, [&] {
    const Json& v = r.Required("version");
    if (!v.is_integer()) r.Fail(v, "version", "expected an integer version");
    const auto version = static_cast<std::int64_t>(v.as_number());
    if (version != kVersion && version != kImageVersion) {
      header_ok = false;
      r.Fail(v, "version",
             "unknown version " + FormatDouble(v.as_number()) + "; this reader knows versions " +
                 std::to_string(kVersion) + " and " + std::to_string(kImageVersion));
    }
    if (version == kImageVersion) seq.image = SonarImageFormat();
  });
  return header_ok;
}

// The image block of version 2: the frame's size within what sonars give.
void ReadImageBlock(ProblemSink& sink, const JsonReader& r, AcousticSequence& seq) {
  if (seq.image) {
    Guard(sink, [&] {
      const JsonReader im = r.Object("image");
      auto count = [&](std::string_view key, int& out) {
        Guard(sink, [&] {
          const std::int64_t n = im.Integer(key);
          if (n < 1 || n > 65535) {
            im.Fail(im.Required(key), key, "must be between 1 and 65535, got " + std::to_string(n));
          }
          out = static_cast<int>(n);
        });
      };
      count("range_bins", seq.image->range_bins);
      count("beams", seq.image->beams);
      const std::int64_t pixels = std::int64_t{seq.image->range_bins} * seq.image->beams;
      if (pixels > plausible::kMaxSonarImagePixels) {
        Guard(sink, [&] {
          im.Fail(im.Required("beams"), "beams",
                  std::to_string(seq.image->range_bins) + " range bins x " + std::to_string(seq.image->beams) +
                      " beams is " + std::to_string(pixels) + " samples a frame; expected at most " +
                      std::to_string(plausible::kMaxSonarImagePixels) +
                      " (imaging sonars give a few thousand "
                      "samples on up to 1,024 beams)");
        });
      }
      Guard(sink, [&] { seq.image->gain_db = im.NumberOr("gain_db", 0.0); });
    });
  } else if (r.Has("image")) {
    Guard(sink, [&] { r.Fail(r.Required("image"), "image", "an image block needs \"version\": 2 (acoustic images)"); });
  }
}

// The sensor: its window, fields of view and measurement sigmas, plausible.
void ReadSensor(ProblemSink& sink, const JsonReader& r, AcousticSequence& seq) {
  Guard(sink, [&] {
    const JsonReader s = r.Object("sensor");
    SonarSensor& q = seq.sensor;
    auto positive = [&](std::string_view key, double& out) {
      Guard(sink, [&] {
        out = s.Number(key);
        if (!(out > 0)) s.Fail(s.Required(key), key, "must be positive, got " + FormatDouble(out));
      });
    };
    positive("range_min", q.range_min);
    positive("range_max", q.range_max);
    positive("azimuth_fov", q.azimuth_fov);
    positive("elevation_fov", q.elevation_fov);
    positive("range_sigma", q.range_sigma);
    positive("azimuth_sigma", q.azimuth_sigma);
    auto at_most = [&](std::string_view key, double value, double bound, const std::string& why) {
      if (s.Has(key) && value > bound) {
        sink.Report(s.Where(s.Required(key), std::string(key)),
                    std::string(key) + " " + FormatDouble(value) + " is implausible: " + why);
      }
    };
    at_most("range_max", q.range_max, kMaxSonarRange,
            "no imaging sonar reaches " + FormatDouble(kMaxSonarRange) + " m");
    at_most("range_sigma", q.range_sigma, std::max(0.0, q.range_max - q.range_min),
            "a range standard deviation must not exceed the range window range_max - range_min");
    at_most("azimuth_sigma", q.azimuth_sigma, q.azimuth_fov,
            "an azimuth standard deviation must not exceed the field of view azimuth_fov");
    if (s.Has("range_max") && q.range_max <= q.range_min) {
      sink.Report(s.Where(s.Required("range_max"), "range_max"),
                  "range_max " + FormatDouble(q.range_max) + " must exceed range_min " + FormatDouble(q.range_min));
    }
    if (s.Has("azimuth_fov") && q.azimuth_fov >= 2 * M_PI) {
      sink.Report(s.Where(s.Required("azimuth_fov"), "azimuth_fov"),
                  "the full azimuth field of view must be below 2 pi rad, got " + FormatDouble(q.azimuth_fov));
    }
    if (s.Has("elevation_fov") && q.elevation_fov >= M_PI) {
      sink.Report(s.Where(s.Required("elevation_fov"), "elevation_fov"),
                  "the full elevation field of view must be below pi rad, got " + FormatDouble(q.elevation_fov));
    }
  });
}

// initial_pose and initial_pose_sigma within the survey's bounds.
void ReadInitialPose(ProblemSink& sink, const JsonReader& r, AcousticSequence& seq) {
  Guard(sink, [&] {
    const std::vector<double> v = r.Numbers("initial_pose", 6);
    for (int i = 0; i < 6; ++i) {
      const double bound = i < 3 ? kMaxPosition : kMaxAngle;
      if (std::fabs(v[static_cast<std::size_t>(i)]) > bound) {
        r.Fail(r.Required("initial_pose"), "initial_pose",
               "entry " + std::to_string(i + 1) + " (" + FormatDouble(v[static_cast<std::size_t>(i)]) +
                   ") is implausible: beyond " + FormatDouble(bound) + (i < 3 ? " m" : " rad"));
      }
    }
    seq.initial_pose = Eigen::Map<const Vector6d>(v.data());
  });
  Guard(sink, [&] {
    const std::vector<double> v = r.Numbers("initial_pose_sigma", 6);
    for (int i = 0; i < 6; ++i) {
      const double x = v[static_cast<std::size_t>(i)];
      if (!(x > 0)) {
        r.Fail(r.Required("initial_pose_sigma"), "initial_pose_sigma",
               "every standard deviation must be positive, got " + FormatDouble(x));
      }
      const double bound = i < 3 ? kMaxPoseSigma : kMaxAngleSigma;
      if (x > bound) {
        r.Fail(r.Required("initial_pose_sigma"), "initial_pose_sigma",
               "entry " + std::to_string(i + 1) + " (" + FormatDouble(x) + ") is implausible: at most " +
                   FormatDouble(bound) + (i < 3 ? " m (a position known to within a kilometre)" : " rad (a turn)"));
      }
    }
    seq.initial_pose_sigma = Eigen::Map<const Vector6d>(v.data());
  });
}

// motion_noise: rates and floors of the odometry's noise.
void ReadMotionNoise(ProblemSink& sink, const JsonReader& r, AcousticSequence& seq) {
  Guard(sink, [&] {
    const JsonReader m = r.Object("motion_noise");
    SonarMotionNoise& q = seq.motion_noise;
    auto non_negative = [&](std::string_view key, double& out, bool required, double bound, const char* why) {
      Guard(sink, [&] {
        out = required ? m.Number(key) : m.NumberOr(key, out);
        if (out < 0) m.Fail(m.Required(key), key, "must not be negative, got " + FormatDouble(out));
        if (out > bound) {
          m.Fail(m.Required(key), key,
                 FormatDouble(out) + " is implausible: at most " + FormatDouble(bound) + " (" + why + ")");
        }
      });
    };
    non_negative("translation_per_metre", q.translation_per_metre, true, kMaxNoiseRate, "1000 % of the motion");
    non_negative("rotation_per_radian", q.rotation_per_radian, true, kMaxNoiseRate, "1000 % of the motion");
    non_negative("translation_floor", q.translation_floor, false, kMaxTranslationFloor, "m per step");
    non_negative("rotation_floor", q.rotation_floor, false, kMaxAngleSigma, "rad per step: a turn");
  });
}

void ReadManifest(ProblemSink& sink, const std::string& dir, AcousticSequence& seq) {
  const std::string path = Join(dir, "sonar.json");
  const std::optional<std::string> text = ReadRequired(sink, path);
  if (!text) return;
  Json doc;
  if (!Guard(sink, [&] { doc = Json::Parse(*text, path); })) return;
  // Each top-level rule in its own guard so the validator sees them all.
  std::optional<JsonReader> root;
  if (!Guard(sink, [&] { root.emplace(doc, path); })) return;
  const JsonReader& r = *root;
  if (!ReadHeader(sink, r, seq)) return;
  ReadImageBlock(sink, r, seq);
  Guard(sink, [&] {
    if (auto name = r.OptionalString("name")) seq.name = *name;
  });
  ReadSensor(sink, r, seq);
  ReadInitialPose(sink, r, seq);
  ReadMotionNoise(sink, r, seq);
}

// ---------------------------------------------------------------------------
// CSV files

struct StepRow {
  std::int64_t step;
  int line;
  int column;  // of the step field
};

// Checks that the rows' steps run from `first` upwards without a gap or a
// repeat (in any row order); a gap is reported on the line of the step after it.
void CheckContiguous(ProblemSink& sink, const std::string& file, std::vector<StepRow> rows, std::int64_t first,
                     const std::string& what) {
  std::stable_sort(rows.begin(), rows.end(), [](const StepRow& a, const StepRow& b) { return a.step < b.step; });
  std::int64_t expected = first;
  for (const StepRow& r : rows) {
    if (r.step < expected) {
      sink.Report({file, r.line, r.column, "step"}, "step " + std::to_string(r.step) + " appears twice; " + what);
      continue;
    }
    if (r.step > expected) {
      const std::string missing = r.step == expected + 1 ? "step " + std::to_string(expected) + " is missing"
                                                         : "steps " + std::to_string(expected) + ".." +
                                                               std::to_string(r.step - 1) + " are missing";
      sink.Report({file, r.line, r.column, "step"}, missing + " before step " + std::to_string(r.step) + "; " + what);
    }
    expected = r.step + 1;
  }
}

// Returns false when the file could not be read at all (the step count is then unknown).
bool ReadControls(ProblemSink& sink, const std::string& dir, AcousticSequence& seq) {
  const std::string path = Join(dir, "controls.csv");
  // One row per step, seven numbers: 256 MiB hold over a million steps.
  const std::optional<std::string> text =
      ReadRequired(sink, path, std::uint64_t{256} << 20, "a control row per step can need (over a million steps)");
  if (!text) return false;
  std::optional<CsvReader> csv;
  if (!Guard(sink, [&] { csv.emplace(*text, path); })) return false;
  int col[7];
  const char* names[7] = {"step", "dx", "dy", "dz", "droll", "dpitch", "dyaw"};
  bool header_ok = true;
  for (int i = 0; i < 7; ++i) {
    if (!Guard(sink, [&] { col[i] = csv->Require(names[i]); })) header_ok = false;
  }
  if (!header_ok) return false;
  std::vector<StepRow> rows;
  ForEachRow(sink, *csv, [&] {
    SonarControl c;
    c.step = csv->Int(col[0]);
    for (int i = 0; i < 6; ++i) {
      c.u[i] = csv->Double(col[i + 1]);
      const double bound = i < 3 ? kMaxStepTranslation : kMaxStepRotation;
      if (std::fabs(c.u[i]) > bound) {
        csv->Fail(col[i + 1], std::string(names[i + 1]) + " " + FormatDouble(c.u[i]) + " is implausible: at most " +
                                  FormatDouble(bound) + (i < 3 ? " m per step" : " rad per step (a turn)"));
      }
    }
    if (c.step < 1)
      csv->Fail(col[0], "control steps start at 1 (step 0 has no control row), got " + std::to_string(c.step));
    rows.push_back({c.step, csv->line(), csv->Where(col[0]).column});
    seq.controls.push_back(c);
  });
  CheckContiguous(sink, path, rows, 1, "controls.csv must give steps 1..T-1, one row each");
  std::stable_sort(seq.controls.begin(), seq.controls.end(),
                   [](const SonarControl& a, const SonarControl& b) { return a.step < b.step; });
  // Keep the contiguous prefix only (a reader that throws never gets here with a gap).
  std::vector<SonarControl> clean;
  for (const SonarControl& c : seq.controls) {
    if (c.step == static_cast<std::int64_t>(clean.size()) + 1) clean.push_back(c);
  }
  seq.controls = std::move(clean);
  return true;
}

void ReadTruth(ProblemSink& sink, const std::string& dir, bool steps_known, AcousticSequence& seq) {
  const std::string poses_path = Join(dir, "truth/poses.csv");
  const std::string features_path = Join(dir, "truth/features.csv");
  const bool has_poses = fs::exists(poses_path), has_features = fs::exists(features_path);
  if (!has_poses && !has_features) return;
  SonarTruth truth;
  const std::int64_t T = seq.num_steps();
  if (has_poses) {
    std::optional<std::string> text = ReadRequired(sink, poses_path);
    std::optional<CsvReader> csv;
    if (text && Guard(sink, [&] { csv.emplace(*text, poses_path); })) {
      int col[7];
      const char* names[7] = {"step", "x", "y", "z", "roll", "pitch", "yaw"};
      bool header_ok = true;
      for (int i = 0; i < 7; ++i) {
        if (!Guard(sink, [&] { col[i] = csv->Require(names[i]); })) header_ok = false;
      }
      if (header_ok) {
        std::vector<std::pair<std::int64_t, Vector6d>> poses;
        std::vector<StepRow> rows;
        ForEachRow(sink, *csv, [&] {
          const std::int64_t step = csv->Int(col[0]);
          Vector6d x;
          for (int i = 0; i < 6; ++i) x[i] = csv->Double(col[i + 1]);
          if (step < 0 || (steps_known && step >= T)) {
            csv->Fail(col[0], "step " + std::to_string(step) + " does not exist; the sequence has steps 0.." +
                                  std::to_string(T - 1) + " (controls.csv)");
          }
          rows.push_back({step, csv->line(), csv->Where(col[0]).column});
          poses.emplace_back(step, x);
        });
        const std::size_t before = sink.count();
        CheckContiguous(sink, poses_path, rows, 0, "truth/poses.csv must give steps 0..T-1, one row each");
        if (steps_known && static_cast<std::int64_t>(poses.size()) < T && sink.count() == before) {
          sink.Report({poses_path, csv->line(), 0, "step"},
                      "the file ends at step " + std::to_string(static_cast<std::int64_t>(poses.size()) - 1) +
                          "; truth/poses.csv must give steps 0.." + std::to_string(T - 1));
        }
        std::stable_sort(poses.begin(), poses.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [step, x] : poses) {
          if (step == static_cast<std::int64_t>(truth.poses.size())) truth.poses.push_back(x);
        }
      }
    }
  }
  if (has_features) {
    std::optional<std::string> text = ReadRequired(sink, features_path);
    std::optional<CsvReader> csv;
    if (text && Guard(sink, [&] { csv.emplace(*text, features_path); })) {
      int col[4];
      const char* names[4] = {"feature", "x", "y", "z"};
      bool header_ok = true;
      for (int i = 0; i < 4; ++i) {
        if (!Guard(sink, [&] { col[i] = csv->Require(names[i]); })) header_ok = false;
      }
      if (header_ok) {
        std::unordered_set<std::int64_t> seen;
        ForEachRow(sink, *csv, [&] {
          const std::int64_t id = csv->Int(col[0]);
          const Eigen::Vector3d p(csv->Double(col[1]), csv->Double(col[2]), csv->Double(col[3]));
          if (!seen.insert(id).second) csv->Fail(col[0], "feature " + std::to_string(id) + " appears twice");
          truth.feature_ids.push_back(id);
          truth.features.push_back(p);
        });
      }
    }
  }
  seq.truth = std::move(truth);
}

void ReadMeasurements(ProblemSink& sink, const std::string& dir, bool steps_known, AcousticSequence& seq) {
  const std::string path = Join(dir, "measurements.csv");
  if (seq.image && !fs::exists(path)) {
    seq.has_measurements = false;  // version 2: the features come from the images
    return;
  }
  const std::optional<std::string> text = ReadRequired(sink, path);
  if (!text) return;
  std::optional<CsvReader> csv;
  if (!Guard(sink, [&] { csv.emplace(*text, path); })) return;
  int col[4];
  const char* names[4] = {"step", "feature", "range", "azimuth"};
  bool header_ok = true;
  for (int i = 0; i < 4; ++i) {
    if (!Guard(sink, [&] { col[i] = csv->Require(names[i]); })) header_ok = false;
  }
  if (!header_ok) return;
  const std::int64_t T = seq.num_steps();
  const SonarSensor& s = seq.sensor;
  std::unordered_set<std::int64_t> truth_ids;
  const bool check_ids = seq.truth && !seq.truth->feature_ids.empty();
  if (check_ids) truth_ids.insert(seq.truth->feature_ids.begin(), seq.truth->feature_ids.end());
  std::map<std::pair<std::int64_t, std::int64_t>, int> seen;  // (step, feature) -> line
  ForEachRow(sink, *csv, [&] {
    SonarMeasurement m;
    m.step = csv->Int(col[0]);
    m.feature = csv->Int(col[1]);
    m.range = csv->Double(col[2]);
    m.azimuth = csv->Double(col[3]);
    if (m.step < 0 || (steps_known && m.step >= T)) {
      csv->Fail(col[0], "step " + std::to_string(m.step) + " does not exist; the sequence has steps 0.." +
                            std::to_string(T - 1) + " (controls.csv gives steps 1.." + std::to_string(T - 1) + ")");
    }
    if (check_ids && !truth_ids.count(m.feature)) {
      csv->Fail(col[1], "feature " + std::to_string(m.feature) + " is not in truth/features.csv");
    }
    auto [it, fresh] = seen.emplace(std::make_pair(m.step, m.feature), csv->line());
    if (!fresh) {
      csv->Fail(col[1], "feature " + std::to_string(m.feature) + " is measured twice at step " +
                            std::to_string(m.step) + " (first on line " + std::to_string(it->second) + ")");
    }
    if (m.range < s.range_min || m.range > s.range_max) {
      csv->Fail(col[2], "range " + FormatDouble(m.range) + " m is outside the sensor's range limits [" +
                            FormatDouble(s.range_min) + ", " + FormatDouble(s.range_max) +
                            "] m: a measurement outside the field of view");
    }
    if (std::fabs(m.azimuth) > s.azimuth_fov / 2) {
      csv->Fail(col[3], "azimuth " + FormatDouble(m.azimuth) +
                            " rad is outside the field of view: |azimuth| must not exceed azimuth_fov/2 = " +
                            FormatDouble(s.azimuth_fov / 2) + " rad");
    }
    seq.measurements.push_back(m);
  });
  std::stable_sort(seq.measurements.begin(), seq.measurements.end(),
                   [](const SonarMeasurement& a, const SonarMeasurement& b) { return a.step < b.step; });
}

// Version 2: images/<step>.png for every step 0..T-1 and no image of a step
// the sequence does not have; the validator also decodes each image.
void CheckImages(ProblemSink& sink, const std::string& dir, bool steps_known, AcousticSequence& seq) {
  if (!seq.image) return;
  const std::string images = Join(dir, "images");
  if (!fs::is_directory(images)) {
    sink.Report({images, 0, 0, ""},
                "the folder is missing; a version 2 acoustic sequence has images/<step>.png "
                "for every step");
    return;
  }
  if (!steps_known) return;
  const std::int64_t T = seq.num_steps();
  const std::string steps = "steps 0.." + std::to_string(T - 1);
  const std::size_t before = sink.count();
  for (std::int64_t k = 0; k < T; ++k) {
    if (sink.count() - before >= static_cast<std::size_t>(kMaxProblemsPerFile)) {
      sink.Report({images, 0, 0, ""}, "too many problems; the other images were not checked");
      return;
    }
    const std::string path = SonarImagePath(dir, k);
    if (!fs::exists(path)) {
      sink.Report({path, 0, 0, ""}, "the image of step " + std::to_string(k) + " is missing; a version 2 " +
                                        "acoustic sequence has images/<step>.png for every step (" + steps + ")");
      continue;
    }
    if (sink.collecting()) {
      Guard(sink, [&] { ReadSonarImage(path, *seq.image); });
    } else {
      InspectSonarImage(path, *seq.image);
    }
  }
  for (const auto& entry : fs::directory_iterator(images)) {
    const fs::path name = entry.path().filename();
    if (name.extension() != ".png") continue;
    const std::string stem = name.stem().string();
    if (stem.empty() || stem.find_first_not_of("0123456789") != std::string::npos) continue;
    if (stem.size() > 12 || std::stoll(stem) >= T) {
      sink.Report({entry.path().string(), 0, 0, ""},
                  "an image of step " + stem + ", which the sequence does not have (" + steps + ", controls.csv)");
    }
  }
}

AcousticSequence ReadImpl(ProblemSink& sink, const std::string& dir) {
  AcousticSequence seq;
  if (!fs::is_directory(dir)) {
    sink.Report({dir, 0, 0, ""}, "not a folder; expected an acoustic sequence folder holding sonar.json");
    return seq;
  }
  ReadManifest(sink, dir, seq);
  const bool steps_known = ReadControls(sink, dir, seq);
  ReadTruth(sink, dir, steps_known, seq);
  ReadMeasurements(sink, dir, steps_known, seq);
  CheckImages(sink, dir, steps_known, seq);
  return seq;
}

Json NumberArray(const Vector6d& v) {
  Json a = Json::Array();
  for (int i = 0; i < 6; ++i) a.Push(Json(v[i]));
  return a;
}

}  // namespace

AcousticSequence ReadAcousticSequence(const std::string& dir) {
  ProblemSink sink(nullptr);
  return ReadImpl(sink, dir);
}

std::vector<Problem> ValidateAcousticSequence(const std::string& dir) {
  std::vector<Problem> problems;
  ProblemSink sink(&problems);
  ReadImpl(sink, dir);
  return problems;
}

void WriteAcousticSequence(const AcousticSequence& seq, const std::string& dir) {
  fs::create_directories(dir);
  Json doc = Json::Object();
  doc.Set("format", Json(kFormat));
  doc.Set("version", Json(seq.image ? kImageVersion : kVersion));
  if (!seq.name.empty()) doc.Set("name", Json(seq.name));
  Json sensor = Json::Object();
  sensor.Set("range_min", Json(seq.sensor.range_min));
  sensor.Set("range_max", Json(seq.sensor.range_max));
  sensor.Set("azimuth_fov", Json(seq.sensor.azimuth_fov));
  sensor.Set("elevation_fov", Json(seq.sensor.elevation_fov));
  sensor.Set("range_sigma", Json(seq.sensor.range_sigma));
  sensor.Set("azimuth_sigma", Json(seq.sensor.azimuth_sigma));
  doc.Set("sensor", std::move(sensor));
  doc.Set("initial_pose", NumberArray(seq.initial_pose));
  doc.Set("initial_pose_sigma", NumberArray(seq.initial_pose_sigma));
  Json noise = Json::Object();
  noise.Set("translation_per_metre", Json(seq.motion_noise.translation_per_metre));
  noise.Set("rotation_per_radian", Json(seq.motion_noise.rotation_per_radian));
  noise.Set("translation_floor", Json(seq.motion_noise.translation_floor));
  noise.Set("rotation_floor", Json(seq.motion_noise.rotation_floor));
  doc.Set("motion_noise", std::move(noise));
  if (seq.image) {
    Json image = Json::Object();
    image.Set("range_bins", Json(seq.image->range_bins));
    image.Set("beams", Json(seq.image->beams));
    image.Set("gain_db", Json(seq.image->gain_db));
    doc.Set("image", std::move(image));
  }
  if (!seq.image && !seq.has_measurements) {
    throw std::invalid_argument("WriteAcousticSequence: a version 1 sequence (no image block) needs its measurements");
  }
  WriteFileAtomic(Join(dir, "sonar.json"), doc.Dump());

  CsvWriter controls({"step", "dx", "dy", "dz", "droll", "dpitch", "dyaw"});
  for (const SonarControl& c : seq.controls) {
    controls.Add(c.step);
    for (int i = 0; i < 6; ++i) controls.Add(c.u[i]);
    controls.EndRow();
  }
  WriteFileAtomic(Join(dir, "controls.csv"), controls.text());

  std::vector<SonarMeasurement> sorted = seq.measurements;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const SonarMeasurement& a, const SonarMeasurement& b) { return a.step < b.step; });
  CsvWriter meas({"step", "feature", "range", "azimuth"});
  for (const SonarMeasurement& m : sorted) meas.Add(m.step).Add(m.feature).Add(m.range).Add(m.azimuth).EndRow();
  if (seq.has_measurements) {
    WriteFileAtomic(Join(dir, "measurements.csv"), meas.text());
  } else {
    fs::remove(Join(dir, "measurements.csv"));
  }

  // Files of an earlier sequence in the same folder must not survive as its truth.
  const bool write_poses = seq.truth && !seq.truth->poses.empty();
  const bool write_features = seq.truth && !seq.truth->features.empty();
  if (!write_poses) fs::remove(Join(dir, "truth/poses.csv"));
  if (!write_features) fs::remove(Join(dir, "truth/features.csv"));
  if (seq.truth) {
    if (seq.truth->feature_ids.size() != seq.truth->features.size()) {
      throw std::invalid_argument("WriteAcousticSequence: truth.feature_ids and truth.features differ in length");
    }
    fs::create_directories(Join(dir, "truth"));
    if (!seq.truth->poses.empty()) {
      CsvWriter poses({"step", "x", "y", "z", "roll", "pitch", "yaw"});
      for (std::size_t k = 0; k < seq.truth->poses.size(); ++k) {
        poses.Add(static_cast<std::int64_t>(k));
        for (int i = 0; i < 6; ++i) poses.Add(seq.truth->poses[k][i]);
        poses.EndRow();
      }
      WriteFileAtomic(Join(dir, "truth/poses.csv"), poses.text());
    }
    if (!seq.truth->features.empty()) {
      CsvWriter features({"feature", "x", "y", "z"});
      for (std::size_t i = 0; i < seq.truth->features.size(); ++i) {
        const Eigen::Vector3d& p = seq.truth->features[i];
        features.Add(seq.truth->feature_ids[i]).Add(p.x()).Add(p.y()).Add(p.z()).EndRow();
      }
      WriteFileAtomic(Join(dir, "truth/features.csv"), features.text());
    }
  }
}

}  // namespace hull
