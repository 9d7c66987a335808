#include "survey/survey_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"
#include "survey/survey_images.h"
#include "survey/survey_manifest.h"
#include "survey/survey_plausibility.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

// Either throws at the first error (reading) or collects every problem
// (validating). Warnings are only ever collected.
class Diagnostics {
 public:
  explicit Diagnostics(std::vector<Problem>* sink) : sink_(sink) {}
  bool collecting() const { return sink_ != nullptr; }
  void Error(const SourceLocation& where, const std::string& message) {
    if (!sink_) throw InputError(where, message);
    if (CountFor(where.file) < kMaxPerFile) sink_->push_back({where, message, Severity::kError});
    ++per_file_[where.file];
  }
  void Error(const InputError& e) { Error(e.where(), e.detail()); }
  void Warning(const SourceLocation& where, const std::string& message) {
    if (sink_ && CountFor(where.file) < kMaxPerFile) sink_->push_back({where, message, Severity::kWarning});
    ++per_file_[where.file];
  }
  // Adds a closing note for files with more problems than were listed.
  void Finish() {
    if (!sink_) return;
    for (const auto& [file, n] : per_file_) {
      if (n > kMaxPerFile) {
        sink_->push_back({{file, 0, 0, ""},
                          std::to_string(n - kMaxPerFile) + " further problems in this file not listed",
                          Severity::kError});
      }
    }
  }

 private:
  static constexpr int kMaxPerFile = 50;
  int CountFor(const std::string& file) const {
    auto it = per_file_.find(file);
    return it == per_file_.end() ? 0 : it->second;
  }
  std::vector<Problem>* sink_;
  std::unordered_map<std::string, int> per_file_;
};

std::string Rel(const std::string& dir, const std::string& file) { return (fs::path(dir) / file).string(); }

Vector6d ToVector6(const std::vector<double>& v) { return Eigen::Map<const Vector6d>(v.data()); }
Eigen::Vector3d ToVector3(const std::vector<double>& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }
using survey_manifest::CheckPositive;
using survey_manifest::ManifestJson;
using survey_manifest::NonZero3;
using survey_manifest::ParseManifest;
using survey_manifest::Vec;

// ---------------------------------------------------------------------------
// CSV files
// ---------------------------------------------------------------------------

// Reads a CSV file if present; returns false (after reporting) when it is
// missing but required, or when its header is unusable.
bool OpenCsv(const std::string& path, const std::string& name, bool required, Diagnostics& diag, std::string& text) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (required) diag.Error({name, 0, 0, ""}, "required file is missing");
    return false;
  }
  try {
    text = ReadFileToString(path);
  } catch (const InputError& e) {
    diag.Error({name, 0, 0, ""}, e.detail());
    return false;
  }
  return true;
}

// Runs body(reader) for every record; a bad record is reported and skipped
// when collecting. Header problems end the file.
template <typename Setup, typename Body>
void ForEachRecord(const std::string& text, const std::string& name, Diagnostics& diag, Setup setup, Body body) {
  std::optional<CsvReader> reader;
  try {
    reader.emplace(text, name);
    setup(*reader);
  } catch (const InputError& e) {
    diag.Error(e);
    return;
  }
  while (true) {
    try {
      if (!reader->Next()) break;
      body(*reader);
    } catch (const InputError& e) {
      diag.Error(e);
    }
  }
}

struct Columns {
  std::vector<int> idx;
};

Vector6d ReadPose6(const CsvReader& r, const int* cols) {
  Vector6d x;
  for (int i = 0; i < 6; ++i) x[i] = r.Double(cols[i]);
  return x;
}

// The keyframes other files may refer to: those nav.csv gave, and those whose
// nav.csv row was reported unreadable (a reference to one of these is not a
// second error: the row is skipped quietly, the first report says why).
struct Keyframes {
  std::unordered_map<std::int64_t, int> index;
  std::unordered_set<std::int64_t> unreadable;
  // False: skip the row. Fails the row when nav.csv has no such keyframe.
  bool Check(const CsvReader& r, int col, std::int64_t id) const {
    if (index.count(id)) return true;
    if (unreadable.count(id)) return false;
    r.Fail(col, "keyframe " + std::to_string(id) + " is not in nav.csv");
    return false;
  }
};

