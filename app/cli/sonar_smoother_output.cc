#include "cli/sonar_smoother_output.h"

#include <cmath>

#include "base/csv.h"
#include "base/file_io.h"

namespace hull::cli {
namespace {

const char* kPoseNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
const char* kXyz[3] = {"x", "y", "z"};

void AddFinite(CsvWriter& csv, double v) {
  if (std::isfinite(v)) {
    csv.Add(v);
  } else {
    csv.AddEmpty();
  }
}

Json Finite(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

void WriteSmootherPoses(const SonarSmootherRun& run, const AcousticSequence& seq, const std::string& path) {
  const SonarSmootherResult& r = run.result;
  const bool truth = run.errors.has_value();
  std::vector<std::string> head = {"step"};
  for (const char* n : kPoseNames) head.push_back(n);
  for (const char* n : kPoseNames) head.push_back(std::string("sigma_") + n);
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) head.push_back(std::string("cov_") + kPoseNames[i] + "_" + kPoseNames[j]);
  }
  if (truth) {
    for (const char* n : {"position_error", "rotation_error", "pose_nees"}) head.push_back(n);
  }
  CsvWriter csv(head);
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
      csv.Add(Pose::AngleBetween(Pose::FromVector(r.poses[k]), Pose::FromVector(seq.truth->poses[k])));
      AddFinite(csv, run.pose_nees[k]);
    }
    csv.EndRow();
  }
  WriteFileAtomic(path, csv.text());
}

void WriteSmootherFeatures(const SonarSmootherRun& run, std::int64_t last_step, const std::string& path) {
  const SonarSmootherResult& r = run.result;
  const bool truth = run.errors.has_value();
  std::vector<std::string> head = {"step", "feature", "smoothed", "x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) head.push_back(std::string("cov_") + kXyz[i] + "_" + kXyz[j]);
  }
  for (const char* n : {"views", "weak_sigma"}) head.push_back(n);
  if (truth) head.push_back("error");
  CsvWriter csv(head);
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
  WriteFileAtomic(path, csv.text());
}

Json SonarSmootherSummary(const SonarSmootherRun& run, const SonarSmootherOptions& options) {
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
  if (run.errors) {
    const SonarSmootherErrors& e = *run.errors;
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
    s.Set("truth", std::move(t));
  }
  return s;
}

}  // namespace hull::cli
