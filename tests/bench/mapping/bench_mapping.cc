// bench_mapping: how long model-assisted mapping takes.
//
//   bench_mapping [--threads N] [--skip-curtiss] [--skip-demo] [--grow-height M]
//
// --grow-height M sets MappingOptions::shape_grow_height (Algorithm 1's
// hysteresis; M >= tau turns it off) for every run.
//
// demo:    the stereo demo survey, simulated and adjusted (max-mixture), then
//          mapped by one Mapper as the GUI keeps it: the first run (shapes,
//          refinement, fusion, inspection), then re-runs after changes of
//          tau and alpha (the goal: at most 1 s each).
// curtiss: the curtiss preset (a 183 m hull, full bottom and sides, about
//          10,000 keyframes), mapped from the truth -- true poses, servo
//          angles, extrinsic, model pose and landmarks with their true
//          deviation, as if adjusted perfectly -- because adjusting it takes
//          many minutes (the goal: the whole mapping in at most 2 minutes on
//          2 cores); then again with 3 mm of noise on every landmark along
//          the CAD normal (about what the demo's adjustment leaves), so that
//          at tau = 0 the clean hull's features cluster too, with the paper's
//          and with the dense eps/alpha (0.20/0.30 m).
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>

#include "adjust/bundle_adjuster.h"
#include "geometry/mesh_index.h"
#include "mapping/mapper.h"
#include "simulate/survey_simulator.h"

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void PrintRun(const char* what, const hull::MappingResult& r) {
  const hull::MappingSummary& s = r.summary;
  std::printf("| %-34s | %5.2f | %5.2f | %5.2f | %6.2f | %5.2f | %6.2f | %5.2f | %7.3f | %8zu | %7zu | %3zu |\n", what,
              r.options.tau, r.options.alpha, s.seconds.shapes, s.seconds.region + s.seconds.refinement,
              s.seconds.fusion, s.seconds.inspection, s.seconds.objects + s.seconds.deviation, s.seconds.total,
              s.model_vertices, s.shapes, r.objects.size());
}

void Header() {
  std::printf("| %-34s | %5s | %5s | %5s | %6s | %5s | %6s | %5s | %7s | %8s | %7s | %3s |\n", "run", "tau", "alpha",
              "shape", "refine", "fuse", "inspct", "objs", "total s", "vertices", "shapes", "obj");
  std::printf("|%s|------:|------:|------:|-------:|------:|-------:|------:|--------:|---------:|--------:|----:|\n",
              std::string(36, '-').c_str());
}

double grow_height = -1;  // --grow-height; < 0: MappingOptions' default

hull::MappingOptions With(double tau, double alpha, double eps = 0.10) {
  hull::MappingOptions o;
  if (grow_height >= 0) o.shape_grow_height = grow_height;
  o.tau = tau;
  o.alpha = alpha;
  o.dbscan_eps = eps;
  return o;
}

void Demo() {
  hull::NullProgress p;
  auto t = Clock::now();
  const hull::SimulatedSurvey s = hull::SimulateSurvey(hull::SurveyPreset("demo"), p);
  const hull::AdjustmentResult adj = hull::RunAdjustment(
      s.bundle, s.cad, hull::Pose::FromVector(*s.bundle.manifest.model_pose_guess), hull::AdjustmentOptions{}, p);
  std::printf("demo: %zu keyframes, %zu landmarks; simulated and adjusted in %.1f s\n\n", s.bundle.nav.size(),
              adj.landmarks.size(), Since(t));
  hull::Mapper mapper(hull::MappingInputFromAdjustment(adj, s.bundle), s.cad);
  Header();
  PrintRun("first run (tau 0)", mapper.Run(With(0.0, 0.12), p));
  PrintRun("tau 0 -> 0.06", mapper.Run(With(0.06, 0.12), p));
  PrintRun("tau 0.06 -> 0.03", mapper.Run(With(0.03, 0.12), p));
  PrintRun("tau 0.03 -> 0 (shapes recomputed)", mapper.Run(With(0.0, 0.12), p));
  PrintRun("alpha 0.12 -> 0.10", mapper.Run(With(0.0, 0.10), p));
  PrintRun("alpha 0.10 -> 0.20 (region grows)", mapper.Run(With(0.0, 0.20), p));
  PrintRun("alpha 0.20 -> 0.15", mapper.Run(With(0.0, 0.15), p));
  PrintRun("eps 0.20, alpha 0.30 (grows)", mapper.Run(With(0.0, 0.30, 0.20), p));
  PrintRun("then tau 0 -> 0.06", mapper.Run(With(0.06, 0.30, 0.20), p));
  std::printf("\n%d refinements in 9 runs\n\n", mapper.refinements());
}

