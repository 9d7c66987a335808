// Reading a sonar results folder back (results/sonar_files.h).
#include <cmath>
#include <filesystem>
#include <map>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "results/sonar_columns.h"
#include "results/sonar_files.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

double NumberOrNan(const JsonReader& r, const char* key) {
  const Json* v = r.value().Get(key);
  if (!v || v->is_null()) return std::nan("");
  return r.Number(key);
}

bool Bool(const JsonReader& r, const char* key) {
  const Json& v = r.Required(key);
  if (!v.is_bool()) r.Fail(v, key, "expected true or false");
  return v.as_bool();
}

// The columns of a CSV header, required in order of `names`.
std::vector<int> Columns(const CsvReader& c, const std::vector<std::string>& names) {
  std::vector<int> cols;
  for (const std::string& n : names) cols.push_back(c.Require(n));
  return cols;
}

double OptionalOrNan(const CsvReader& c, int col) { return c.OptionalDouble(col).value_or(std::nan("")); }

// ---- summary.json

void ReadEkfOptions(const JsonReader& o, SonarEkfOptions& e) {
  try {
    e.init = ParseSonarInit(o.String("init"));
  } catch (const OptionError& err) {
    o.Fail(o.Required("init"), "init", err.what());
  }
  e.hypotheses = static_cast<int>(o.Integer("hypotheses"));
  e.collapse_probability = o.Number("collapse_probability");
  e.max_delay_steps = static_cast<int>(o.Integer("max_delay_steps"));
  e.paper_elevation_sigma_fraction = o.Number("paper_elevation_sigma_fraction");
  e.joseph = Bool(o, "joseph");
  e.confirm_views = static_cast<int>(o.Integer("confirm_views"));
}

void ReadImageSummary(const JsonReader& s, SonarPipelineResult& p) {
  SonarImageRunResult& im = *p.images;
  if (const auto o = s.OptionalObject("options")) {
    p.image_options.tracker.gate_probability = o->Number("gate_probability");
    p.image_options.tracker.drop_misses = static_cast<int>(o->Integer("drop_misses"));
    p.image_options.detector.min_contrast = o->Number("min_contrast");
  }
  im.image_seconds = s.NumberOr("image_seconds", 0);
  im.detect_seconds = s.NumberOr("detect_seconds", 0);
  im.track_seconds = s.NumberOr("track_seconds", 0);
  const auto t = s.OptionalObject("truth");
  if (!t) return;
  im.has_truth = true;
  SonarImageEvaluation& e = im.evaluation;
  e.frames = static_cast<int>(t->Integer("frames_with_visible_features"));
  e.mean_detection_rate = t->Number("mean_detection_rate");
  e.min_detection_rate = t->Number("min_detection_rate");
  e.frames_below_90 = static_cast<int>(t->Integer("frames_below_90_percent"));
  e.clutter_per_frame = t->Number("clutter_per_frame");
  e.associations = static_cast<int>(t->Integer("associations"));
  e.wrong_associations = static_cast<int>(t->Integer("wrong_associations"));
  e.in_state_associations = static_cast<int>(t->Integer("in_state_associations"));
  e.wrong_in_state_associations = static_cast<int>(t->Integer("wrong_in_state_associations"));
  e.final_features = static_cast<int>(t->Integer("final_features"));
  e.final_features_with_truth = static_cast<int>(t->Integer("final_features_with_truth"));
  e.duplicate_features = static_cast<int>(t->Integer("duplicate_features"));
  e.final_mean_error = t->Number("final_mean_error");
  const Json& map = t->Required("truth_of_features");
  for (std::size_t i = 0; i < map.items().size(); ++i) {
    const JsonReader f(map.items()[i], t->file(), t->PathOf("truth_of_features") + "[" + std::to_string(i) + "]");
    im.truth_of[f.Integer("feature")] = f.Integer("truth_feature");
  }
}

