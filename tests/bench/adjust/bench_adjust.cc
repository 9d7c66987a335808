// bench_adjust: the three surface models on the stereo and mono demo
// surveys (iterations, time, time relative to naive: the paper's Fig. 17),
// and optionally the curtiss-size survey (>= 10,000 keyframes; wall time and
// peak memory of alignment + max-mixture adjustment).
//
//   build/bin/bench_adjust [--repeat N] [--curtiss | --curtiss-only] [--threads N]
//                          [--linear-solver sparse|iterative] [--verbose]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "adjust/bundle_adjuster.h"
#include "pipeline/pipeline.h"
#include "simulate/survey_simulator.h"

namespace {

double PeakRssGiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / (1024.0 * 1024.0);  // ru_maxrss is in KiB
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3, threads = 0;
  bool curtiss = false, presets = true, verbose = false;
  auto solver = hull::AdjustmentOptions::LinearSolver::kSparseSchur;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
      threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--curtiss"))
      curtiss = true;
    else if (!std::strcmp(argv[i], "--curtiss-only"))
      curtiss = true, presets = false;
    else if (!std::strcmp(argv[i], "--verbose"))
      verbose = true;
    else if (!std::strcmp(argv[i], "--linear-solver") && i + 1 < argc &&
             (!std::strcmp(argv[i + 1], "sparse") || !std::strcmp(argv[i + 1], "iterative")))
      solver = !std::strcmp(argv[++i], "sparse") ? hull::AdjustmentOptions::LinearSolver::kSparseSchur
                                                 : hull::AdjustmentOptions::LinearSolver::kIterativeSchur;
    else {
      std::fprintf(stderr,
                   "usage: %s [--repeat N] [--threads N] [--curtiss | --curtiss-only] "
                   "[--linear-solver sparse|iterative] [--verbose]\n",
                   argv[0]);
      return 2;
    }
  }
  hull::NullProgress quiet;
  std::printf("%-7s %-15s %10s %11s %12s %9s %12s\n", "survey", "model", "iterations", "median s", "vs naive",
              "lambda=1", "RMSE (mm)");
  for (const char* preset : {"demo", "mono"}) {
    if (!presets) break;
    const hull::SimulatedSurvey s = hull::SimulateSurvey(hull::SurveyPreset(preset), quiet);
    hull::PipelineInputs in;
    in.bundle = s.bundle;
    in.mesh = s.cad;
    const hull::ModelAlignment al = hull::RunAlignment(in, hull::PipelineOptions(), quiet);
    std::map<hull::SurfaceModel, double> median;
    for (hull::SurfaceModel m :
         {hull::SurfaceModel::kNaive, hull::SurfaceModel::kAllOnSurface, hull::SurfaceModel::kMaxMixture}) {
      hull::AdjustmentOptions o;
      o.model = m;
      o.num_threads = threads;
      std::vector<double> times;
      hull::AdjustmentResult r;
      for (int k = 0; k < repeat; ++k) {
        r = hull::RunAdjustment(in.bundle, in.mesh, al.x_gM, o, quiet);
        times.push_back(r.seconds);
      }
      std::sort(times.begin(), times.end());
      median[m] = times[times.size() / 2];
      const hull::AdjustmentEvaluation e = hull::EvaluateAdjustment(in.bundle, in.mesh, r);
      std::printf("%-7s %-15s %10d %11.2f %+11.1f%% %8.1f%% %12.1f\n", preset, hull::SurfaceModelName(m),
                  r.iterations.empty() ? 0 : r.iterations.back().iteration, median[m],
                  100.0 * (median[m] / median[hull::SurfaceModel::kNaive] - 1.0), 100.0 * r.FractionOnSurface(),
                  1000.0 * e.landmark_rmse);
      std::fflush(stdout);
    }
  }
  if (curtiss) {
    const auto t0 = std::chrono::steady_clock::now();
    const hull::SimulatedSurvey s = hull::SimulateSurvey(hull::SurveyPreset("curtiss"), quiet);
    hull::PipelineInputs in;
    in.bundle = s.bundle;
    in.mesh = s.cad;
    const double sim_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto t1 = std::chrono::steady_clock::now();
    // --verbose: the alignment's stages with their start times.
    hull::CallbackProgress stages([&](double, const std::string& message) {
      if (verbose) {
        std::printf("  %7.2f s  %s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(),
                    message.c_str());
      }
    });
    const hull::ModelAlignment al = hull::RunAlignment(in, hull::PipelineOptions(), stages);
    const double align_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    hull::AdjustmentOptions o;
    o.num_threads = threads;
    o.linear_solver = solver;
    o.verbose = verbose;
    const hull::AdjustmentResult r = hull::RunAdjustment(in.bundle, in.mesh, al.x_gM, o, quiet);
    const hull::AdjustmentEvaluation e = hull::EvaluateAdjustment(in.bundle, in.mesh, r);
    std::printf(
        "\ncurtiss: %zu keyframes, %zu landmarks, %zu observations\n"
        "  simulation %.1f s, alignment %.1f s, max-mixture adjustment %.1f s (%d iterations, %s)\n"
        "  converged: %s; landmark RMSE %.1f mm; labels %.2f %%; peak memory %.2f GiB\n",
        in.bundle.nav.size(), r.landmarks.size(), in.bundle.features.size(), sim_s, align_s, r.seconds,
        r.iterations.empty() ? 0 : r.iterations.back().iteration, r.termination.c_str(), r.converged ? "yes" : "no",
        1000.0 * e.landmark_rmse, 100.0 * e.label_agreement, PeakRssGiB());
  }
  return 0;
}