void ReadNav(const std::string& dir, SurveyBundle& b, Diagnostics& diag, Keyframes& kf, CsvRowPlaces& places) {
  const std::string name = Rel(dir, "nav.csv");
  std::string text;
  if (!OpenCsv(name, name, true, diag, text)) return;
  int c_kf = -1, c_t = -1, c_x[6], c_depth = -1, c_rm = -1, c_pm = -1, c_servo = -1;
  std::unordered_set<std::int64_t> seen;
  double last_t = -INFINITY;
  ForEachRecord(
      text, name, diag,
      [&](const CsvReader& r) {
        c_kf = r.Require("keyframe");
        c_t = r.Require("t");
        const char* names[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
        for (int i = 0; i < 6; ++i) c_x[i] = r.Require(names[i]);
        c_depth = r.Require("depth");
        c_rm = r.Require("roll_meas");
        c_pm = r.Require("pitch_meas");
        c_servo = r.Require("servo");
      },
      [&](const CsvReader& r) {
        NavRecord n;
        n.keyframe = r.Int(c_kf);
        try {
          n.t = r.Double(c_t);
          n.x_gv = ReadPose6(r, c_x);
          n.depth = r.Double(c_depth);
          n.roll_meas = r.Double(c_rm);
          n.pitch_meas = r.Double(c_pm);
          n.servo = r.Double(c_servo);
        } catch (const InputError&) {
          if (!seen.count(n.keyframe)) kf.unreadable.insert(n.keyframe);
          throw;
        }
        if (!seen.insert(n.keyframe).second) {
          r.Fail(c_kf, "keyframe " + std::to_string(n.keyframe) + " appears twice; ids must be unique");
        }
        if (!(n.t > last_t)) {
          r.Fail(c_t, "time " + FormatDouble(n.t) + " is not after the previous row's " + FormatDouble(last_t) +
                          "; t must increase");
        }
        last_t = n.t;
        b.nav.push_back(n);
        const int cols[11] = {c_t, c_x[0], c_x[1], c_x[2], c_x[3], c_x[4], c_x[5], c_depth, c_rm, c_pm, c_servo};
        places.Add(r, cols);
      });
  if (b.nav.empty()) diag.Error({name, 0, 0, ""}, "no keyframes: expected at least one row");
  kf.index = b.KeyframeIndex();
}

void ReadOdometry(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag,
                  CsvRowPlaces& places) {
  const std::string name = Rel(dir, "odometry.csv");
  std::string text;
  if (!OpenCsv(name, name, true, diag, text)) return;
  int c_from = -1, c_to = -1, c_z[6];
  ForEachRecord(
      text, name, diag,
      [&](const CsvReader& r) {
        c_from = r.Require("from");
        c_to = r.Require("to");
        const char* names[6] = {"dx", "dy", "dz", "droll", "dpitch", "dyaw"};
        for (int i = 0; i < 6; ++i) c_z[i] = r.Require(names[i]);
      },
      [&](const CsvReader& r) {
        OdometryRecord o;
        o.from = r.Int(c_from);
        o.to = r.Int(c_to);
        o.z = ReadPose6(r, c_z);
        if (!kf.Check(r, c_from, o.from) || !kf.Check(r, c_to, o.to)) return;
        if (o.from == o.to) r.Fail(c_to, "odometry from a keyframe to itself");
        b.odometry.push_back(o);
        const int cols[8] = {c_from, c_to, c_z[0], c_z[1], c_z[2], c_z[3], c_z[4], c_z[5]};
        places.Add(r, cols);
      });
}

void ReadDvl(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag, CsvRowPlaces& places) {
  const std::string name = Rel(dir, "dvl.csv");
  std::string text;
  if (!OpenCsv(name, name, true, diag, text)) return;
  int c_kf = -1, c_r[4];
  std::unordered_set<std::int64_t> seen;
  ForEachRecord(
      text, name, diag,
      [&](const CsvReader& r) {
        c_kf = r.Require("keyframe");
        for (int i = 0; i < 4; ++i) c_r[i] = r.Require("r" + std::to_string(i + 1));
      },
      [&](const CsvReader& r) {
        DvlRecord d;
        d.keyframe = r.Int(c_kf);
        if (!seen.insert(d.keyframe).second) {
          r.Fail(c_kf, "keyframe " + std::to_string(d.keyframe) + " has a second row; expected one per keyframe");
        }
        for (int i = 0; i < 4; ++i) {
          if (auto v = r.OptionalDouble(c_r[i])) {
            if (!(*v > 0)) r.Fail(c_r[i], "expected a positive range (m) or an empty field, got " + FormatDouble(*v));
            d.range[static_cast<std::size_t>(i)] = *v;
          }
        }
        if (kf.Check(r, c_kf, d.keyframe)) {
          b.dvl.push_back(d);
          places.Add(r, c_r);
        }
      });
}

void ReadFeatures(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag, bool required) {
  const std::string name = Rel(dir, "features.csv");
  std::string text;
  if (!OpenCsv(name, name, required, diag, text)) return;
  const bool stereo = b.manifest.camera.stereo();
  const CameraRig& cam = b.manifest.camera;
  int c_kf = -1, c_lm = -1, c_ut = -1, c_vt = -1, c_ub = -1, c_vb = -1;
  std::unordered_set<std::uint64_t> seen;
  std::size_t warned_outside = 0;
  b.features.reserve(text.size() / 40);
  seen.reserve(text.size() / 40);
  ForEachRecord(
      text, name, diag,
      [&](const CsvReader& r) {
        c_kf = r.Require("keyframe");
        c_lm = r.Require("landmark");
        c_ut = r.Require("u_top");
        c_vt = r.Require("v_top");
        c_ub = stereo ? r.Require("u_bottom") : r.Find("u_bottom");
        c_vb = stereo ? r.Require("v_bottom") : r.Find("v_bottom");
      },
      [&](const CsvReader& r) {
        FeatureObservation f;
        f.keyframe = r.Int(c_kf);
        f.landmark = r.Int(c_lm);
        f.top = {r.Double(c_ut), r.Double(c_vt)};
        const bool ub = !r.Empty(c_ub), vb = !r.Empty(c_vb);
        if (!stereo && (ub || vb)) {
          r.Fail(ub ? c_ub : c_vb, "a monocular survey has no bottom camera; expected an empty field");
        }
        if (ub != vb) r.Fail(ub ? c_vb : c_ub, "u_bottom and v_bottom must both be given or both be empty");
        if (ub) {
          f.bottom = {r.Double(c_ub), r.Double(c_vb)};
          f.has_bottom = true;
        }
        const std::uint64_t key =
            (static_cast<std::uint64_t>(f.keyframe) << 32) ^ static_cast<std::uint64_t>(f.landmark);
        if (!seen.insert(key).second) {
          r.Fail(c_lm, "landmark " + std::to_string(f.landmark) + " is observed twice in keyframe " +
                           std::to_string(f.keyframe));
        }
        if ((!cam.InImage(f.top) || (f.has_bottom && !cam.InImage(f.bottom))) && warned_outside++ < 5) {
          diag.Warning(r.Where(c_ut), "pixel lies outside the " + std::to_string(cam.width) + "x" +
                                          std::to_string(cam.height) + " image");
        }
        if (kf.Check(r, c_kf, f.keyframe)) b.features.push_back(f);
      });
}

void ReadLandmarks(const std::string& dir, SurveyBundle& b, Diagnostics& diag, CsvRowPlaces& places) {
  const std::string name = Rel(dir, "landmarks.csv");
  std::string text;
  if (!OpenCsv(name, name, false, diag, text)) return;
  std::unordered_set<std::int64_t> observed;
  for (const auto& f : b.features) observed.insert(f.landmark);
  int c_id = -1, c_p[3];
  std::unordered_set<std::int64_t> seen;
  std::vector<LandmarkRecord> out;
  ForEachRecord(
      text, name, diag,
      [&](const CsvReader& r) {
        c_id = r.Require("landmark");
        c_p[0] = r.Require("x");
        c_p[1] = r.Require("y");
        c_p[2] = r.Require("z");
      },
      [&](const CsvReader& r) {
        LandmarkRecord l;
        l.landmark = r.Int(c_id);
        l.p = {r.Double(c_p[0]), r.Double(c_p[1]), r.Double(c_p[2])};
        if (!seen.insert(l.landmark).second) {
          r.Fail(c_id, "landmark " + std::to_string(l.landmark) + " appears twice");
        }
        if (!observed.count(l.landmark)) diag.Warning(r.Where(c_id), "landmark is never observed in features.csv");
        out.push_back(l);
        places.Add(r, c_p);
      });
  b.landmarks = std::move(out);
}

Json ReadJsonFile(const std::string& path, Diagnostics& diag, bool& ok) {
  ok = false;
  try {
    Json j = Json::Parse(ReadFileToString(path), path);
    ok = true;
    return j;
  } catch (const InputError& e) {
    diag.Error(e);
  }
  return Json();
}

void ReadTruth(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag) {
  const std::string tdir = Rel(dir, "truth");
  std::error_code ec;
  if (!fs::is_directory(tdir, ec)) return;
  SurveyTruth t;
  // poses.csv
  {
    const std::string name = Rel(tdir, "poses.csv");
    std::string text;
    if (OpenCsv(name, name, false, diag, text)) {
      int c_kf = -1, c_x[6], c_s = -1;
      ForEachRecord(
          text, name, diag,
          [&](const CsvReader& r) {
            c_kf = r.Require("keyframe");
            const char* names[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
            for (int i = 0; i < 6; ++i) c_x[i] = r.Require(names[i]);
            c_s = r.Require("servo");
          },
          [&](const CsvReader& r) {
            TruePose p;
            p.keyframe = r.Int(c_kf);
            p.x_gv = ReadPose6(r, c_x);
            p.servo = r.Double(c_s);
            if (!kf.Check(r, c_kf, p.keyframe)) return;
            t.poses.push_back(p);
          });
    }
  }
  // objects.json (read before landmarks to check object references)
  std::unordered_set<std::string> object_ids;
  {
    const std::string name = Rel(tdir, "objects.json");
    if (fs::exists(name, ec)) {
      bool ok = false;
      Json doc = ReadJsonFile(name, diag, ok);
      if (ok) {
        try {
          JsonReader root(doc, name);
          const Json& arr = root.Required("objects");
          if (!arr.is_array()) root.Fail(arr, "objects", "expected an array");
          for (std::size_t i = 0; i < arr.items().size(); ++i) {
            JsonReader o(arr.items()[i], name, "objects[" + std::to_string(i) + "]");
            TrueObject obj;
            obj.id = o.String("id");
            if (!object_ids.insert(obj.id).second) o.Fail(o.Required("id"), "id", "duplicate object id " + obj.id);
            const std::string kind = o.String("kind");
            if (kind == "cylinder")
              obj.kind = ObjectKind::kCylinder;
            else if (kind == "box")
              obj.kind = ObjectKind::kBox;
            else if (kind == "patch")
              obj.kind = ObjectKind::kPatch;
            else
              o.Fail(o.Required("kind"), "kind", "expected \"cylinder\", \"box\" or \"patch\", got \"" + kind + "\"");
            obj.center = ToVector3(o.Numbers("center", 3));
            obj.normal = NonZero3(o, "normal").normalized();
            if (obj.kind == ObjectKind::kBox) {
              obj.size = ToVector3(o.Numbers("size", 3));
              obj.height = obj.size.z();
              obj.radius = 0.5 * std::hypot(obj.size.x(), obj.size.y());
            } else {
              obj.radius = o.Number("radius");
              obj.height = o.Number("height");
              CheckPositive(o, "radius", obj.radius);
              CheckPositive(o, "height", obj.height);
            }
            t.objects.push_back(obj);
          }
        } catch (const InputError& e) {
          diag.Error(e);
        }
      }
    }
  }
  // landmarks.csv
  {
    const std::string name = Rel(tdir, "landmarks.csv");
    std::string text;
    if (OpenCsv(name, name, false, diag, text)) {
      int c_id = -1, c_p[3], c_dev = -1, c_obj = -1;
      std::unordered_set<std::int64_t> seen;
      ForEachRecord(
          text, name, diag,
          [&](const CsvReader& r) {
            c_id = r.Require("landmark");
            c_p[0] = r.Require("x");
            c_p[1] = r.Require("y");
            c_p[2] = r.Require("z");
            c_dev = r.Require("deviation");
            c_obj = r.Require("object");
          },
          [&](const CsvReader& r) {
            TrueLandmark l;
            l.landmark = r.Int(c_id);
            l.p = {r.Double(c_p[0]), r.Double(c_p[1]), r.Double(c_p[2])};
            l.deviation = r.Double(c_dev);
            l.object = std::string(r.Field(c_obj));
            if (!seen.insert(l.landmark).second)
              r.Fail(c_id, "landmark " + std::to_string(l.landmark) + " appears twice");
            if (!l.object.empty() && !object_ids.empty() && !object_ids.count(l.object)) {
              r.Fail(c_obj, "object '" + l.object + "' is not in truth/objects.json");
            }
            t.landmarks.push_back(l);
          });
    }
  }
  auto read_pose_json = [&](const char* file, const char* key, Vector6d& out) {
    const std::string name = Rel(tdir, file);
    if (!fs::exists(name, ec)) return;
    bool ok = false;
    Json doc = ReadJsonFile(name, diag, ok);
    if (!ok) return;
    try {
      out = ToVector6(JsonReader(doc, name).Numbers(key, 6));
    } catch (const InputError& e) {
      diag.Error(e);
    }
  };
  read_pose_json("model_pose.json", "x_gM", t.x_gM);
  read_pose_json("servo_to_top.json", "x_s_cT", t.x_s_cT);
  b.truth = std::move(t);
}

// Version 2: lists images/ (and, when validating, checks every image).
// Returns whether the bundle has images, i.e. whether features.csv is optional.
bool ReadImagesFolder(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag) {
  const std::string folder = Rel(dir, "images");
  std::error_code ec;
  if (!fs::exists(folder, ec)) return false;
  if (b.manifest.version < 2) {
    diag.Warning({folder, 0, 0, ""}, "ignored: images need \"version\": 2 in survey.json (this bundle is version 1)");
    return false;
  }
  if (!fs::is_directory(folder, ec)) {
    diag.Error({folder, 0, 0, ""}, "is not a folder; expected the folder of camera images");
    return false;
  }
  std::vector<Problem> found;
  b.images = ListSurveyImages(dir, b.manifest, b.nav, kf.unreadable, found);
  if (diag.collecting()) CheckSurveyImages(dir, b.manifest, *b.images, found);
  for (const Problem& p : found) {
    if (p.severity == Severity::kError) {
      diag.Error(p.where, p.message);
    } else {
      diag.Warning(p.where, p.message);
    }
  }
  if (b.images->present() == 0 && !fs::exists(Rel(dir, "features.csv"), ec)) {
    diag.Error({folder, 0, 0, ""}, "holds no image and there is no features.csv: the bundle has no camera data");
  }
  return true;
}

// The mesh model_hint names, opened and checked as the pipeline will load it
// (finite, indices in range, a usable surface: geometry/mesh_io.h); its
// problem is reported at model_hint, naming the mesh's own place.
void CheckModelHintMesh(const std::string& path, const SourceLocation& at, Diagnostics& diag) {
  try {
    MeshLoadOptions o;
    o.orient_outward = false;
    LoadMesh(path, o);
  } catch (const InputError& e) {
    diag.Error(at, "the mesh cannot be used: " + std::string(e.what()));
  }
}

SurveyBundle ReadImpl(const std::string& dir, std::vector<Problem>* problems) {
  Diagnostics diag(problems);
  SurveyPlaces places = SurveyPlaces::ForBundle(dir);
  SurveyBundle b;
  b.directory = dir;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    diag.Error({dir, 0, 0, ""}, "is not a folder; expected a survey bundle folder holding survey.json");
    diag.Finish();
    return b;
  }
  const std::string man_path = Rel(dir, "survey.json");
  bool manifest_ok = false;
  if (!fs::exists(man_path, ec)) {
    diag.Error({man_path, 0, 0, ""}, "required file is missing");
  } else {
    bool ok = false;
    Json doc = ReadJsonFile(man_path, diag, ok);
    if (ok) {
      try {
        b.manifest = ParseManifest(doc, man_path);
        manifest_ok = true;
        if (const Json* guess = doc.Get("model_pose_guess")) {
          places.model_pose_guess = {man_path, guess->line(), guess->column(), "model_pose_guess"};
        }
        if (b.manifest.model_hint) {
          const Json* hint = doc.Get("model_hint");
          const SourceLocation at{man_path, hint->line(), hint->column(), "model_hint"};
          if (!fs::exists(b.ModelHintPath(), ec)) {
            diag.Error(at, "the mesh file '" + *b.manifest.model_hint + "' does not exist in the bundle");
          } else if (diag.collecting()) {
            CheckModelHintMesh(b.ModelHintPath(), at, diag);
          }
        }
      } catch (const InputError& e) {
        diag.Error(e);
      }
    }
  }
  Keyframes kf;
  ReadNav(dir, b, diag, kf, places.nav);
  ReadOdometry(dir, b, kf, diag, places.odometry);
  ReadDvl(dir, b, kf, diag, places.dvl);
  if (manifest_ok) {
    ReadFeatures(dir, b, kf, diag, !ReadImagesFolder(dir, b, kf, diag));
  } else if (diag.collecting()) {
    diag.Warning({Rel(dir, "features.csv"), 0, 0, ""}, "not checked: survey.json could not be read");
  }
  ReadLandmarks(dir, b, diag, places.landmarks);
  {
    // The rules that need the whole survey (survey_plausibility.h).
    std::vector<Problem> found;
    CheckSurveyPlausibility(b, places, found);
    for (const Problem& p : found) diag.Error(p.where, p.message);
  }
  ReadTruth(dir, b, kf, diag);
  // features.csv written by the visual front end (match-graph.csv beside it):
  // its landmark ids are the front end's, not those of landmarks.csv and
  // truth/landmarks.csv (simulate/image_track_truth.h derives their truth).
  if (!b.features.empty() && fs::exists(Rel(dir, "match-graph.csv"), ec))
    b.AdoptImageFeatureTracks(std::move(b.features));
  const std::string sonar_dir = Rel(dir, "sonar");
  if (fs::exists(Rel(sonar_dir, "sonar.json"), ec)) {
    if (problems) {
      for (auto& p : ValidateAcousticSequence(sonar_dir)) problems->push_back(std::move(p));
      try {
        b.sonar = ReadAcousticSequence(sonar_dir);
      } catch (const InputError&) {
        // already reported by the validator
      }
    } else {
      b.sonar = ReadAcousticSequence(sonar_dir);
    }
  }
  diag.Finish();
  return b;
}

}  // namespace