void ReadSmootherSummary(const JsonReader& s, SonarPipelineResult& p) {
  SonarSmootherRun& run = *p.smoother;
  const JsonReader o = s.Object("options");
  p.smoother_options.max_iterations = static_cast<int>(o.Integer("max_iterations"));
  p.smoother_options.min_views = static_cast<int>(o.Integer("min_views"));
  p.smoother_options.max_weak_sigma_fraction = o.Number("max_weak_sigma_fraction");
  p.smoother_options.covariances = Bool(o, "covariances");
  SonarSmootherResult& r = run.result;
  r.measurements_used = static_cast<int>(s.Integer("measurements_used"));
  r.residual_blocks = static_cast<int>(s.Integer("residual_blocks"));
  r.initial_cost = s.Number("initial_cost");
  r.final_cost = s.Number("final_cost");
  r.iterations = static_cast<int>(s.Integer("iterations"));
  r.converged = Bool(s, "converged");
  r.covariance_ok = Bool(s, "covariance_ok");
  r.solve_seconds = s.Number("solve_seconds");
  r.covariance_seconds = s.Number("covariance_seconds");
  r.report = s.String("report");
  const auto t = s.OptionalObject("truth");
  if (!t) return;
  SonarSmootherErrors e;
  e.position = t->Number("final_position_error");
  e.rotation = t->Number("final_rotation_error");
  e.mean_position = t->Number("mean_position_error");
  e.pose_nees = NumberOrNan(*t, "final_pose_nees");
  e.mean_pose_nees = NumberOrNan(*t, "mean_pose_nees");
  e.features = static_cast<int>(t->Integer("features_with_truth"));
  e.mean_feature_error = t->Number("final_mean_feature_error");
  e.max_feature_error = t->Number("final_max_feature_error");
  e.mean_point_nees = NumberOrNan(*t, "mean_point_nees");
  e.feature_nees = NumberOrNan(*t, "feature_nees");
  e.feature_nees_dof = static_cast<int>(t->Integer("feature_nees_dof"));
  e.joint_nees = NumberOrNan(*t, "joint_nees");
  e.joint_nees_dof = static_cast<int>(t->Integer("joint_nees_dof"));
  run.errors = e;
}

void ReadSummary(const std::string& dir, SonarPipelineResult& p) {
  const std::string path = Path(dir, kSonarSummaryJson);
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader r(doc, path);
  if (r.String("format") != "hull-sonar-result") {
    r.Fail(r.Required("format"), "format", "expected \"hull-sonar-result\"");
  }
  if (r.Integer("version") != 1) r.Fail(r.Required("version"), "version", "unsupported; this reader knows 1");
  p.sequence = r.String("sequence");
  const std::string source = r.String("source");
  if (source != "images" && source != "measurements")
    r.Fail(r.Required("source"), "source", "expected images or measurements");
  p.from_images = source == "images";
  ReadEkfOptions(r.Object("options"), p.options.ekf);
  p.image_options.run = p.options;
  p.measurements = r.Integer("measurements");
  p.run.filter_seconds = r.Number("filter_seconds");
  if (const auto im = r.OptionalObject("images")) {
    p.images.emplace();
    ReadImageSummary(*im, p);
  }
  if (const auto sm = r.OptionalObject("smoother")) {
    p.smoother.emplace();
    ReadSmootherSummary(*sm, p);
  }
}

// ---- poses.csv

