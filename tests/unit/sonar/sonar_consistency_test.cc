// The filter's consistency without truth (sonar/sonar_consistency.h): the
// summed NIS and its windows against chi-square. A run whose innovations
// match their covariance is consistent, one whose sensor sigmas understate
// the real noise tenfold is called INCONSISTENT with the factor, a tiny
// excess over a very long run is not, and a burst of bad windows is.
#include <gtest/gtest.h>

#include "simulate/sonar_simulator.h"
#include "sonar/sonar_consistency.h"

namespace hull {
namespace {

// A run of `steps` steps, each with an update of 8 degrees of freedom and
// the NIS nis(k).
template <typename F>
SonarRunResult NisRun(int steps, F nis) {
  SonarRunResult r;
  for (int k = 0; k < steps; ++k) {
    SonarStepRecord s;
    s.estimate.step = k;
    s.estimate.nis_dof = k == 0 ? 0 : 8;  // the first step updates nothing
    s.estimate.nis = k == 0 ? 0 : nis(k);
    r.steps.push_back(s);
  }
  return r;
}

TEST(SonarConsistency, VerdictsFromTheInnovations) {
  const SonarConsistency fine = CheckSonarConsistency(NisRun(41, [](int k) { return k % 2 ? 6.0 : 10.0; }));
  EXPECT_TRUE(fine.known);
  EXPECT_EQ(fine.dof, 320);
  EXPECT_DOUBLE_EQ(fine.nis, 320);
  EXPECT_FALSE(fine.inconsistent);
  EXPECT_FALSE(fine.conservative);
  EXPECT_EQ(fine.windows, 36);
  EXPECT_EQ(fine.Verdict().rfind("consistent (NIS 1.00 per degree of freedom over 320", 0), 0u) << fine.Verdict();

  const SonarConsistency over = CheckSonarConsistency(NisRun(41, [](int) { return 8.0 * 9; }));
  EXPECT_TRUE(over.inconsistent);
  EXPECT_EQ(over.windows_high, over.windows);
  EXPECT_NE(over.Verdict().find("INCONSISTENT: the innovations are 3.0 times larger"), std::string::npos)
      << over.Verdict();

  const SonarConsistency under = CheckSonarConsistency(NisRun(41, [](int) { return 1.0; }));
  EXPECT_FALSE(under.inconsistent);
  EXPECT_TRUE(under.conservative);

  // 1.2 per degree of freedom over 80,000: far outside the interval, but
  // not a mismatch that matters; no window is high.
  const SonarConsistency long_run = CheckSonarConsistency(NisRun(10001, [](int) { return 8 * 1.2; }));
  EXPECT_GT(long_run.nis, long_run.high);
  EXPECT_FALSE(long_run.inconsistent);
  // A burst: a third of the run ten times its dof.
  const SonarConsistency burst = CheckSonarConsistency(NisRun(61, [](int k) { return k > 40 ? 80.0 : 8.0; }));
  EXPECT_TRUE(burst.inconsistent) << burst.Verdict();

  EXPECT_FALSE(CheckSonarConsistency(SonarRunResult{}).known);
  EXPECT_EQ(CheckSonarConsistency(SonarRunResult{}).Verdict(), "not known (no update used a measurement)");
}

TEST(SonarConsistency, SigmasThatUnderstateTheNoiseAreFound) {
  AcousticSequence seq = SimulateSonarPreset("prism", 4);
  EXPECT_FALSE(CheckSonarConsistency(RunSonarSequence(seq)).inconsistent);
  // The same measurements, the sensor claiming ten times better ranges and angles.
  seq.sensor.range_sigma /= 10;
  seq.sensor.azimuth_sigma /= 10;
  const SonarConsistency c = CheckSonarConsistency(RunSonarSequence(seq));
  EXPECT_TRUE(c.inconsistent) << c.Verdict();
  EXPECT_GT(std::sqrt(c.ratio()), 4.0) << c.Verdict();
}

}  // namespace
}  // namespace hull
