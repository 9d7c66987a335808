// Benchmarks of the mapping-trust steps (docs/benchmarks.md):
//   bench_trust [--threads N] [--skip-covariance] [--skip-compare]
//               [--preset NAME] [--methods none,conditional,full,full-qr]
//               [--max-iterations N]
// - covariance: the survey (default demo) adjusted (max-mixture) with each
//   landmark covariance method: the wall and CPU seconds of the covariance
//   step, and the z-scores (h - h_true) / sigma_h of the hull features (std
//   near 1 when sigma_h is honest);
// - compare: the demo survey and its second survey (2 patches grown by 5 cm,
//   2 new, the last object removed), each mapped from the truth; the
//   seconds of CompareSurveys and its object classes against the truth.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "adjust/bundle_adjuster.h"
#include "mapping/mapper.h"
#include "mapping/survey_compare.h"
#include "simulate/survey_simulator.h"

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// max_iterations > 0 caps the solver (the covariance step of a big preset
// timed on the same structure without waiting for convergence).
void Covariance(int threads, const std::string& preset, const std::vector<hull::CovarianceMethod>& methods,
                int max_iterations) {
  hull::NullProgress p;
  const hull::SimulatedSurvey s = hull::SimulateSurvey(hull::SurveyPreset(preset), p);
  std::map<std::int64_t, const hull::TrueLandmark*> truth;
  for (const auto& l : s.bundle.truth->landmarks) truth[l.landmark] = &l;
  std::printf("%s: %zu keyframes, %zu landmarks, %d threads\n", preset.c_str(), s.bundle.nav.size(),
              s.bundle.truth->landmarks.size(), threads);
  std::printf(
      "| covariance | adjustment s | covariance s (wall) | covariance s (CPU) | hull features | sigma_h mean (mm) | z "
      "mean | z std |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const hull::CovarianceMethod m : methods) {
    hull::AdjustmentOptions o;
    o.covariance = m;
    o.num_threads = threads;
    if (max_iterations > 0) o.max_iterations = max_iterations;
    const hull::AdjustmentResult r =
        hull::RunAdjustment(s.bundle, s.cad, hull::Pose::FromVector(*s.bundle.manifest.model_pose_guess), o, p);
    double sum = 0, sum2 = 0, sig = 0;
    int n = 0;
    for (const auto& l : r.landmarks) {
      const auto it = truth.find(l.id);
      if (it == truth.end() || !it->second->object.empty() || !std::isfinite(l.sigma_h)) continue;
      const double z = (l.deviation - it->second->deviation) / l.sigma_h;
      sum += z;
      sum2 += z * z;
      sig += l.sigma_h;
      ++n;
    }
    const double mean = n ? sum / n : 0, sd = n ? std::sqrt(sum2 / n - mean * mean) : 0;
    std::printf("| %s | %.2f | %.2f | %.2f | %d | %.2f | %.3f | %.3f |\n",
                hull::CovarianceMethodName(r.covariance_method), r.seconds, r.covariance_seconds,
                r.covariance_cpu_seconds, n, n ? 1000 * sig / n : 0.0, mean, sd);
    if (!r.covariance_note.empty()) std::printf("  note: %s\n", r.covariance_note.c_str());
    if (r.covariance_reduced_size) {
      std::printf("  reduced system: %zu columns, factor %zu nonzeros\n", r.covariance_reduced_size,
                  r.covariance_factor_nonzeros);
    }
    std::fflush(stdout);
  }
}

void Compare(int threads) {
  hull::NullProgress p;
  hull::SurveySimulationOptions a = hull::SurveyPreset("demo");
  hull::SurveySimulationOptions b = a;
  b.changes.grow = 2;
  b.changes.remove = 1;
  b.changes.add = 2;
  const hull::SimulatedSurvey sa = hull::SimulateSurvey(a, p), sb = hull::SimulateSurvey(b, p);
  hull::MappingOptions mo;
  mo.num_threads = threads;
  const hull::MappingResult ma = hull::RunMapping(hull::MappingInputFromTruth(sa.bundle), sa.cad, mo, p);
  const hull::MappingResult mb = hull::RunMapping(hull::MappingInputFromTruth(sb.bundle), sb.cad, mo, p);
  const auto t = Clock::now();
  const hull::SurveyComparison c =
      hull::CompareSurveys(sa.cad, ma.model, ma.objects, mb.model, mb.objects, hull::SurveyCompareOptions{});
  const double seconds = Since(t);
  std::printf("compare (demo pair, mapped from truth): %zu vertices of B, %.2f s\n", c.model.num_vertices(), seconds);
  std::printf("truth: A %zu objects, B %zu objects\n", sa.bundle.truth->objects.size(),
              sb.bundle.truth->objects.size());
  for (const auto& o : sb.bundle.truth->objects) {
    std::printf("  B truth %-10s height %.3f at (%.2f %.2f %.2f)\n", o.id.c_str(), o.Height(), o.center.x(),
                o.center.y(), o.center.z());
  }
  for (const auto& o : c.objects) {
    std::printf("  %-9s A %-6s B %-6s %.3f -> %.3f (%+.3f) at (%.2f %.2f %.2f)\n", hull::ObjectChangeKindName(o.kind),
                o.id_a.empty() ? "-" : o.id_a.c_str(), o.id_b.empty() ? "-" : o.id_b.c_str(), o.height_a, o.height_b,
                o.change, o.centroid.x(), o.centroid.y(), o.centroid.z());
  }
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, max_iterations = 0;
  bool covariance = true, compare = true;
  std::string preset = "demo";
  std::vector<hull::CovarianceMethod> methods = {hull::CovarianceMethod::kNone, hull::CovarianceMethod::kConditional,
                                                 hull::CovarianceMethod::kFull, hull::CovarianceMethod::kFullSparseQr};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--skip-covariance")) {
      covariance = false;
    } else if (!std::strcmp(argv[i], "--skip-compare")) {
      compare = false;
    } else if (!std::strcmp(argv[i], "--max-iterations") && i + 1 < argc) {
      max_iterations = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--preset") && i + 1 < argc) {
      preset = argv[++i];
    } else if (!std::strcmp(argv[i], "--methods") && i + 1 < argc) {
      methods.clear();
      std::stringstream list(argv[++i]);
      for (std::string name; std::getline(list, name, ',');) methods.push_back(hull::ParseCovarianceMethod(name));
    } else {
      std::fprintf(stderr,
                   "usage: bench_trust [--threads N] [--skip-covariance] [--skip-compare] [--preset NAME] "
                   "[--methods none,conditional,full,full-qr] [--max-iterations N]\n");
      return 2;
    }
  }
  if (covariance) Covariance(threads, preset, methods, max_iterations);
  if (compare) Compare(threads);
  return 0;
}
