// Writing a sonar results folder (results/sonar_files.h).
#include "results/sonar_files.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "results/sonar_columns.h"
#include "sonar/sonar_consistency.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

Json ArrayOf(const Vector6d& v) {
  Json a = Json::Array();
  for (int i = 0; i < 6; ++i) a.Push(Json(v[i]));
  return a;
}

Json Finite(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

void AddFinite(CsvWriter& csv, double v) {
  if (std::isfinite(v)) {
    csv.Add(v);
  } else {
    csv.AddEmpty();
  }
}

// ---- poses.csv, features.csv

void AddPoseRow(CsvWriter& poses, const SonarStepRecord& s, bool truth) {
  const SonarStepEstimate& e = s.estimate;
  poses.Add(e.step);
  for (int i = 0; i < 6; ++i) poses.Add(e.pose[i]);
  for (int i = 0; i < 6; ++i) poses.Add(std::sqrt(e.pose_covariance(i, i)));
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) poses.Add(e.pose_covariance(i, j));
  }
  for (int i = 0; i < 6; ++i) poses.Add(s.dead_reckoning[i]);
  poses.Add(e.measurements).Add(e.updated).Add(e.initialised).Add(e.pending).Add(e.nis).Add(e.nis_dof);
  if (truth) {
    const SonarStepErrors& x = *s.errors;
    poses.Add(x.position).Add(x.rotation).Add(x.dr_position).Add(x.dr_rotation).Add(x.pose_nees).Add(x.features);
    poses.Add(x.mean_feature_error).Add(x.max_feature_error);
    AddFinite(poses, x.joint_nees);
    poses.Add(x.joint_nees_dof);
  }
  poses.EndRow();
}

std::string PosesCsv(const SonarRunResult& r) {
  CsvWriter poses(SonarPoseColumns(r.has_truth));
  for (const SonarStepRecord& s : r.steps) AddPoseRow(poses, s, r.has_truth);
  return poses.Take();
}

void AddFeatureRows(CsvWriter& features, std::int64_t step, const std::vector<SonarFeatureEstimate>& fs,
                    const std::vector<double>& errors, bool truth) {
  for (std::size_t n = 0; n < fs.size(); ++n) {
    const SonarFeatureEstimate& f = fs[n];
    features.Add(step).Add(f.id).Add(f.in_state ? 1 : 0);
    for (int i = 0; i < 3; ++i) features.Add(f.position[i]);
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) features.Add(f.covariance(i, j));
    }
    features.Add(f.observations).Add(f.first_step);
    if (truth) {
      if (n < errors.size() && std::isfinite(errors[n])) {
        features.Add(errors[n]);
      } else {
        features.AddEmpty();
      }
    }
    features.EndRow();
  }
}

std::string FeaturesCsv(const SonarRunResult& r, bool final_only) {
  CsvWriter features(SonarFeatureColumns(r.has_truth));
  if (final_only) {
    AddFeatureRows(features, r.steps.back().estimate.step, r.final_features, r.final_feature_errors, r.has_truth);
  } else {
    for (const SonarStepRecord& s : r.steps)
      AddFeatureRows(features, s.estimate.step, s.features, s.feature_errors, r.has_truth);
  }
  return features.Take();
}

// ---- detections.csv

std::string DetectionsCsv(const SonarImageRunResult& r) {
  CsvWriter csv(SonarDetectionColumns(r.has_truth));
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const SonarImageStep& s = r.steps[k];
    for (std::size_t j = 0; j < s.detections.size(); ++j) {
      const SonarDetection& d = s.detections[j];
      csv.Add(static_cast<std::int64_t>(k)).Add(static_cast<std::int64_t>(j)).Add(d.row).Add(d.col);
      csv.Add(d.range).Add(d.azimuth).Add(d.strength).Add(d.contrast);
      csv.Add(std::sqrt(d.covariance(0, 0))).Add(std::sqrt(d.covariance(1, 1)));
      csv.Add(s.track.feature[j]).Add(SonarPairingName(s.track.pairing[j]));
      if (r.has_truth) {
        if (s.label[j] >= 0) {
          csv.Add(s.label[j]);
        } else {
          csv.AddEmpty();
        }
      }
      csv.EndRow();
    }
  }
  return csv.Take();
}

// ---- smoother_poses.csv, smoother_features.csv

