// bench_sonar: time per step of the sonar EKF (prediction + update) for
// n = 8, 100 and 500 features, on one core.
//
//   bench_sonar [--steps T] [--big-steps T]
//
// Scenarios (the prism layout of core/simulate/sonar_simulator.h with extra
// random features):
//   all in view  every feature inside the field of view at every step (the
//                worst case: m = 2n scalar measurements per update);
//   partial      features spread over a 3 m wide field, a part seen per step.
// Reported: measurements and state size per step, the median and mean time of
// a steady-state step (after every feature entered the state) and steps/s.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "simulate/sonar_simulator.h"
#include "sonar/sonar_ekf.h"
#include "sonar/sonar_runner.h"

namespace {

using hull::AcousticSequence;
using hull::SonarEkf;
using hull::SonarEkfOptions;
using hull::SonarInit;

struct Row {
  const char* scenario;
  int n;
  double seen;
  double state;
  double median_ms;
  double mean_ms;
};

Row Measure(const char* scenario, const AcousticSequence& seq, SonarEkfOptions options, int warmup) {
  const auto by_step = hull::MeasurementsByStep(seq);
  SonarEkf ekf(seq, options);
  std::vector<double> ms;
  double seen = 0, state = 0;
  for (int k = 0; k < seq.num_steps(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ekf.Step(k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr, by_step[static_cast<std::size_t>(k)]);
    const double dt = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (k < warmup) continue;
    ms.push_back(dt);
    seen += static_cast<double>(by_step[static_cast<std::size_t>(k)].size());
    state += static_cast<double>(ekf.state().size());
  }
  const double count = static_cast<double>(ms.size());
  double mean = 0;
  for (double v : ms) mean += v / count;
  std::sort(ms.begin(), ms.end());
  return Row{scenario, static_cast<int>(seq.truth->features.size()), seen / count, state / count, ms[ms.size() / 2],
             mean};
}

AcousticSequence Scene(int n, bool all_in_view, int steps) {
  hull::SonarSimulationOptions o;
  o.seed = 17;
  o.num_steps = steps;
  o.extra_features = n - 8;
  // All in view: a 0.5 x 0.6 x 0.3 m box around the prism stays inside the
  // 32 x 14 deg fan along the whole trajectory; partial: a 2 x 3 x 0.5 m field.
  o.extra_box = all_in_view ? Eigen::Vector3d(0.5, 0.6, 0.3) : Eigen::Vector3d(2.0, 3.0, 0.5);
  return hull::SimulateSonar(o);
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 60, big_steps = 16;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--steps")) steps = std::max(12, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--big-steps")) big_steps = std::max(12, std::atoi(argv[i + 1]));
  }
  std::printf("Sonar EKF time per step (prediction + update), one core\n");
  std::printf("%-12s %5s %-10s %-7s %10s %8s %10s %10s %10s\n", "scenario", "n", "init", "update", "meas/step",
              "state N", "median ms", "mean ms", "steps/s");
  for (bool all : {true, false}) {
    for (int n : {8, 100, 500}) {
      if (!all && n == 8) continue;
      const int T = n >= 500 ? big_steps : steps;
      const AcousticSequence seq = Scene(n, all, T);
      for (SonarInit init : {SonarInit::kPaper, SonarInit::kHypotheses}) {
        for (bool joseph : {true, false}) {
          if (!joseph && init == SonarInit::kHypotheses) continue;
          SonarEkfOptions o;
          o.init = init;
          o.joseph = joseph;
          // Steady state: after max_delay_steps every feature seen is in the state.
          const Row r = Measure(all ? "all in view" : "partial", seq, o, o.max_delay_steps + 2);
          std::printf("%-12s %5d %-10s %-7s %10.1f %8.0f %10.3f %10.3f %10.1f\n", r.scenario, r.n,
                      hull::SonarInitName(init), joseph ? "Joseph" : "short", r.seen, r.state, r.median_ms, r.mean_ms,
                      1000.0 / r.mean_ms);
          std::fflush(stdout);
        }
      }
    }
  }
  return 0;
}
