#include "results/adjustment_files.h"

#include <cmath>
#include <filesystem>
#include <utility>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

Json Vec(const Vector6d& v) {
  Json a = Json::Array();
  for (int i = 0; i < 6; ++i) a.Push(Json(v[i]));
  return a;
}

Vector6d Vec6(const JsonReader& r, const char* key) {
  const auto v = r.Numbers(key, 6);
  return Eigen::Map<const Vector6d>(v.data());
}

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

std::optional<double> Finite(double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; }

// The upper triangle of a landmark covariance in landmarks.csv.
constexpr std::pair<int, int> kCovarianceEntries[6] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
constexpr const char* kCovarianceColumns[6] = {"cov_xx", "cov_xy", "cov_xz", "cov_yy", "cov_yz", "cov_zz"};

}  // namespace

void WriteAdjustmentResult(const AdjustmentResult& r, const std::string& dir) {
  fs::create_directories(dir);
  Json root = Json::Object();
  root.Set("format", "hull-adjustment");
  root.Set("version", AdjustmentResult::kFormatVersion);
  root.Set("model", SurfaceModelName(r.options.model));
  Json inputs = Json::Object();
  inputs.Set("bundle", r.bundle_path);
  inputs.Set("mesh", r.mesh_path);
  inputs.Set("mesh_scale", r.mesh_scale);
  root.Set("inputs", inputs);
  Json opt = Json::Object();
  opt.Set("sigma0", r.options.sigma0);
  opt.Set("sigma1", r.options.sigma1);
  opt.Set("labels", LabelRuleName(r.options.labels));
  opt.Set("lookup", r.options.lookup == SurfaceLookup::kClosestFace ? "closest-face" : "nearest-vertex");
  opt.Set("huber_sigmas", r.options.huber_sigmas);
  opt.Set("estimate_servo", r.options.estimate_servo);
  opt.Set("estimate_extrinsic", r.options.estimate_extrinsic);
  opt.Set("estimate_model_pose", r.options.estimate_model_pose);
  opt.Set("use_dvl", r.options.use_dvl);
  opt.Set("max_iterations", r.options.max_iterations);
  opt.Set("max_initial_deviation", r.options.max_initial_deviation);
  root.Set("options", opt);
  Json sum = Json::Object();
  sum.Set("termination", r.termination);
  sum.Set("converged", r.converged);
  sum.Set("initial_cost", r.initial_cost);
  sum.Set("final_cost", r.final_cost);
  sum.Set("iterations", static_cast<int>(r.iterations.empty() ? 0 : r.iterations.back().iteration));
  sum.Set("residual_blocks", r.num_residual_blocks);
  sum.Set("landmarks", static_cast<std::int64_t>(r.landmarks.size()));
  sum.Set("landmarks_skipped", r.num_landmarks_skipped);
  sum.Set("landmarks_off_model", r.num_landmarks_off_model);
  sum.Set("observations_rejected", r.observations_rejected);
  sum.Set("labels_off_by_cavity", r.num_labels_off_by_cavity);
  sum.Set("fraction_on_surface", r.FractionOnSurface());
  sum.Set("decision_boundary", r.options.DecisionBoundary());
  sum.Set("covariance", CovarianceMethodName(r.covariance_method));
  if (!r.covariance_note.empty()) sum.Set("covariance_note", r.covariance_note);
  root.Set("summary", sum);
  root.Set("x_gM", Vec(r.x_gM));
  root.Set("x_gM_initial", Vec(r.x_gM_initial));
  root.Set("x_s_cT", Vec(r.x_s_cT));
  root.Set("x_s_cT_initial", Vec(r.x_s_cT_initial));
  Json its = Json::Array();
  for (const auto& it : r.iterations) {
    Json j = Json::Object();
    j.Set("iteration", it.iteration);
    j.Set("cost", it.cost);
    j.Set("fraction_on_surface", it.fraction_on_surface);
    its.Push(j);
  }
  root.Set("iterations", its);
  WriteFileAtomic(Path(dir, "adjustment.json"), root.Dump());
  // Wall times apart, so that adjustment.json and the CSV files of the same
  // run are byte-identical from one run to the next.
  Json timing = Json::Object();
  timing.Set("format", "hull-adjustment-timing");
  timing.Set("version", 1);
  timing.Set("seconds", r.seconds);
  timing.Set("solver_seconds", r.solver_seconds);
  timing.Set("covariance_seconds", r.covariance_seconds);
  Json per = Json::Array();
  for (const auto& it : r.iterations) per.Push(Json(it.seconds));
  timing.Set("iteration_seconds", per);
  WriteFileAtomic(Path(dir, "timing.json"), timing.Dump());

  CsvWriter poses({"keyframe", "x", "y", "z", "roll", "pitch", "yaw", "servo"});
  for (std::size_t i = 0; i < r.poses.size(); ++i) {
    poses.Add(r.keyframes[i]);
    for (int k = 0; k < 6; ++k) poses.Add(r.poses[i][k]);
    poses.Add(r.servo[i]);
    poses.EndRow();
  }
  WriteFileAtomic(Path(dir, "poses.csv"), poses.text());
  CsvWriter lms({"landmark", "x", "y", "z", "label", "deviation", "observations", "sigma_h", "cov_xx", "cov_xy",
                 "cov_xz", "cov_yy", "cov_yz", "cov_zz"});
  for (const auto& l : r.landmarks) {
    lms.Add(l.id).Add(l.p.x()).Add(l.p.y()).Add(l.p.z()).Add(l.label).Add(l.deviation).Add(l.observations);
    lms.AddOptional(Finite(l.sigma_h));
    for (const auto& [i, j] : kCovarianceEntries) lms.AddOptional(Finite(l.covariance(i, j)));
    lms.EndRow();
  }
  WriteFileAtomic(Path(dir, "landmarks.csv"), lms.text());
  CsvWriter dvl({"keyframe", "beam", "measured", "initial", "final"});
  for (const auto& d : r.dvl) {
    dvl.Add(d.keyframe).Add(d.beam).Add(d.measured).AddOptional(Finite(d.initial)).AddOptional(Finite(d.final));
    dvl.EndRow();
  }
  WriteFileAtomic(Path(dir, "dvl_residuals.csv"), dvl.text());
}

