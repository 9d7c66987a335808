// bench_survey_io: reading and validating a survey bundle whose features.csv
// holds about two million observations (stereo), written into a temporary
// folder first.
//
//   build/bin/bench_survey_io [--observations N] [--dir DIR]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "survey/survey_io.h"

int main(int argc, char** argv) {
  long long n_obs = 2000000;
  std::string dir = (std::filesystem::temp_directory_path() / "hi_bench_survey_io").string();
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--observations") && i + 1 < argc)
      n_obs = std::atoll(argv[++i]);
    else if (!std::strcmp(argv[i], "--dir") && i + 1 < argc)
      dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: %s [--observations N] [--dir DIR]\n", argv[0]);
      return 2;
    }
  }
  // A bundle of K keyframes with ~60 observations each.
  hull::SurveyBundle b;
  const long long per = 60;
  const long long K = (n_obs + per - 1) / per;
  for (long long k = 0; k < K; ++k) {
    hull::NavRecord n;
    n.keyframe = k;
    n.t = 1.8 * static_cast<double>(k);
    n.x_gv << 0.45 * static_cast<double>(k), 0.123456789, 10.5, 0.001, -0.002, 0.35;
    n.depth = 10.49;
    n.servo = 1.5707;
    b.nav.push_back(n);
    hull::DvlRecord d;
    d.keyframe = k;
    d.range = {1.512345, 1.623456, 1.734567, 1.845678};
    b.dvl.push_back(d);
    if (k) b.odometry.push_back({k - 1, k, (hull::Vector6d() << 0.45, 0.001, 0, 0, 0, 0.0001).finished()});
  }
  for (long long i = 0; i < n_obs; ++i) {
    hull::FeatureObservation f;
    f.keyframe = i / per;
    f.landmark = i / 4 + (i % 4) * 1000000;
    f.top = {123.456789 + static_cast<double>(i % 1000), 456.789123 + static_cast<double>(i % 500)};
    f.bottom = {f.top.x() + 0.5, f.top.y() - 76.25};
    f.has_bottom = true;
    b.features.push_back(f);
  }
  hull::WriteSurveyBundle(b, dir);
  const auto size = std::filesystem::file_size(std::filesystem::path(dir) / "features.csv");
  std::printf("features.csv: %lld observations, %.1f MB, %lld keyframes\n", n_obs, static_cast<double>(size) / 1e6, K);
  using Clock = std::chrono::steady_clock;
  for (int rep = 0; rep < 3; ++rep) {
    auto t0 = Clock::now();
    const hull::SurveyBundle r = hull::ReadSurveyBundle(dir);
    const double read_s = std::chrono::duration<double>(Clock::now() - t0).count();
    t0 = Clock::now();
    const auto problems = hull::ValidateSurveyBundle(dir);
    const double validate_s = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("run %d: read %.2f s (%.2f M observations/s), validate %.2f s, %zu problems\n", rep + 1, read_s,
                static_cast<double>(r.features.size()) / read_s / 1e6, validate_s, problems.size());
  }
  std::filesystem::remove_all(dir);
  return 0;
}
