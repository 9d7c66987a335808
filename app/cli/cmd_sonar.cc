// hullinspect-cli sonar: run the imaging-sonar EKF (Mai et al.) over an
// acoustic sequence and write per-step estimates, errors and a summary.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "results/sonar_files.h"
#include "sonar/sonar_consistency.h"
#include "sonar/sonar_pipeline.h"
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
  smoother_poses.csv, smoother_features.csv  (--smoother) the batch smoother's
                poses and features with their covariances (the columns of
                poses.csv and features.csv), errors and NEES with truth; its
                counts, costs, timing and errors go into summary.json

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
  --smoother               after the EKF, a batch adjustment (Ceres) of every
                           pose and feature with all measurements, started
                           from the EKF; written beside the filter's results
  --smoother-iterations N  its iterations at most (default 50)
  --no-smoother-covariance skip its covariances
  --final-only             features.csv holds the last step only
  --quiet                  no progress output
  --force                  write into an --out folder that holds files
                           HullInspect did not write (they are kept; none is
                           replaced)

DIR must be new, empty or a results folder HullInspect wrote (checked before
any work); it is replaced as a whole: a run that fails or is killed leaves
the previous folder whole (docs/results-format.md).

exit codes: 0 done, 2 bad command line or options, 3 malformed sequence,
            4 insufficient data (no measurement, images without a detection or
            that look like noise, no feature confirmed: nothing is written)
)";

std::string SequenceFolder(const std::string& path) {
  namespace fs = std::filesystem;
  if (fs::exists(fs::path(path) / "sonar.json")) return path;
  if (fs::exists(fs::path(path) / "sonar" / "sonar.json")) return (fs::path(path) / "sonar").string();
  throw UsageError("'" + path + "' holds neither sonar.json nor sonar/sonar.json");
}

// What the run found, on stdout.
void PrintSonarSummary(const SonarPipelineResult& result, const std::string& dir, const std::string& out) {
  const SonarRunResult& r = result.run;
  const SonarRunOptions& options = result.options;
  const SonarSmootherOptions& smoother_options = result.smoother_options;
  const std::optional<SonarImageRunResult>& images = result.images;
  const std::optional<SonarSmootherRun>& smoother = result.smoother;
  int in_state = 0;
  for (const SonarFeatureEstimate& f : r.final_features) in_state += f.in_state;
  const SonarStepRecord& last = r.steps.back();
  std::printf("%s: %zu steps, %zu features (%d in the state), %s initialisation, %.1f steps/s\n", dir.c_str(),
              r.steps.size(), r.final_features.size(), in_state, SonarInitName(options.ekf.init),
              r.filter_seconds > 0 ? r.steps.size() / r.filter_seconds : 0.0);
  std::printf("consistency: %s\n", CheckSonarConsistency(r).Verdict().c_str());
  if (r.has_truth) {
    const SonarStepErrors& e = *last.errors;
    if (e.features > 0) {
      std::printf("final mean feature error %.4f m over %d features with truth; ", e.mean_feature_error, e.features);
    } else {
      std::printf("truth: no feature in the state stands for a true feature (no feature error); ");
    }
    std::printf("position error %.4f m (dead reckoning %.4f m)\n", e.position, e.dr_position);
  }
  if (images && images->has_truth) {
    const SonarImageEvaluation& e = images->evaluation;
    std::printf("from images: %.1f %% of the visible true features detected per frame, %d of %d associations wrong\n",
                100 * e.mean_detection_rate, e.wrong_associations, e.associations);
  }
  if (smoother) {
    const SonarSmootherResult& sr = smoother->result;
    int held_out = 0;
    for (const SonarSmoothedFeature& f : sr.features) held_out += !f.smoothed;
    std::printf(
        "smoother: %d iterations, cost %.4g -> %.4g, %d features held out (elevation not observable), "
        "%.1f ms + %.1f ms covariances%s\n",
        sr.iterations, sr.initial_cost, sr.final_cost, held_out, 1e3 * sr.solve_seconds, 1e3 * sr.covariance_seconds,
        sr.covariance_ok || !smoother_options.covariances ? "" : " (FAILED)");
    if (smoother->errors && smoother->errors->features > 0) {
      const SonarSmootherErrors& e = *smoother->errors;
      std::printf("smoother: final mean feature error %.4f m; position error %.4f m; joint NEES %.2f / %d dof\n",
                  e.mean_feature_error, e.position, e.joint_nees, e.joint_nees_dof);
    }
  }
  std::printf("wrote %s/{poses.csv,features.csv,summary.json%s%s}\n", out.c_str(), images ? ",detections.csv" : "",
              smoother ? ",smoother_poses.csv,smoother_features.csv" : "");
}

}  // namespace

