// bench_adjust: the surface models on the stereo and mono demo surveys and,
// with --mesh, a survey of that hull (e.g. the DTMB 5415): iterations, time
// and time relative to naive (the paper's Fig. 17), for the max-mixture with
// both label rules (the paper's merged E-step, `estimate`, and the default
// `cavity`), with the labels' agreement with truth and where the map sits
// along the hull (landmark RMSE in M and its mean along the hull's forward
// axis, no alignment). The runs of one survey are interleaved (each repeat
// runs every model once), so a load that comes and goes weighs on all of
// them alike; the medians of the repeats are printed, of wall time and of
// the process's CPU time (steadier under a load that comes and goes). Optionally the
// curtiss-size survey (>= 10,000 keyframes; wall time and peak memory of
// alignment + max-mixture adjustment).
//
//   build/bin/bench_adjust [--repeat N] [--surveys demo,mono,mesh] [--mesh PATH]
//                          [--covariance none|full] [--curtiss | --curtiss-only] [--threads N]
//                          [--linear-solver sparse|iterative] [--verbose]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "adjust/bundle_adjuster.h"
#include "adjust/evaluation.h"
#include "pipeline/pipeline.h"
#include "simulate/survey_simulator.h"

namespace {

// CPU seconds of the process so far (every thread): under a load that comes
// and goes, a steadier measure of the work than wall time.
double CpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double PeakRssGiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / (1024.0 * 1024.0);  // ru_maxrss is in KiB
}

struct Args {
  int repeat = 3, threads = 0;
  bool curtiss = false, presets = true, verbose = false;
  std::string surveys = "demo,mono,mesh";
  std::string mesh;  // the hull surveyed by the "mesh" row (none: the row is skipped)
  hull::CovarianceMethod covariance = hull::CovarianceMethod::kNone;
  hull::AdjustmentOptions::LinearSolver solver = hull::AdjustmentOptions::LinearSolver::kSparseSchur;
};

bool Parse(int argc, char** argv, Args* a) {
  for (int i = 1; i < argc; ++i) {
    const bool more = i + 1 < argc;
    if (!std::strcmp(argv[i], "--repeat") && more) {
      a->repeat = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--threads") && more) {
      a->threads = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--surveys") && more) {
      a->surveys = argv[++i];
    } else if (!std::strcmp(argv[i], "--mesh") && more) {
      a->mesh = argv[++i];
    } else if (!std::strcmp(argv[i], "--covariance") && more) {
      a->covariance = hull::ParseCovarianceMethod(argv[++i]);
    } else if (!std::strcmp(argv[i], "--curtiss")) {
      a->curtiss = true;
    } else if (!std::strcmp(argv[i], "--curtiss-only")) {
      a->curtiss = true, a->presets = false;
    } else if (!std::strcmp(argv[i], "--verbose")) {
      a->verbose = true;
    } else if (!std::strcmp(argv[i], "--linear-solver") && more &&
               (!std::strcmp(argv[i + 1], "sparse") || !std::strcmp(argv[i + 1], "iterative"))) {
      a->solver = !std::strcmp(argv[++i], "sparse") ? hull::AdjustmentOptions::LinearSolver::kSparseSchur
                                                    : hull::AdjustmentOptions::LinearSolver::kIterativeSchur;
    } else {
      return false;
    }
  }
  return true;
}

// One row of the table: a surface model and, for the max-mixture, its label rule.
struct Model {
  const char* name;
  hull::SurfaceModel model;
  hull::LabelRule labels;
};

const std::vector<Model>& Models() {
  static const std::vector<Model> models = {
      {"naive", hull::SurfaceModel::kNaive, hull::LabelRule::kCavity},
      {"all-on-surface", hull::SurfaceModel::kAllOnSurface, hull::LabelRule::kCavity},
      {"mm estimate", hull::SurfaceModel::kMaxMixture, hull::LabelRule::kEstimate},
      {"mm cavity", hull::SurfaceModel::kMaxMixture, hull::LabelRule::kCavity},
  };
  return models;
}

// The survey of a row: a preset, or the demo's plan over the mesh file.
hull::SurveySimulationOptions SurveyOf(const std::string& survey, const Args& a) {
  if (survey != "mesh") return hull::SurveyPreset(survey);
  hull::SurveySimulationOptions o = hull::SurveyPreset("demo");
  o.mesh_path = a.mesh;
  return o;
}