std::string SmootherPosesCsv(const SonarSmootherRun& run) {
  const SonarSmootherResult& r = run.result;
  const bool truth = run.errors.has_value();
  CsvWriter csv(SonarSmootherPoseColumns(truth));
  for (std::size_t k = 0; k < r.poses.size(); ++k) {
    const Matrix6d& C = r.pose_covariances[k];
    csv.Add(static_cast<std::int64_t>(k));
    for (int i = 0; i < 6; ++i) csv.Add(r.poses[k][i]);
    for (int i = 0; i < 6; ++i) AddFinite(csv, std::sqrt(C(i, i)));
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) AddFinite(csv, C(i, j));
    }
    if (truth) {
      csv.Add(run.pose_position_errors[k]);
      csv.Add(run.pose_rotation_errors[k]);
      AddFinite(csv, run.pose_nees[k]);
    }
    csv.EndRow();
  }
  return csv.Take();
}

std::string SmootherFeaturesCsv(const SonarSmootherRun& run, std::int64_t last_step) {
  const SonarSmootherResult& r = run.result;
  const bool truth = run.errors.has_value();
  CsvWriter csv(SonarSmootherFeatureColumns(truth));
  for (std::size_t n = 0; n < r.features.size(); ++n) {
    const SonarSmoothedFeature& f = r.features[n];
    csv.Add(last_step).Add(f.id).Add(f.smoothed ? 1 : 0);
    for (int i = 0; i < 3; ++i) csv.Add(f.position[i]);
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) AddFinite(csv, f.covariance(i, j));
    }
    csv.Add(f.views);
    AddFinite(csv, f.weak_sigma);
    if (truth) AddFinite(csv, run.feature_errors[n]);
    csv.EndRow();
  }
  return csv.Take();
}

// ---- summary.json

Json OptionsJson(const SonarEkfOptions& o) {
  Json opt = Json::Object();
  opt.Set("init", Json(SonarInitName(o.init)));
  opt.Set("hypotheses", Json(o.hypotheses));
  opt.Set("collapse_probability", Json(o.collapse_probability));
  opt.Set("max_delay_steps", Json(o.max_delay_steps));
  opt.Set("paper_elevation_sigma_fraction", Json(o.paper_elevation_sigma_fraction));
  opt.Set("joseph", Json(o.joseph));
  opt.Set("confirm_views", Json(o.confirm_views));
  return opt;
}

Json TruthJson(const SonarRunResult& r) {
  Json t = Json::Object();
  const SonarStepErrors& e = *r.steps.back().errors;
  t.Set("final_position_error", Json(e.position));
  t.Set("final_rotation_error", Json(e.rotation));
  t.Set("final_dead_reckoning_position_error", Json(e.dr_position));
  t.Set("final_dead_reckoning_rotation_error", Json(e.dr_rotation));
  t.Set("final_mean_feature_error", Json(e.mean_feature_error));
  t.Set("final_max_feature_error", Json(e.max_feature_error));
  double first_mean = NAN;
  for (const SonarStepRecord& s : r.steps) {
    if (s.errors->features > 0) {
      first_mean = s.errors->mean_feature_error;
      break;
    }
  }
  t.Set("first_mean_feature_error", Finite(first_mean));
  double nees = 0, dof = 0, pose_nees = 0;
  for (const SonarStepRecord& s : r.steps) {
    if (std::isfinite(s.errors->joint_nees)) {
      nees += s.errors->joint_nees;
      dof += s.errors->joint_nees_dof;
    }
    pose_nees += s.errors->pose_nees;
  }
  t.Set("mean_normalised_joint_nees", Finite(dof > 0 ? nees / dof : NAN));
  t.Set("mean_pose_nees", Json(pose_nees / static_cast<double>(r.steps.size())));
  Json per = Json::Array();
  for (std::size_t n = 0; n < r.final_features.size(); ++n) {
    Json f = Json::Object();
    f.Set("feature", Json(r.final_features[n].id));
    f.Set("error", Finite(r.final_feature_errors[n]));
    per.Push(std::move(f));
  }
  t.Set("final_feature_errors", std::move(per));
  return t;
}

Json ImageTruthJson(const SonarImageRunResult& r) {
  const SonarImageEvaluation& e = r.evaluation;
  Json t = Json::Object();
  t.Set("frames_with_visible_features", Json(e.frames));
  t.Set("mean_detection_rate", Json(e.mean_detection_rate));
  t.Set("min_detection_rate", Json(e.min_detection_rate));
  t.Set("frames_below_90_percent", Json(e.frames_below_90));
  t.Set("clutter_per_frame", Json(e.clutter_per_frame));
  t.Set("associations", Json(e.associations));
  t.Set("wrong_associations", Json(e.wrong_associations));
  t.Set("in_state_associations", Json(e.in_state_associations));
  t.Set("wrong_in_state_associations", Json(e.wrong_in_state_associations));
  t.Set("final_features", Json(e.final_features));
  t.Set("final_features_with_truth", Json(e.final_features_with_truth));
  t.Set("duplicate_features", Json(e.duplicate_features));
  t.Set("final_mean_error", Json(e.final_mean_error));
  Json map = Json::Array();
  for (const auto& [feature, truth] : r.truth_of) {
    if (truth < 0) continue;
    Json f = Json::Object();
    f.Set("feature", Json(feature));
    f.Set("truth_feature", Json(truth));
    map.Push(std::move(f));
  }
  t.Set("truth_of_features", std::move(map));
  return t;
}