SurveyManifest ParseSurveyManifest(const std::string& text, const std::string& file) {
  return ParseManifest(Json::Parse(text, file), file);
}

std::string SurveyManifestToJson(const SurveyManifest& manifest) { return ManifestJson(manifest).Dump(); }

SurveyBundle ReadSurveyBundle(const std::string& dir) { return ReadImpl(dir, nullptr); }

SurveyBundle ReadSurveyBundleCollecting(const std::string& dir, std::vector<Problem>* problems) {
  std::vector<Problem> local;
  return ReadImpl(dir, problems ? problems : &local);
}

std::vector<Problem> ValidateSurveyBundle(const std::string& dir) {
  std::vector<Problem> problems;
  ReadImpl(dir, &problems);
  return problems;
}

// ---------------------------------------------------------------------------
// Writing
// ---------------------------------------------------------------------------

std::string FeaturesCsvText(const std::vector<FeatureObservation>& features, bool stereo) {
  std::vector<std::string> head = {"keyframe", "landmark", "u_top", "v_top", "u_bottom", "v_bottom"};
  if (!stereo) head.resize(4);
  CsvWriter w(head);
  for (const auto& f : features) {
    w.Add(f.keyframe).Add(f.landmark).Add(f.top.x()).Add(f.top.y());
    if (stereo) {
      if (f.has_bottom)
        w.Add(f.bottom.x()).Add(f.bottom.y());
      else
        w.AddEmpty().AddEmpty();
    }
    w.EndRow();
  }
  return w.Take();
}