// Every model on one survey, the repeats interleaved; prints a row per model.
void BenchSurvey(const std::string& survey, const Args& a, hull::Progress& quiet) {
  const hull::SimulatedSurvey s = hull::SimulateSurvey(SurveyOf(survey, a), quiet);
  hull::PipelineInputs in;
  in.bundle = s.bundle;
  in.mesh = s.cad;
  const hull::ModelAlignment al = hull::RunAlignment(in, hull::PipelineOptions(), quiet);
  const hull::ModelAxes axes = in.bundle.manifest.model_axes.value_or(hull::ModelAxes{});
  const std::vector<Model>& models = Models();
  std::vector<std::vector<double>> times(models.size()), cpu(models.size());
  std::vector<hull::AdjustmentResult> last(models.size());
  for (int k = 0; k < a.repeat; ++k) {
    for (std::size_t m = 0; m < models.size(); ++m) {
      hull::AdjustmentOptions o;
      o.model = models[m].model;
      o.labels = models[m].labels;
      o.num_threads = a.threads;
      o.covariance = a.covariance;
      const double c0 = CpuSeconds();
      last[m] = hull::RunAdjustment(in.bundle, in.mesh, al.x_gM, o, quiet);
      cpu[m].push_back(CpuSeconds() - c0);
      times[m].push_back(last[m].seconds);
    }
  }
  double naive = 0, naive_cpu = 0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double median = Median(times[m]), median_cpu = Median(cpu[m]);
    if (m == 0) naive = median, naive_cpu = median_cpu;
    const hull::AdjustmentResult& r = last[m];
    const hull::AdjustmentEvaluation e = hull::EvaluateAdjustment(in.bundle, in.mesh, r);
    std::printf("%-6s %-15s %9d %6d %9.2f %8.3f %8.2f %8.3f %8.2f%% %7d %8.1f %8.1f %+9.1f\n", survey.c_str(),
                models[m].name, r.iterations.empty() ? 0 : r.iterations.back().iteration,
                static_cast<int>(r.landmarks.size()), median, median / naive, median_cpu, median_cpu / naive_cpu,
                100.0 * e.label_agreement, r.num_labels_off_by_cavity, 1000.0 * e.landmark_rmse,
                1000.0 * e.landmark_rmse_raw, 1000.0 * e.landmark_mean_error_raw.dot(axes.forward.normalized()));
    std::fflush(stdout);
  }
}

void BenchCurtiss(const Args& a, hull::Progress& quiet) {
  const auto t0 = std::chrono::steady_clock::now();
  const hull::SimulatedSurvey s = hull::SimulateSurvey(hull::SurveyPreset("curtiss"), quiet);
  hull::PipelineInputs in;
  in.bundle = s.bundle;
  in.mesh = s.cad;
  const double sim_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto t1 = std::chrono::steady_clock::now();
  // --verbose: the alignment's stages with their start times.
  hull::CallbackProgress stages([&](double, const std::string& message) {
    if (a.verbose) {
      std::printf("  %7.2f s  %s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(),
                  message.c_str());
    }
  });
  const hull::ModelAlignment al = hull::RunAlignment(in, hull::PipelineOptions(), stages);
  const double align_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  hull::AdjustmentOptions o;
  o.num_threads = a.threads;
  o.linear_solver = a.solver;
  o.verbose = a.verbose;
  o.covariance = a.covariance;
  const hull::AdjustmentResult r = hull::RunAdjustment(in.bundle, in.mesh, al.x_gM, o, quiet);
  const hull::AdjustmentEvaluation e = hull::EvaluateAdjustment(in.bundle, in.mesh, r);
  std::printf(
      "\ncurtiss: %zu keyframes, %zu landmarks, %zu observations\n"
      "  simulation %.1f s, alignment %.1f s, max-mixture adjustment %.1f s (solver %.1f s, %d iterations, %s)\n"
      "  alignment + adjustment %.1f s; converged: %s; landmark RMSE %.1f mm; labels %.2f %%; peak memory %.2f GiB\n",
      in.bundle.nav.size(), r.landmarks.size(), in.bundle.features.size(), sim_s, align_s, r.seconds, r.solver_seconds,
      r.iterations.empty() ? 0 : r.iterations.back().iteration, r.termination.c_str(), align_s + r.seconds,
      r.converged ? "yes" : "no", 1000.0 * e.landmark_rmse, 100.0 * e.label_agreement, PeakRssGiB());
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!Parse(argc, argv, &a)) {
    std::fprintf(stderr,
                 "usage: %s [--repeat N] [--surveys demo,mono,mesh] [--mesh PATH] [--covariance none|full] "
                 "[--threads N] [--curtiss | --curtiss-only] [--linear-solver sparse|iterative] [--verbose]\n",
                 argv[0]);
    return 2;
  }
  hull::NullProgress quiet;
  if (a.presets) {
    std::printf("%-6s %-15s %9s %6s %9s %8s %9s %7s %8s %8s %9s\n", "survey", "model", "iterations", "lms", "median s",
                "/ naive", "labels", "cavity", "RMSE mm", "raw M mm", "along mm");
  }
  std::string list = a.surveys + ",";
  for (std::size_t at = 0; a.presets && at < list.size();) {
    const std::size_t comma = list.find(',', at);
    const std::string survey = list.substr(at, comma - at);
    at = comma + 1;
    if (survey.empty()) continue;
    if (survey == "mesh" && a.mesh.empty()) {
      std::printf("mesh   (skipped: no --mesh PATH, e.g. ../shared/data/dtmb5415.stl.gz)\n");
      continue;
    }
    BenchSurvey(survey, a, quiet);
  }
  if (a.curtiss) BenchCurtiss(a, quiet);
  return 0;
}