// Counts, timings, the chain's options and, with truth, the evaluation.
Json ImageSummaryJson(const SonarImageRunResult& r, const SonarImageRunOptions& options) {
  Json o = Json::Object();
  Json opt = Json::Object();
  opt.Set("gate_probability", Json(options.tracker.gate_probability));
  opt.Set("drop_misses", Json(options.tracker.drop_misses));
  opt.Set("min_contrast", Json(options.detector.min_contrast));
  o.Set("options", std::move(opt));
  std::int64_t detections = 0, in_state = 0, waiting = 0, started = 0, dropped = 0, fallbacks = 0;
  for (const SonarImageStep& s : r.steps) {
    detections += static_cast<std::int64_t>(s.detections.size());
    in_state += s.track.paired_in_state;
    waiting += s.track.paired_waiting;
    started += s.track.started;
    dropped += static_cast<std::int64_t>(s.track.dropped.size());
    fallbacks += s.track.jcbb_gave_up;
  }
  o.Set("detections", Json(detections));
  o.Set("paired_in_state", Json(in_state));
  o.Set("paired_waiting", Json(waiting));
  o.Set("features_started", Json(started));
  o.Set("features_dropped", Json(dropped));
  o.Set("jcbb_gave_up_steps", Json(fallbacks));
  o.Set("image_seconds", Json(r.image_seconds));
  o.Set("detect_seconds", Json(r.detect_seconds));
  o.Set("track_seconds", Json(r.track_seconds));
  if (r.has_truth) o.Set("truth", ImageTruthJson(r));
  return o;
}

Json SmootherTruthJson(const SonarSmootherErrors& e) {
  Json t = Json::Object();
  t.Set("final_position_error", Json(e.position));
  t.Set("final_rotation_error", Json(e.rotation));
  t.Set("mean_position_error", Json(e.mean_position));
  t.Set("final_pose_nees", Finite(e.pose_nees));
  t.Set("mean_pose_nees", Finite(e.mean_pose_nees));
  t.Set("features_with_truth", Json(e.features));
  t.Set("final_mean_feature_error", Json(e.mean_feature_error));
  t.Set("final_max_feature_error", Json(e.max_feature_error));
  t.Set("mean_point_nees", Finite(e.mean_point_nees));
  t.Set("feature_nees", Finite(e.feature_nees));
  t.Set("feature_nees_dof", Json(e.feature_nees_dof));
  t.Set("joint_nees", Finite(e.joint_nees));
  t.Set("joint_nees_dof", Json(e.joint_nees_dof));
  t.Set("normalised_joint_nees", Finite(e.joint_nees_dof > 0 ? e.joint_nees / e.joint_nees_dof : NAN));
  return t;
}

// Options, counts, costs, timing and, with truth, the errors and NEES.
Json SmootherSummaryJson(const SonarSmootherRun& run, const SonarSmootherOptions& options) {
  const SonarSmootherResult& r = run.result;
  Json s = Json::Object();
  Json opt = Json::Object();
  opt.Set("max_iterations", Json(options.max_iterations));
  opt.Set("min_views", Json(options.min_views));
  opt.Set("max_weak_sigma_fraction", Json(options.max_weak_sigma_fraction));
  opt.Set("covariances", Json(options.covariances));
  s.Set("options", std::move(opt));
  int smoothed = 0;
  for (const SonarSmoothedFeature& f : r.features) smoothed += f.smoothed;
  s.Set("features", Json(static_cast<std::int64_t>(r.features.size())));
  s.Set("features_smoothed", Json(smoothed));
  s.Set("features_held_out", Json(static_cast<int>(r.features.size()) - smoothed));
  s.Set("measurements_used", Json(r.measurements_used));
  s.Set("residual_blocks", Json(r.residual_blocks));
  s.Set("initial_cost", Json(r.initial_cost));
  s.Set("final_cost", Json(r.final_cost));
  s.Set("iterations", Json(r.iterations));
  s.Set("converged", Json(r.converged));
  s.Set("covariance_ok", Json(r.covariance_ok));
  s.Set("solve_seconds", Json(r.solve_seconds));
  s.Set("covariance_seconds", Json(r.covariance_seconds));
  s.Set("report", Json(r.report));
  if (run.errors) s.Set("truth", SmootherTruthJson(*run.errors));
  return s;
}

