// hullinspect-cli sonar: run the imaging-sonar EKF (Mai et al.) over an
// acoustic sequence and write per-step estimates, errors and a summary.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "cli/sonar_image_output.h"
#include "sonar/sonar_image_runner.h"
#include "sonar/sonar_runner.h"
#include "survey/acoustic_sequence.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli sonar SEQUENCE --out DIR [options]

Reconstructs the 3-D features of an acoustic sequence (a folder with
sonar.json, or a survey bundle with sonar/) with the EKF of Mai et al.: the
sonar pose and the features' positions with their full covariance, updated
step by step from the controls and the range/azimuth measurements.

The features come from measurements.csv (given correspondences) or, with
--from-images, from the acoustic images of a version 2 sequence: point
features detected in every image, associated with the filter's prediction
(joint compatibility), started, confirmed and dropped automatically. The
default is measurements.csv when the sequence has it, the images otherwise.

Writes to DIR:
  poses.csv     per step: pose estimate, standard deviations, the 21 terms of
                its covariance (upper triangle), dead reckoning, the update's
                statistics, and errors against truth/ when present
  features.csv  per step and feature: estimate, covariance (6 terms), whether
                it is in the state or still waiting for its elevation, and its
                error against the truth when present
  summary.json  options, counts, timing, final pose and features, and error
                and NEES statistics when the sequence has truth
  detections.csv  (--from-images) per step and detection: position, strength,
                the feature it measured or started, and its true feature

options:
  --from-images            features from images/ (default when measurements.csv is absent)
  --from-measurements      features from measurements.csv (default when present)
  --confirm N              from images: views before a feature enters the state (default 3)
  --gate P                 from images: chi-square gate probability (default 0.99)
  --drop-misses N          from images: drop a feature predicted in view but
                           missed at N consecutive steps (default 8)
  --min-contrast L         from images: grey levels above the background (default 60)
  --init hypotheses|paper  feature initialisation (default hypotheses):
                           paper       elevation 0, sigma = elevation_fov/4
                           hypotheses  elevation hypotheses weighed by later
                                       views, entered once one dominates
  --hypotheses K           number of elevation hypotheses (default 9)
  --collapse P             weight share of the best hypothesis and its
                           neighbours that lets a feature in (default 0.99)
  --max-delay N            steps a feature may wait (default 8)
  --paper-sigma F          paper: sigma_phi as a fraction of the fan (default 0.25)
  --short-form             covariance update P - K S K^T instead of Joseph
  --final-only             features.csv holds the last step only
  --quiet                  no progress output

exit codes: 0 done, 2 bad command line or options, 3 malformed sequence
)";

std::string SequenceFolder(const std::string& path) {
  namespace fs = std::filesystem;
  if (fs::exists(fs::path(path) / "sonar.json")) return path;
  if (fs::exists(fs::path(path) / "sonar" / "sonar.json")) return (fs::path(path) / "sonar").string();
  throw UsageError("'" + path + "' holds neither sonar.json nor sonar/sonar.json");
}

const char* kPoseNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
const char* kXyz[3] = {"x", "y", "z"};

Json ArrayOf(const Vector6d& v) {
  Json a = Json::Array();
  for (int i = 0; i < 6; ++i) a.Push(Json(v[i]));
  return a;
}