void ReadPoses(const std::string& dir, SonarRunResult& r) {
  const std::string path = Path(dir, kSonarPosesCsv);
  const std::string text = ReadFileToString(path);
  CsvReader c(text, path);
  r.has_truth = c.Find("position_error") >= 0;
  const std::vector<std::string> names = SonarPoseColumns(r.has_truth);
  const std::vector<int> col = Columns(c, names);
  while (c.Next()) {
    SonarStepRecord s;
    SonarStepEstimate& e = s.estimate;
    std::size_t k = 0;
    e.step = c.Int(col[k++]);
    for (int i = 0; i < 6; ++i) e.pose[i] = c.Double(col[k++]);
    k += 6;  // the standard deviations: the covariance's diagonal
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) e.pose_covariance(i, j) = e.pose_covariance(j, i) = c.Double(col[k++]);
    }
    for (int i = 0; i < 6; ++i) s.dead_reckoning[i] = c.Double(col[k++]);
    e.measurements = static_cast<int>(c.Int(col[k++]));
    e.updated = static_cast<int>(c.Int(col[k++]));
    e.initialised = static_cast<int>(c.Int(col[k++]));
    e.pending = static_cast<int>(c.Int(col[k++]));
    e.nis = c.Double(col[k++]);
    e.nis_dof = static_cast<int>(c.Int(col[k++]));
    if (r.has_truth) {
      SonarStepErrors x;
      x.position = c.Double(col[k++]);
      x.rotation = c.Double(col[k++]);
      x.dr_position = c.Double(col[k++]);
      x.dr_rotation = c.Double(col[k++]);
      x.pose_nees = c.Double(col[k++]);
      x.features = static_cast<int>(c.Int(col[k++]));
      x.mean_feature_error = c.Double(col[k++]);
      x.max_feature_error = c.Double(col[k++]);
      x.joint_nees = OptionalOrNan(c, col[k++]);
      x.joint_nees_dof = static_cast<int>(c.Int(col[k++]));
      s.errors = x;
    }
    r.steps.push_back(std::move(s));
  }
  if (r.steps.empty()) throw InputError({path, 0, 0, ""}, "holds no steps");
}

// ---- features.csv

void ReadFeatures(const std::string& dir, SonarRunResult& r) {
  const std::string path = Path(dir, kSonarFeaturesCsv);
  const std::string text = ReadFileToString(path);
  CsvReader c(text, path);
  const std::vector<int> col = Columns(c, SonarFeatureColumns(r.has_truth));
  std::map<std::int64_t, std::size_t> index;  // step -> its record
  for (std::size_t k = 0; k < r.steps.size(); ++k) index[r.steps[k].estimate.step] = k;
  const std::int64_t last = r.steps.back().estimate.step;
  while (c.Next()) {
    const std::int64_t step = c.Int(col[0]);
    const auto it = index.find(step);
    if (it == index.end()) c.Fail(col[0], "step " + std::to_string(step) + " is not in poses.csv");
    SonarFeatureEstimate f;
    f.id = c.Int(col[1]);
    f.in_state = c.Int(col[2]) != 0;
    for (int i = 0; i < 3; ++i) f.position[i] = c.Double(col[static_cast<std::size_t>(3 + i)]);
    std::size_t k = 6;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) f.covariance(i, j) = f.covariance(j, i) = c.Double(col[k++]);
    }
    f.observations = static_cast<int>(c.Int(col[k++]));
    f.first_step = c.Int(col[k++]);
    const double error = r.has_truth ? OptionalOrNan(c, col[k]) : std::nan("");
    SonarStepRecord& s = r.steps[it->second];
    s.features.push_back(f);
    s.feature_errors.push_back(error);
    if (step == last) {
      r.final_features.push_back(f);
      r.final_feature_errors.push_back(error);
    }
  }
}

// ---- detections.csv

void ReadDetections(const std::string& dir, SonarImageRunResult& im, std::size_t steps) {
  const std::string path = Path(dir, kSonarDetectionsCsv);
  const std::string text = ReadFileToString(path);
  CsvReader c(text, path);
  im.has_truth = im.has_truth || c.Find("truth_feature") >= 0;
  const std::vector<int> col = Columns(c, SonarDetectionColumns(c.Find("truth_feature") >= 0));
  im.steps.resize(steps);
  while (c.Next()) {
    const std::int64_t k = c.Int(col[0]);
    if (k < 0 || k >= static_cast<std::int64_t>(steps)) c.Fail(col[0], "not a step of poses.csv");
    SonarImageStep& s = im.steps[static_cast<std::size_t>(k)];
    if (c.Int(col[1]) != static_cast<std::int64_t>(s.detections.size())) c.Fail(col[1], "detections out of order");
    SonarDetection d;
    d.row = c.Double(col[2]);
    d.col = c.Double(col[3]);
    d.range = c.Double(col[4]);
    d.azimuth = c.Double(col[5]);
    d.strength = c.Double(col[6]);
    d.contrast = c.Double(col[7]);
    d.covariance = Eigen::Vector2d(std::pow(c.Double(col[8]), 2), std::pow(c.Double(col[9]), 2)).asDiagonal();
    s.detections.push_back(d);
    s.track.feature.push_back(c.Int(col[10]));
    try {
      s.track.pairing.push_back(ParseSonarPairing(std::string(c.Field(col[11]))));
    } catch (const std::invalid_argument& e) {
      c.Fail(col[11], e.what());
    }
    if (col.size() > 12) s.label.push_back(c.OptionalInt(col[12]).value_or(-1));
  }
}