void WriteSurveyBundle(const SurveyBundle& b, const std::string& dir) {
  fs::create_directories(dir);
  WriteFileAtomic(Rel(dir, "survey.json"), ManifestJson(b.manifest).Dump());
  {
    CsvWriter w({"keyframe", "t", "x", "y", "z", "roll", "pitch", "yaw", "depth", "roll_meas", "pitch_meas", "servo"});
    for (const auto& n : b.nav) {
      w.Add(n.keyframe).Add(n.t);
      for (int i = 0; i < 6; ++i) w.Add(n.x_gv[i]);
      w.Add(n.depth).Add(n.roll_meas).Add(n.pitch_meas).Add(n.servo);
      w.EndRow();
    }
    WriteFileAtomic(Rel(dir, "nav.csv"), w.text());
  }
  {
    CsvWriter w({"from", "to", "dx", "dy", "dz", "droll", "dpitch", "dyaw"});
    for (const auto& o : b.odometry) {
      w.Add(o.from).Add(o.to);
      for (int i = 0; i < 6; ++i) w.Add(o.z[i]);
      w.EndRow();
    }
    WriteFileAtomic(Rel(dir, "odometry.csv"), w.text());
  }
  {
    CsvWriter w({"keyframe", "r1", "r2", "r3", "r4"});
    for (const auto& d : b.dvl) {
      w.Add(d.keyframe);
      for (double r : d.range) {
        if (DvlRecord::HasReturn(r))
          w.Add(r);
        else
          w.AddEmpty();
      }
      w.EndRow();
    }
    WriteFileAtomic(Rel(dir, "dvl.csv"), w.text());
  }
  // A version 2 bundle with images may have no features.csv (images/ itself
  // is written by whoever has the pixels, e.g. the simulator's renderer).
  if (!(b.manifest.version >= 2 && b.images && b.features.empty())) {
    WriteFileAtomic(Rel(dir, "features.csv"), FeaturesCsvText(b.features, b.manifest.camera.stereo()));
  }
  if (b.landmarks) {
    CsvWriter w({"landmark", "x", "y", "z"});
    for (const auto& l : *b.landmarks) {
      w.Add(l.landmark).Add(l.p.x()).Add(l.p.y()).Add(l.p.z());
      w.EndRow();
    }
    WriteFileAtomic(Rel(dir, "landmarks.csv"), w.text());
  }
  if (b.truth) {
    const SurveyTruth& t = *b.truth;
    const std::string tdir = Rel(dir, "truth");
    {
      CsvWriter w({"keyframe", "x", "y", "z", "roll", "pitch", "yaw", "servo"});
      for (const auto& p : t.poses) {
        w.Add(p.keyframe);
        for (int i = 0; i < 6; ++i) w.Add(p.x_gv[i]);
        w.Add(p.servo);
        w.EndRow();
      }
      WriteFileAtomic(Rel(tdir, "poses.csv"), w.text());
    }
    {
      CsvWriter w({"landmark", "x", "y", "z", "deviation", "object"});
      for (const auto& l : t.landmarks) {
        w.Add(l.landmark).Add(l.p.x()).Add(l.p.y()).Add(l.p.z()).Add(l.deviation).Add(std::string_view(l.object));
        w.EndRow();
      }
      WriteFileAtomic(Rel(tdir, "landmarks.csv"), w.text());
    }
    {
      Json arr = Json::Array();
      for (const auto& o : t.objects) {
        Json j = Json::Object();
        j.Set("id", o.id);
        j.Set("kind", ObjectKindName(o.kind));
        j.Set("center", Vec(o.center));
        j.Set("normal", Vec(o.normal));
        if (o.kind == ObjectKind::kBox) {
          j.Set("size", Vec(o.size));
        } else {
          j.Set("radius", o.radius);
          j.Set("height", o.height);
        }
        arr.Push(j);
      }
      Json root = Json::Object();
      root.Set("objects", arr);
      WriteFileAtomic(Rel(tdir, "objects.json"), root.Dump());
    }
    {
      Json root = Json::Object();
      root.Set("x_gM", Vec(t.x_gM));
      WriteFileAtomic(Rel(tdir, "model_pose.json"), root.Dump());
    }
    {
      Json root = Json::Object();
      root.Set("x_s_cT", Vec(t.x_s_cT));
      WriteFileAtomic(Rel(tdir, "servo_to_top.json"), root.Dump());
    }
  }
  if (b.sonar) WriteAcousticSequence(*b.sonar, Rel(dir, "sonar"));
}

}  // namespace hull