// Moves every landmark by N(0, sigma) along the CAD's outward normal and
// changes its deviation by the same amount.
void AddNoise(hull::MappingInput& in, const hull::TriangleMesh& cad, double sigma) {
  const hull::MeshIndex index(cad);
  const hull::Pose x_Mg = in.x_gM.Inverse();
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0.0, sigma);
  for (auto& l : in.landmarks) {
    const hull::ClosestPoint cp = index.Closest(x_Mg * l.p_g);
    const double n = g(rng);
    l.p_g += in.x_gM.Rotate(cad.face_normals[static_cast<std::size_t>(cp.face)]) * n;
    l.deviation += n;
  }
}

void Summarise(const hull::MappingResult& r, double whole, double setup) {
  std::size_t inspected = 0, fouled = 0;
  for (const auto& z : r.zones) {
    inspected += z.rating != hull::FoulingRating::kUninspected;
    fouled += z.rating != hull::FoulingRating::kUninspected && z.rating != hull::FoulingRating::kZeroToOne;
  }
  std::printf(
      "\nwhole mapping %.1f s including the Mapper's set-up (%.2f s); %.0f of %.0f m^2 inspected (%zu of %zu "
      "zones), %zu objects, %zu zones with macrofouling; %.1f m^2 refined, %zu shapes\n\n",
      whole, setup, r.summary.inspected_area, r.summary.hull_area, inspected, r.zones.size(), r.objects.size(), fouled,
      r.summary.refined_area, r.summary.shapes);
}

void Curtiss() {
  hull::NullProgress p;
  auto t = Clock::now();
  const hull::SimulatedSurvey s = hull::SimulateSurvey(hull::SurveyPreset("curtiss"), p);
  const double sim = Since(t);
  const hull::MappingInput truth = hull::MappingInputFromTruth(s.bundle);
  std::printf("curtiss: %zu keyframes, %zu landmarks, %zu observations, %zu objects; simulated in %.1f s\n",
              truth.keyframes.size(), truth.landmarks.size(), s.bundle.features.size(), s.bundle.truth->objects.size(),
              sim);
  for (const bool noisy : {false, true}) {
    hull::MappingInput input = truth;
    if (noisy) AddNoise(input, s.cad, 0.003);
    std::printf("\nmapping input from the truth (true poses, landmarks with their true deviation)%s\n\n",
                noisy ? " + 3 mm noise along the normal" : "");
    t = Clock::now();
    hull::Mapper mapper(std::move(input), s.cad);
    const double setup = Since(t);
    Header();
    t = Clock::now();
    const hull::MappingResult first = mapper.Run(With(0.0, 0.12), p);
    const double whole = Since(t) + setup;
    PrintRun("whole mapping (tau 0)", first);
    PrintRun("tau 0 -> 0.06", mapper.Run(With(0.06, 0.12), p));
    PrintRun("alpha 0.12 -> 0.10", mapper.Run(With(0.0, 0.10), p));
    if (noisy) {
      t = Clock::now();
      const hull::MappingResult dense = mapper.Run(With(0.0, 0.30, 0.20), p);
      PrintRun("eps 0.20, alpha 0.30 (grows)", dense);
      PrintRun("then tau 0 -> 0.06", mapper.Run(With(0.06, 0.30, 0.20), p));
      Summarise(first, whole, setup);
      std::printf("dense eps/alpha: ");
      Summarise(dense, Since(t), 0);
    } else {
      Summarise(first, whole, setup);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0;
  bool demo = true, curtiss = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--grow-height") && i + 1 < argc) {
      grow_height = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--skip-curtiss")) {
      curtiss = false;
    } else if (!std::strcmp(argv[i], "--skip-demo")) {
      demo = false;
    } else {
      std::fprintf(stderr, "usage: bench_mapping [--threads N] [--skip-demo] [--skip-curtiss] [--grow-height M]\n");
      return 2;
    }
  }
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(threads));
  }
  std::printf("bench_mapping: %d threads (times in seconds of wall clock)\n\n",
              threads > 0 ? threads : tbb::info::default_concurrency());
  if (demo) Demo();
  if (curtiss) Curtiss();
  return 0;
}