// ---- smoother_poses.csv, smoother_features.csv

void ReadSmootherPoses(const std::string& dir, SonarSmootherRun& run) {
  const std::string path = Path(dir, kSonarSmootherPosesCsv);
  const std::string text = ReadFileToString(path);
  CsvReader c(text, path);
  const bool truth = c.Find("position_error") >= 0;
  const std::vector<int> col = Columns(c, SonarSmootherPoseColumns(truth));
  while (c.Next()) {
    Vector6d x;
    Matrix6d C;
    std::size_t k = 1;
    for (int i = 0; i < 6; ++i) x[i] = c.Double(col[k++]);
    k += 6;
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) C(i, j) = C(j, i) = OptionalOrNan(c, col[k++]);
    }
    run.result.poses.push_back(x);
    run.result.pose_covariances.push_back(C);
    if (truth) {
      run.pose_position_errors.push_back(c.Double(col[k++]));
      run.pose_rotation_errors.push_back(c.Double(col[k++]));
      run.pose_nees.push_back(OptionalOrNan(c, col[k++]));
    }
  }
}

void ReadSmootherFeatures(const std::string& dir, SonarSmootherRun& run) {
  const std::string path = Path(dir, kSonarSmootherFeaturesCsv);
  const std::string text = ReadFileToString(path);
  CsvReader c(text, path);
  const bool truth = c.Find("error") >= 0;
  const std::vector<int> col = Columns(c, SonarSmootherFeatureColumns(truth));
  while (c.Next()) {
    SonarSmoothedFeature f;
    f.id = c.Int(col[1]);
    f.smoothed = c.Int(col[2]) != 0;
    for (int i = 0; i < 3; ++i) f.position[i] = c.Double(col[static_cast<std::size_t>(3 + i)]);
    std::size_t k = 6;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) f.covariance(i, j) = f.covariance(j, i) = OptionalOrNan(c, col[k++]);
    }
    f.views = static_cast<int>(c.Int(col[k++]));
    f.weak_sigma = OptionalOrNan(c, col[k++]);
    run.result.features.push_back(f);
    if (truth) run.feature_errors.push_back(OptionalOrNan(c, col[k]));
  }
}

}  // namespace

SonarPipelineResult ReadSonarResults(const std::string& dir) {
  std::vector<std::string> files;
  for (const char* f : {kSonarSummaryJson, kSonarPosesCsv, kSonarFeaturesCsv, kSonarDetectionsCsv,
                        kSonarSmootherPosesCsv, kSonarSmootherFeaturesCsv}) {
    files.push_back(Path(dir, f));
  }
  CheckResultsFiles(files, "the sonar results in " + dir);
  SonarPipelineResult p;
  ReadSummary(dir, p);
  p.run.options = p.options.ekf;
  ReadPoses(dir, p.run);
  ReadFeatures(dir, p.run);
  if (p.images) {
    ReadDetections(dir, *p.images, p.run.steps.size());
    p.images->run = p.run;
  }
  if (p.smoother) {
    ReadSmootherPoses(dir, *p.smoother);
    ReadSmootherFeatures(dir, *p.smoother);
  }
  return p;
}

}  // namespace hull