int RunSonar(const CommandArgs& argv) {
  const std::set<std::string> flags = {"help",        "short-form",        "final-only", "quiet",
                                       "from-images", "from-measurements", "smoother",   "no-smoother-covariance",
                                       "force"};
  Args a(argv, flags);
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out", "init", "hypotheses", "collapse", "max-delay", "paper-sigma", "short-form", "final-only", "quiet",
               "from-images", "from-measurements", "confirm", "gate", "drop-misses", "min-contrast", "smoother",
               "smoother-iterations", "no-smoother-covariance", "force"});
  if (a.Has("from-images") && a.Has("from-measurements")) {
    throw UsageError("--from-images and --from-measurements exclude each other");
  }
  if (a.positionals().size() != 1) throw UsageError("expected one acoustic sequence folder");
  if (!a.Has("out")) throw UsageError("--out DIR is required");
  const OutputFolder out{a.Get("out"), a.Has("force")};
  CheckResultsFolder(out);

  SonarPipelineOptions o;
  if (a.Has("from-images")) o.source = SonarFeatureSource::kImages;
  if (a.Has("from-measurements")) o.source = SonarFeatureSource::kMeasurements;
  SonarEkfOptions& ekf = o.run.ekf;
  ekf.init = ParseSonarInit(a.Get("init", "hypotheses"));
  ekf.hypotheses = static_cast<int>(a.GetInt("hypotheses", ekf.hypotheses));
  ekf.collapse_probability = a.GetDouble("collapse", ekf.collapse_probability);
  ekf.max_delay_steps = static_cast<int>(a.GetInt("max-delay", ekf.max_delay_steps));
  ekf.paper_elevation_sigma_fraction = a.GetDouble("paper-sigma", ekf.paper_elevation_sigma_fraction);
  ekf.joseph = !a.Has("short-form");
  o.images.run.ekf = ekf;
  o.images.run.ekf.confirm_views = static_cast<int>(a.GetInt("confirm", 3));
  o.images.tracker.gate_probability = a.GetDouble("gate", o.images.tracker.gate_probability);
  o.images.tracker.drop_misses = static_cast<int>(a.GetInt("drop-misses", o.images.tracker.drop_misses));
  o.images.detector.min_contrast = a.GetDouble("min-contrast", o.images.detector.min_contrast);
  o.smoother = a.Has("smoother");
  o.smoother_options.max_iterations =
      static_cast<int>(a.GetInt("smoother-iterations", o.smoother_options.max_iterations));
  o.smoother_options.covariances = !a.Has("no-smoother-covariance");
  o.Check();

  const std::string dir = SequenceFolder(a.positionals()[0]);
  const AcousticSequence seq = ReadAcousticSequence(dir);
  ConsoleProgress progress(a.Has("quiet"));
  const SonarPipelineResult result = RunSonarPipeline(seq, dir, o, progress);
  progress.Finish();
  SonarWriteOptions write;
  write.final_only = a.Has("final-only");
  SaveSonarResults(result, out, NewResultsRun("sonar"), write);

  PrintSonarSummary(result, dir, out.path);
  return kExitOk;
}

}  // namespace hull::cli
