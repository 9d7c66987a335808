// What issue 11 asks the image chain to show, on rendered images of the
// prism, tank and above-the-object layouts: at least 90 % of the visible
// vertices detected per frame, at most 1 % wrong associations, and the
// EKF's final feature error within 1.5 times that of the run with the given
// correspondences (measurements.csv of the same sequence). Each figure is
// printed; docs/sonar.md quotes them.
#include <gtest/gtest.h>

#include <cstdio>

#include "simulate/sonar_image_simulator.h"
#include "sonar/sonar_image_runner.h"

namespace hull {
namespace {

struct Totals {
  int runs = 0;
  double detection_rate = 0;  // mean over runs of the mean per-frame rate
  double worst_frame = 1;
  int frames = 0, frames_below_90 = 0;
  int associations = 0, wrong = 0;
  double image_error = 0, given_error = 0;  // summed over runs
  int features = 0;
};

Totals RunLayout(const std::string& preset, int seeds, SonarInit init) {
  Totals t;
  for (int seed = 1; seed <= seeds; ++seed) {
    const SonarImageSimulation sim = SimulateSonarImages(SonarImagePreset(preset, static_cast<std::uint64_t>(seed)));
    SonarImageRunOptions o;
    o.run.ekf.init = init;
    const SonarImageRunResult r = RunSonarImages(
        sim.sequence, [&](int k) { return sim.images[static_cast<std::size_t>(k)]; }, o);
    SonarRunOptions g;
    g.ekf.init = init;
    const SonarRunResult given = RunSonarSequence(sim.sequence, g);
    EXPECT_TRUE(r.has_truth);
    const SonarImageEvaluation& e = r.evaluation;
    EXPECT_GE(e.mean_detection_rate, 0.9) << preset << " seed " << seed;
    EXPECT_EQ(e.duplicate_features, 0) << preset << " seed " << seed;
    // The given correspondences' error over the same true features.
    const SonarGivenComparison c = CompareWithGiven(r, given);
    const int n = c.features;
    const double ge = c.given_error;
    EXPECT_EQ(n, e.final_features_with_truth) << preset << " seed " << seed;
    EXPECT_GE(n, preset == "tank" ? 5 : 6) << preset << " seed " << seed << ": most vertices end in the state";
    ++t.runs;
    t.detection_rate += e.mean_detection_rate;
    t.worst_frame = std::min(t.worst_frame, e.min_detection_rate);
    t.frames += e.frames;
    t.frames_below_90 += e.frames_below_90;
    t.associations += e.associations;
    t.wrong += e.wrong_associations;
    t.image_error += e.final_mean_error;
    t.given_error += ge;
    t.features += n;
  }
  t.detection_rate /= t.runs;
  std::printf(
      "%s (%s, %d seeds): detected %.1f %% of the visible vertices per frame (worst frame %.0f %%, %d of %d frames "
      "below 90 %%), %d of %d associations wrong (%.2f %%), final mean error %.4f m from images vs %.4f m given "
      "(ratio %.2f), %.1f features per run\n",
      preset.c_str(), SonarInitName(init), seeds, 100 * t.detection_rate, 100 * t.worst_frame, t.frames_below_90,
      t.frames, t.wrong, t.associations, 100.0 * t.wrong / t.associations, t.image_error / t.runs,
      t.given_error / t.runs, t.image_error / t.given_error, static_cast<double>(t.features) / t.runs);
  return t;
}

void ExpectIssueFigures(const Totals& t) {
  EXPECT_GE(t.detection_rate, 0.9);
  EXPECT_LE(t.wrong, t.associations / 100) << t.wrong << " of " << t.associations;
  EXPECT_LE(t.image_error, 1.5 * t.given_error);
}

TEST(SonarImagesResults, Prism) { ExpectIssueFigures(RunLayout("prism", 4, SonarInit::kHypotheses)); }
TEST(SonarImagesResults, Tank) { ExpectIssueFigures(RunLayout("tank", 6, SonarInit::kHypotheses)); }
TEST(SonarImagesResults, Above) { ExpectIssueFigures(RunLayout("above", 4, SonarInit::kHypotheses)); }

}  // namespace
}  // namespace hull