Json Finite(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

int RunSonar(const CommandArgs& argv) {
  const std::set<std::string> flags = {"help", "short-form", "final-only", "quiet", "from-images", "from-measurements"};
  Args a(argv, flags);
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out", "init", "hypotheses", "collapse", "max-delay", "paper-sigma", "short-form", "final-only", "quiet",
               "from-images", "from-measurements", "confirm", "gate", "drop-misses", "min-contrast"});
  if (a.Has("from-images") && a.Has("from-measurements")) {
    throw UsageError("--from-images and --from-measurements exclude each other");
  }
  if (a.positionals().size() != 1) throw UsageError("expected one acoustic sequence folder");
  if (!a.Has("out")) throw UsageError("--out DIR is required");
  const std::string out = a.Get("out");

  SonarRunOptions options;  // not const: from images, the image chain's
  options.ekf.init = ParseSonarInit(a.Get("init", "hypotheses"));
  options.ekf.hypotheses = static_cast<int>(a.GetInt("hypotheses", options.ekf.hypotheses));
  options.ekf.collapse_probability = a.GetDouble("collapse", options.ekf.collapse_probability);
  options.ekf.max_delay_steps = static_cast<int>(a.GetInt("max-delay", options.ekf.max_delay_steps));
  options.ekf.paper_elevation_sigma_fraction = a.GetDouble("paper-sigma", options.ekf.paper_elevation_sigma_fraction);
  options.ekf.joseph = !a.Has("short-form");
  std::string why;
  if (!options.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }

  SonarImageRunOptions image_options;
  image_options.run.ekf = options.ekf;
  image_options.run.ekf.confirm_views = static_cast<int>(a.GetInt("confirm", 3));
  image_options.tracker.gate_probability = a.GetDouble("gate", image_options.tracker.gate_probability);
  image_options.tracker.drop_misses = static_cast<int>(a.GetInt("drop-misses", image_options.tracker.drop_misses));
  image_options.detector.min_contrast = a.GetDouble("min-contrast", image_options.detector.min_contrast);
  if (!image_options.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }

  const std::string dir = SequenceFolder(a.positionals()[0]);
  const AcousticSequence seq = ReadAcousticSequence(dir);
  const bool from_images = a.Has("from-images") || (!a.Has("from-measurements") && !seq.has_measurements);
  if (from_images && !seq.image) throw UsageError("'" + dir + "' has no images (a version 1 sequence)");
  if (!from_images && !seq.has_measurements) {
    throw UsageError("'" + dir + "' has no measurements.csv; its features can only come from its images");
  }
  ConsoleProgress progress(a.Has("quiet"));
  std::optional<SonarImageRunResult> images;
  if (from_images) {
    images = RunSonarImages(seq, dir, image_options, &progress);
    options = image_options.run;
  }
  const SonarRunResult r = images ? images->run : RunSonarSequence(seq, options, &progress);
  progress.Finish();
  std::filesystem::create_directories(out);
  if (images) WriteSonarDetections(*images, (std::filesystem::path(out) / "detections.csv").string());

  // poses.csv
  std::vector<std::string> head = {"step"};
  for (const char* n : kPoseNames) head.push_back(n);
  for (const char* n : kPoseNames) head.push_back(std::string("sigma_") + n);
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) head.push_back(std::string("cov_") + kPoseNames[i] + "_" + kPoseNames[j]);
  }
  for (const char* n : kPoseNames) head.push_back(std::string("dr_") + n);
  for (const char* n : {"measurements", "updated", "initialised", "pending", "nis", "nis_dof"}) head.push_back(n);
  if (r.has_truth) {
    for (const char* n :
         {"position_error", "rotation_error", "dr_position_error", "dr_rotation_error", "pose_nees",
          "features_in_state", "mean_feature_error", "max_feature_error", "joint_nees", "joint_nees_dof"}) {
      head.push_back(n);
    }
  }
  CsvWriter poses(head);
  for (const SonarStepRecord& s : r.steps) {
    const SonarStepEstimate& e = s.estimate;
    poses.Add(e.step);
    for (int i = 0; i < 6; ++i) poses.Add(e.pose[i]);
    for (int i = 0; i < 6; ++i) poses.Add(std::sqrt(e.pose_covariance(i, i)));
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) poses.Add(e.pose_covariance(i, j));
    }
    for (int i = 0; i < 6; ++i) poses.Add(s.dead_reckoning[i]);
    poses.Add(e.measurements).Add(e.updated).Add(e.initialised).Add(e.pending).Add(e.nis).Add(e.nis_dof);
    if (r.has_truth) {
      const SonarStepErrors& x = *s.errors;
      poses.Add(x.position).Add(x.rotation).Add(x.dr_position).Add(x.dr_rotation).Add(x.pose_nees).Add(x.features);
      poses.Add(x.mean_feature_error).Add(x.max_feature_error);
      if (std::isfinite(x.joint_nees)) {
        poses.Add(x.joint_nees);
      } else {
        poses.AddEmpty();
      }
      poses.Add(x.joint_nees_dof);
    }
    poses.EndRow();
  }
  WriteFileAtomic((std::filesystem::path(out) / "poses.csv").string(), poses.text());

  // features.csv
  std::vector<std::string> fhead = {"step", "feature", "in_state", "x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) fhead.push_back(std::string("cov_") + kXyz[i] + "_" + kXyz[j]);
  }
  for (const char* n : {"observations", "first_step"}) fhead.push_back(n);
  if (r.has_truth) fhead.push_back("error");
  CsvWriter features(fhead);
  auto add_features = [&](std::int64_t step, const std::vector<SonarFeatureEstimate>& fs,
                          const std::vector<double>& errors) {
    for (std::size_t n = 0; n < fs.size(); ++n) {
      const SonarFeatureEstimate& f = fs[n];
      features.Add(step).Add(f.id).Add(f.in_state ? 1 : 0);
      for (int i = 0; i < 3; ++i) features.Add(f.position[i]);
      for (int i = 0; i < 3; ++i) {
        for (int j = i; j < 3; ++j) features.Add(f.covariance(i, j));
      }
      features.Add(f.observations).Add(f.first_step);
      if (r.has_truth) {
        if (n < errors.size() && std::isfinite(errors[n])) {
          features.Add(errors[n]);
        } else {
          features.AddEmpty();
        }
      }
      features.EndRow();
    }
  };
  if (a.Has("final-only")) {
    add_features(r.steps.back().estimate.step, r.final_features, r.final_feature_errors);
  } else {
    for (const SonarStepRecord& s : r.steps) add_features(s.estimate.step, s.features, s.feature_errors);
  }
  WriteFileAtomic((std::filesystem::path(out) / "features.csv").string(), features.text());

  // summary.json
  Json sum = Json::Object();
  sum.Set("format", Json("hull-sonar-result"));
  sum.Set("version", Json(1));
  sum.Set("sequence", Json(dir));
  sum.Set("source", Json(from_images ? "images" : "measurements"));
  Json opt = Json::Object();
  opt.Set("init", Json(SonarInitName(options.ekf.init)));
  opt.Set("hypotheses", Json(options.ekf.hypotheses));
  opt.Set("collapse_probability", Json(options.ekf.collapse_probability));
  opt.Set("max_delay_steps", Json(options.ekf.max_delay_steps));
  opt.Set("paper_elevation_sigma_fraction", Json(options.ekf.paper_elevation_sigma_fraction));
  opt.Set("joseph", Json(options.ekf.joseph));
  opt.Set("confirm_views", Json(options.ekf.confirm_views));
  sum.Set("options", std::move(opt));
  sum.Set("steps", Json(static_cast<int>(r.steps.size())));
  sum.Set("measurements", Json(static_cast<std::int64_t>(seq.measurements.size())));
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
  if (r.has_truth) {
    Json t = Json::Object();
    const SonarStepErrors& e = *last.errors;
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
    sum.Set("truth", std::move(t));
  }
  if (images) sum.Set("images", SonarImageSummary(*images));
  WriteFileAtomic((std::filesystem::path(out) / "summary.json").string(), sum.Dump());

  std::printf("%s: %zu steps, %zu features (%d in the state), %s initialisation, %.1f steps/s\n", dir.c_str(),
              r.steps.size(), r.final_features.size(), in_state, SonarInitName(options.ekf.init),
              r.filter_seconds > 0 ? r.steps.size() / r.filter_seconds : 0.0);
  if (r.has_truth) {
    const SonarStepErrors& e = *last.errors;
    std::printf("final mean feature error %.4f m; position error %.4f m (dead reckoning %.4f m)\n",
                e.mean_feature_error, e.position, e.dr_position);
  }
  if (images && images->has_truth) {
    const SonarImageEvaluation& e = images->evaluation;
    std::printf("from images: %.1f %% of the visible true features detected per frame, %d of %d associations wrong\n",
                100 * e.mean_detection_rate, e.wrong_associations, e.associations);
  }
  std::printf("wrote %s/{poses.csv,features.csv,summary.json%s}\n", out.c_str(), images ? ",detections.csv" : "");
  return kExitOk;
}

}  // namespace hull::cli
