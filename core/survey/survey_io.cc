#include "survey/survey_io.h"

#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "survey/survey_images.h"

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

Json Vec(const Eigen::VectorXd& v) {
  Json a = Json::Array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.Push(Json(v[i]));
  return a;
}

// ---------------------------------------------------------------------------
// survey.json
// ---------------------------------------------------------------------------

void CheckPositive(const JsonReader& r, std::string_view key, double v) {
  if (!(v > 0)) r.Fail(r.Required(key), key, "expected a positive number, got " + FormatDouble(v));
}

PinholeIntrinsics ReadIntrinsics(const JsonReader& r) {
  PinholeIntrinsics k;
  k.fx = r.Number("fx");
  CheckPositive(r, "fx", k.fx);
  k.fy = r.Number("fy");
  CheckPositive(r, "fy", k.fy);
  k.cx = r.Number("cx");
  k.cy = r.Number("cy");
  return k;
}

Eigen::Vector3d NonZero3(const JsonReader& r, std::string_view key) {
  Eigen::Vector3d v = ToVector3(r.Numbers(key, 3));
  if (v.norm() < 1e-12) r.Fail(r.Required(key), key, "expected a non-zero direction");
  return v;
}

SurveyManifest ParseManifest(const Json& doc, const std::string& file) {
  JsonReader root(doc, file);
  SurveyManifest m;
  const std::string format = root.String("format");
  if (format != "hull-survey") {
    root.Fail(root.Required("format"), "format", "expected \"hull-survey\", got \"" + format + "\"");
  }
  const std::int64_t version = root.Integer("version");
  if (version != 1 && version != 2) {
    root.Fail(root.Required("version"), "version",
              "unsupported version " + std::to_string(version) + "; this reader knows versions 1 and 2");
  }
  m.version = static_cast<int>(version);
  m.name = root.OptionalString("name").value_or("");
  m.vehicle = root.OptionalString("vehicle").value_or("");
  m.model_hint = root.OptionalString("model_hint");
  if (m.model_hint && m.model_hint->empty()) root.Fail(root.Required("model_hint"), "model_hint", "empty path");

  const JsonReader cam = root.Object("camera");
  const std::string type = cam.String("type");
  if (type == "stereo") {
    m.camera.type = CameraType::kStereo;
  } else if (type == "mono") {
    m.camera.type = CameraType::kMono;
  } else {
    cam.Fail(cam.Required("type"), "type", "expected \"stereo\" or \"mono\", got \"" + type + "\"");
  }
  const std::int64_t w = cam.Integer("width"), h = cam.Integer("height");
  if (w <= 0) cam.Fail(cam.Required("width"), "width", "expected a positive integer");
  if (h <= 0) cam.Fail(cam.Required("height"), "height", "expected a positive integer");
  m.camera.width = static_cast<int>(w);
  m.camera.height = static_cast<int>(h);
  m.camera.top = ReadIntrinsics(cam.Object("top"));
  if (m.camera.stereo()) {
    m.camera.bottom = ReadIntrinsics(cam.Object("bottom"));
    m.camera.top_to_bottom = ToVector6(cam.Numbers("top_to_bottom", 6));
  } else {
    m.camera.bottom = m.camera.top;
    m.camera.top_to_bottom.setZero();
  }
  m.camera.servo_to_top = ToVector6(cam.Numbers("servo_to_top", 6));

  m.servo_mount = ToVector6(root.Object("servo").Numbers("mount", 6));

  const JsonReader dvl = root.Object("dvl");
  m.servo_to_dvl = ToVector6(dvl.Numbers("servo_to_dvl", 6));
  const Json& beams = dvl.Required("beams");
  if (!beams.is_array() || beams.items().size() != 4) {
    dvl.Fail(beams, "beams", "expected an array of 4 beam directions (Janus DVL, in the order r1..r4)");
  }
  for (int i = 0; i < 4; ++i) {
    const Json& b = beams.items()[static_cast<std::size_t>(i)];
    const std::string key = "beams[" + std::to_string(i) + "]";
    if (!b.is_array() || b.items().size() != 3) dvl.Fail(b, key, "expected 3 numbers");
    for (int k = 0; k < 3; ++k) {
      const Json& c = b.items()[static_cast<std::size_t>(k)];
      if (!c.is_number()) dvl.Fail(c, key, "expected a number");
      m.beams[static_cast<std::size_t>(i)][k] = c.as_number();
    }
    if (m.beams[static_cast<std::size_t>(i)].norm() < 1e-12) dvl.Fail(b, key, "expected a non-zero direction");
  }

  if (auto g = root.OptionalNumbers("model_pose_guess", 6)) m.model_pose_guess = ToVector6(*g);
  if (auto ax = root.OptionalObject("model_axes")) {
    ModelAxes a;
    a.forward = NonZero3(*ax, "forward").normalized();
    a.up = NonZero3(*ax, "up").normalized();
    if (std::abs(a.forward.dot(a.up)) > 0.99) {
      ax->Fail(ax->Required("up"), "up", "expected a direction not parallel to forward");
    }
    m.model_axes = a;
  }
  if (auto im = root.OptionalObject("images")) {
    ImagingNote note;
    if (im->Has("exposure_s")) {
      note.exposure_s = im->Number("exposure_s");
      CheckPositive(*im, "exposure_s", *note.exposure_s);
    }
    note.illumination = im->OptionalString("illumination");
    m.imaging = note;
  }
  if (auto nz = root.OptionalObject("noise")) {
    NoiseModel& n = m.noise;
    struct Item {
      const char* key;
      double* value;
    } items[] = {{"pixel_sigma", &n.pixel_sigma},
                 {"dvl_range_sigma", &n.dvl_range_sigma},
                 {"depth_sigma", &n.depth_sigma},
                 {"roll_pitch_sigma", &n.roll_pitch_sigma},
                 {"servo_sigma", &n.servo_sigma},
                 {"odometry_translation_rate", &n.odometry_translation_rate},
                 {"odometry_rotation_rate", &n.odometry_rotation_rate},
                 {"model_pose_sigma", &n.model_pose_sigma}};
    for (const auto& it : items) {
      if (!nz->Has(it.key)) continue;
      *it.value = nz->Number(it.key);
      CheckPositive(*nz, it.key, *it.value);
    }
    if (auto s = nz->OptionalNumbers("servo_to_top_sigma", 6)) {
      for (double v : *s) {
        if (!(v > 0)) nz->Fail(nz->Required("servo_to_top_sigma"), "servo_to_top_sigma", "expected 6 positive numbers");
      }
      n.servo_to_top_sigma = ToVector6(*s);
    }
  }
  return m;
}