// The filter's NIS against chi-square (sonar/sonar_consistency.h).
Json ConsistencyJson(const SonarConsistency& c) {
  Json j = Json::Object();
  j.Set("nis", Finite(c.nis));
  j.Set("dof", Json(c.dof));
  j.Set("interval", Json::ArrayOf(std::vector<double>{c.low, c.high}));
  j.Set("window", Json(c.window));
  j.Set("windows", Json(c.windows));
  j.Set("windows_high", Json(c.windows_high));
  j.Set("inconsistent", Json(c.inconsistent));
  j.Set("conservative", Json(c.conservative));
  j.Set("verdict", Json(c.Verdict()));
  return j;
}

Json SummaryJson(const SonarPipelineResult& p) {
  const SonarRunResult& r = p.run;
  Json sum = Json::Object();
  sum.Set("format", Json("hull-sonar-result"));
  sum.Set("version", Json(1));
  sum.Set("sequence", Json(p.sequence));
  sum.Set("source", Json(p.from_images ? "images" : "measurements"));
  sum.Set("options", OptionsJson(p.options.ekf));
  sum.Set("steps", Json(static_cast<int>(r.steps.size())));
  sum.Set("measurements", Json(p.measurements));
  int in_state = 0;
  for (const SonarFeatureEstimate& f : r.final_features) in_state += f.in_state;
  sum.Set("features", Json(static_cast<std::int64_t>(r.final_features.size())));
  sum.Set("features_in_state", Json(in_state));
  sum.Set("filter_seconds", Json(r.filter_seconds));
  sum.Set("steps_per_second", Finite(r.filter_seconds > 0 ? r.steps.size() / r.filter_seconds : NAN));
  const SonarStepRecord& last = r.steps.back();
  sum.Set("final_pose", ArrayOf(last.estimate.pose));
  Vector6d sigma;
  for (int i = 0; i < 6; ++i) sigma[i] = std::sqrt(last.estimate.pose_covariance(i, i));
  sum.Set("final_pose_sigma", ArrayOf(sigma));
  sum.Set("final_dead_reckoning", ArrayOf(last.dead_reckoning));
  sum.Set("consistency", ConsistencyJson(CheckSonarConsistency(r)));
  if (r.has_truth) sum.Set("truth", TruthJson(r));
  if (p.images) sum.Set("images", ImageSummaryJson(*p.images, p.image_options));
  if (p.smoother) sum.Set("smoother", SmootherSummaryJson(*p.smoother, p.smoother_options));
  return sum;
}

}  // namespace

void WriteSonarResults(const SonarPipelineResult& p, const std::string& dir, const SonarWriteOptions& options) {
  if (p.run.steps.empty()) throw std::invalid_argument("WriteSonarResults: the run has no steps");
  fs::create_directories(dir);
  if (p.images) WriteFileAtomic(Path(dir, kSonarDetectionsCsv), DetectionsCsv(*p.images));
  WriteFileAtomic(Path(dir, kSonarPosesCsv), PosesCsv(p.run));
  WriteFileAtomic(Path(dir, kSonarFeaturesCsv), FeaturesCsv(p.run, options.final_only));
  if (p.smoother) {
    WriteFileAtomic(Path(dir, kSonarSmootherPosesCsv), SmootherPosesCsv(*p.smoother));
    WriteFileAtomic(Path(dir, kSonarSmootherFeaturesCsv),
                    SmootherFeaturesCsv(*p.smoother, p.run.steps.back().estimate.step));
  }
  WriteFileAtomic(Path(dir, kSonarSummaryJson), SummaryJson(p).Dump());
}

std::vector<std::string> SonarFileNames(const SonarPipelineResult& p) {
  std::vector<std::string> names = {kSonarPosesCsv, kSonarFeaturesCsv, kSonarSummaryJson};
  if (p.images) names.push_back(kSonarDetectionsCsv);
  if (p.smoother) {
    names.push_back(kSonarSmootherPosesCsv);
    names.push_back(kSonarSmootherFeaturesCsv);
  }
  return names;
}

void SaveSonarResults(const SonarPipelineResult& p, const OutputFolder& out, ResultsRun run,
                      const SonarWriteOptions& options) {
  if (!p.sequence.empty()) run.AddSequence("sequence", p.sequence);
  WriteResultsFolder(out, run, [&](const std::string& tmp) { WriteSonarResults(p, tmp, options); });
}

bool IsSonarResults(const std::string& dir) {
  std::error_code ec;
  return fs::is_regular_file(Path(dir, kSonarSummaryJson), ec) && fs::is_regular_file(Path(dir, kSonarPosesCsv), ec);
}

}  // namespace hull