namespace {

// adjustment.json: the model, inputs, options, summary, poses and iteration log.
void ReadAdjustmentJson(const std::string& dir, AdjustmentResult& r) {
  const std::string jpath = Path(dir, "adjustment.json");
  const Json doc = Json::Parse(ReadFileToString(jpath), jpath);
  JsonReader root(doc, jpath);
  if (root.String("format") != "hull-adjustment") {
    root.Fail(root.Required("format"), "format", "expected \"hull-adjustment\"");
  }
  if (root.Integer("version") != AdjustmentResult::kFormatVersion) {
    root.Fail(root.Required("version"), "version", "unsupported version; this reader knows 1");
  }
  try {
    r.options.model = ParseSurfaceModel(root.String("model"));
  } catch (const OptionError& e) {
    root.Fail(root.Required("model"), "model", e.what());
  }
  if (auto in = root.OptionalObject("inputs")) {
    r.bundle_path = in->OptionalString("bundle").value_or("");
    r.mesh_path = in->OptionalString("mesh").value_or("");
    r.mesh_scale = in->NumberOr("mesh_scale", 1.0);
  }
  const JsonReader opt = root.Object("options");
  r.options.sigma0 = opt.Number("sigma0");
  r.options.sigma1 = opt.Number("sigma1");
  if (auto labels = opt.OptionalString("labels")) {
    try {
      r.options.labels = ParseLabelRule(*labels);
    } catch (const OptionError& e) {
      opt.Fail(opt.Required("labels"), "labels", e.what());
    }
  } else {
    r.options.labels = LabelRule::kEstimate;  // older results: the label by the estimate
  }
  r.options.lookup =
      opt.String("lookup") == "nearest-vertex" ? SurfaceLookup::kNearestVertex : SurfaceLookup::kClosestFace;
  r.options.huber_sigmas = opt.Number("huber_sigmas");
  r.options.max_iterations = static_cast<int>(opt.Integer("max_iterations"));
  r.options.max_initial_deviation = opt.NumberOr("max_initial_deviation", 0);  // older results: no limit
  const JsonReader sum = root.Object("summary");
  r.termination = sum.String("termination");
  r.converged = sum.Required("converged").as_bool();
  // Older results kept the wall times in adjustment.json.
  r.seconds = sum.NumberOr("seconds", 0);
  r.solver_seconds = sum.NumberOr("solver_seconds", 0);
  r.initial_cost = sum.Number("initial_cost");
  r.final_cost = sum.Number("final_cost");
  r.num_residual_blocks = static_cast<int>(sum.Integer("residual_blocks"));
  r.num_landmarks_skipped = static_cast<int>(sum.Integer("landmarks_skipped"));
  r.num_landmarks_off_model = static_cast<int>(sum.NumberOr("landmarks_off_model", 0));  // older results: none
  r.num_labels_off_by_cavity = static_cast<int>(sum.NumberOr("labels_off_by_cavity", 0));
  if (auto m = sum.OptionalString("covariance")) {
    try {
      r.covariance_method = ParseCovarianceMethod(*m);
    } catch (const OptionError& e) {
      sum.Fail(sum.Required("covariance"), "covariance", e.what());
    }
  }
  r.covariance_note = sum.OptionalString("covariance_note").value_or("");
  r.observations_rejected = static_cast<int>(sum.NumberOr("observations_rejected", 0));
  r.x_gM = Vec6(root, "x_gM");
  r.x_gM_initial = Vec6(root, "x_gM_initial");
  r.x_s_cT = Vec6(root, "x_s_cT");
  r.x_s_cT_initial = Vec6(root, "x_s_cT_initial");
  const Json& its = root.Required("iterations");
  for (std::size_t i = 0; i < its.items().size(); ++i) {
    JsonReader it(its.items()[i], jpath, "iterations[" + std::to_string(i) + "]");
    r.iterations.push_back({static_cast<int>(it.Integer("iteration")), it.Number("cost"), it.NumberOr("seconds", 0),
                            it.Number("fraction_on_surface")});
  }
}

// timing.json (absent in older results).
void ReadTimingJson(const std::string& dir, AdjustmentResult& r) {
  const std::string tpath = Path(dir, "timing.json");
  if (!fs::exists(tpath)) return;
  const Json tdoc = Json::Parse(ReadFileToString(tpath), tpath);
  JsonReader t(tdoc, tpath);
  r.seconds = t.Number("seconds");
  r.solver_seconds = t.Number("solver_seconds");
  r.covariance_seconds = t.NumberOr("covariance_seconds", 0);
  const auto per = t.Numbers("iteration_seconds", static_cast<int>(r.iterations.size()));
  for (std::size_t i = 0; i < per.size(); ++i) r.iterations[i].seconds = per[i];
}

void ReadPosesCsv(const std::string& dir, AdjustmentResult& r) {
  const std::string p = Path(dir, "poses.csv");
  const std::string text = ReadFileToString(p);
  CsvReader c(text, p);
  const int k = c.Require("keyframe");
  const int cols[6] = {c.Require("x"),    c.Require("y"),     c.Require("z"),
                       c.Require("roll"), c.Require("pitch"), c.Require("yaw")};
  const int s = c.Require("servo");
  while (c.Next()) {
    r.keyframes.push_back(c.Int(k));
    Vector6d x;
    for (int i = 0; i < 6; ++i) x[i] = c.Double(cols[i]);
    r.poses.push_back(x);
    r.servo.push_back(c.Double(s));
  }
}

void ReadLandmarksCsv(const std::string& dir, AdjustmentResult& r) {
  const std::string p = Path(dir, "landmarks.csv");
  const std::string text = ReadFileToString(p);
  CsvReader c(text, p);
  const int id = c.Require("landmark"), x = c.Require("x"), y = c.Require("y"), z = c.Require("z");
  const int label = c.Require("label"), dev = c.Require("deviation"), obs = c.Require("observations");
  const int sigma = c.Find("sigma_h");
  int cov[6];
  for (int k = 0; k < 6; ++k) cov[k] = c.Find(kCovarianceColumns[k]);
  while (c.Next()) {
    LandmarkEstimate l;
    l.id = c.Int(id);
    l.p = {c.Double(x), c.Double(y), c.Double(z)};
    l.label = static_cast<int>(c.Int(label));
    if (l.label != 0 && l.label != 1) c.Fail(label, "expected 0 or 1");
    l.deviation = c.Double(dev);
    l.observations = static_cast<int>(c.Int(obs));
    l.sigma_h = c.OptionalDouble(sigma).value_or(std::nan(""));
    for (int k = 0; k < 6; ++k) {
      const auto [i, j] = kCovarianceEntries[k];
      l.covariance(i, j) = l.covariance(j, i) = c.OptionalDouble(cov[k]).value_or(std::nan(""));
    }
    r.landmarks.push_back(l);
  }
}

void ReadDvlResidualsCsv(const std::string& dir, AdjustmentResult& r) {
  const std::string p = Path(dir, "dvl_residuals.csv");
  const std::string text = ReadFileToString(p);
  CsvReader c(text, p);
  const int k = c.Require("keyframe"), b = c.Require("beam"), m = c.Require("measured");
  const int i0 = c.Require("initial"), i1 = c.Require("final");
  while (c.Next()) {
    DvlResidual d;
    d.keyframe = c.Int(k);
    d.beam = static_cast<int>(c.Int(b));
    d.measured = c.Double(m);
    d.initial = c.OptionalDouble(i0).value_or(std::nan(""));
    d.final = c.OptionalDouble(i1).value_or(std::nan(""));
    r.dvl.push_back(d);
  }
}

}  // namespace

AdjustmentResult ReadAdjustmentResult(const std::string& dir) {
  std::vector<std::string> files;
  for (const std::string& name : AdjustmentFileNames()) files.push_back(Path(dir, name.c_str()));
  CheckResultsFiles(files, "the adjustment in " + dir);
  AdjustmentResult r;
  ReadAdjustmentJson(dir, r);
  ReadTimingJson(dir, r);
  ReadPosesCsv(dir, r);
  ReadLandmarksCsv(dir, r);
  ReadDvlResidualsCsv(dir, r);
  return r;
}

std::vector<std::string> AdjustmentFileNames() {
  return {"adjustment.json", "timing.json", "poses.csv", "landmarks.csv", "dvl_residuals.csv"};
}

void SaveAdjustmentResults(const AdjustmentResult& r, const OutputFolder& out, ResultsRun run) {
  if (!r.bundle_path.empty()) run.AddSurvey("bundle", r.bundle_path);
  if (!r.mesh_path.empty()) run.AddFile("mesh", r.mesh_path);
  WriteResultsFolder(out, run, [&](const std::string& tmp) { WriteAdjustmentResult(r, tmp); });
}

}  // namespace hull