Json ManifestJson(const SurveyManifest& m) {
  Json root = Json::Object();
  root.Set("format", "hull-survey");
  root.Set("version", m.version);
  if (!m.name.empty()) root.Set("name", m.name);
  if (!m.vehicle.empty()) root.Set("vehicle", m.vehicle);
  if (m.model_hint) root.Set("model_hint", *m.model_hint);
  auto intr = [](const PinholeIntrinsics& k) {
    Json j = Json::Object();
    j.Set("fx", k.fx);
    j.Set("fy", k.fy);
    j.Set("cx", k.cx);
    j.Set("cy", k.cy);
    return j;
  };
  Json cam = Json::Object();
  cam.Set("type", m.camera.stereo() ? "stereo" : "mono");
  cam.Set("width", m.camera.width);
  cam.Set("height", m.camera.height);
  cam.Set("top", intr(m.camera.top));
  if (m.camera.stereo()) {
    cam.Set("bottom", intr(m.camera.bottom));
    cam.Set("top_to_bottom", Vec(m.camera.top_to_bottom));
  }
  cam.Set("servo_to_top", Vec(m.camera.servo_to_top));
  root.Set("camera", cam);
  Json servo = Json::Object();
  servo.Set("mount", Vec(m.servo_mount));
  root.Set("servo", servo);
  Json dvl = Json::Object();
  dvl.Set("servo_to_dvl", Vec(m.servo_to_dvl));
  Json beams = Json::Array();
  for (const auto& b : m.beams) beams.Push(Vec(b));
  dvl.Set("beams", beams);
  root.Set("dvl", dvl);
  if (m.model_pose_guess) root.Set("model_pose_guess", Vec(*m.model_pose_guess));
  if (m.model_axes) {
    Json ax = Json::Object();
    ax.Set("forward", Vec(m.model_axes->forward));
    ax.Set("up", Vec(m.model_axes->up));
    root.Set("model_axes", ax);
  }
  const NoiseModel& n = m.noise;
  Json nz = Json::Object();
  nz.Set("pixel_sigma", n.pixel_sigma);
  nz.Set("dvl_range_sigma", n.dvl_range_sigma);
  nz.Set("depth_sigma", n.depth_sigma);
  nz.Set("roll_pitch_sigma", n.roll_pitch_sigma);
  nz.Set("servo_sigma", n.servo_sigma);
  nz.Set("odometry_translation_rate", n.odometry_translation_rate);
  nz.Set("odometry_rotation_rate", n.odometry_rotation_rate);
  nz.Set("model_pose_sigma", n.model_pose_sigma);
  nz.Set("servo_to_top_sigma", Vec(n.servo_to_top_sigma));
  root.Set("noise", nz);
  if (m.imaging) {
    Json im = Json::Object();
    if (m.imaging->exposure_s) im.Set("exposure_s", *m.imaging->exposure_s);
    if (m.imaging->illumination) im.Set("illumination", *m.imaging->illumination);
    root.Set("images", im);
  }
  return root;
}

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

void ReadNav(const std::string& dir, SurveyBundle& b, Diagnostics& diag, Keyframes& kf) {
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
      });
  if (b.nav.empty()) diag.Error({name, 0, 0, ""}, "no keyframes: expected at least one row");
  kf.index = b.KeyframeIndex();
}

void ReadOdometry(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag) {
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
      });
}

void ReadDvl(const std::string& dir, SurveyBundle& b, const Keyframes& kf, Diagnostics& diag) {
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
        if (kf.Check(r, c_kf, d.keyframe)) b.dvl.push_back(d);
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

void ReadLandmarks(const std::string& dir, SurveyBundle& b, Diagnostics& diag) {
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

SurveyBundle ReadImpl(const std::string& dir, std::vector<Problem>* problems) {
  Diagnostics diag(problems);
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
        if (b.manifest.model_hint && !fs::exists(b.ModelHintPath(), ec)) {
          const Json* hint = doc.Get("model_hint");
          diag.Error({man_path, hint->line(), hint->column(), "model_hint"},
                     "the mesh file '" + *b.manifest.model_hint + "' does not exist in the bundle");
        }
      } catch (const InputError& e) {
        diag.Error(e);
      }
    }
  }
  Keyframes kf;
  ReadNav(dir, b, diag, kf);
  ReadOdometry(dir, b, kf, diag);
  ReadDvl(dir, b, kf, diag);
  if (manifest_ok) {
    ReadFeatures(dir, b, kf, diag, !ReadImagesFolder(dir, b, kf, diag));
  } else if (diag.collecting()) {
    diag.Warning({Rel(dir, "features.csv"), 0, 0, ""}, "not checked: survey.json could not be read");
  }
  ReadLandmarks(dir, b, diag);
  ReadTruth(dir, b, kf, diag);
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
    const bool stereo = b.manifest.camera.stereo();
    std::vector<std::string> head = {"keyframe", "landmark", "u_top", "v_top", "u_bottom", "v_bottom"};
    if (!stereo) head.resize(4);
    CsvWriter w(head);
    for (const auto& f : b.features) {
      w.Add(f.keyframe).Add(f.landmark).Add(f.top.x()).Add(f.top.y());
      if (stereo) {
        if (f.has_bottom)
          w.Add(f.bottom.x()).Add(f.bottom.y());
        else
          w.AddEmpty().AddEmpty();
      }
      w.EndRow();
    }
    WriteFileAtomic(Rel(dir, "features.csv"), w.text());
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
