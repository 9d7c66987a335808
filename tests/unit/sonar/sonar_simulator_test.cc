// The sonar simulator: determinism, truth consistency (the contract's
// measurement model, field of view, control noise) and the independent
// contract checker on every preset.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include "base/error.h"
#include "simulate/sonar_simulator.h"
#include "sonar/acoustic_camera.h"
#include "support/test_files.h"

namespace hull {
namespace {

TEST(SonarSimulator, PresetsHaveThePapersShape) {
  const AcousticSequence prism = SimulateSonarPreset("prism", 1);
  EXPECT_EQ(prism.num_steps(), 21);
  ASSERT_TRUE(prism.truth.has_value());
  EXPECT_EQ(prism.truth->features.size(), 8u);
  EXPECT_EQ(prism.truth->poses[0], Vector6d::Zero());
  double roll_min = 0, roll_max = 0;
  for (const Vector6d& x : prism.truth->poses) {
    roll_min = std::min(roll_min, x[3]);
    roll_max = std::max(roll_max, x[3]);
    EXPECT_EQ(x[4], 0.0);
    EXPECT_EQ(x[5], 0.0);
    const Eigen::Vector3d centre(2.5, 0, 0);
    EXPECT_NEAR((centre - x.head<3>()).norm(), 2.4, 0.25);  // about 2.5 m away
  }
  EXPECT_GE(roll_max - roll_min, 20 * M_PI / 180);  // the elevation is observable
  // The prism is 0.2 x 0.2 x 0.3 m.
  const auto& f = prism.truth->features;
  EXPECT_NEAR((f[0] - f[1]).norm(), 0.2, 1e-12);
  EXPECT_NEAR((f[1] - f[2]).norm(), 0.2, 1e-12);
  EXPECT_NEAR((f[0] - f[4]).norm(), 0.3, 1e-12);

  const AcousticSequence tank = SimulateSonarPreset("tank", 1);
  EXPECT_EQ(tank.num_steps(), 8);
  ASSERT_EQ(tank.truth->features.size(), 4u);
  for (int k = 0; k < 8; ++k) {
    EXPECT_NEAR(tank.truth->poses[static_cast<std::size_t>(k)][3], k * 10 * M_PI / 180, 1e-12);
    EXPECT_NEAR(tank.truth->poses[static_cast<std::size_t>(k)][4], -20 * M_PI / 180, 1e-12);
  }
  const auto& t = tank.truth->features;           // A, B, C, D of the face toward the sonar
  EXPECT_NEAR((t[0] - t[3]).norm(), 0.3, 1e-12);  // AD
  EXPECT_NEAR((t[1] - t[2]).norm(), 0.3, 1e-12);  // BC
  EXPECT_NEAR((t[0] - t[1]).norm(), 0.2, 1e-12);  // AB
  EXPECT_EQ(tank.measurements.size(), 4u * 8u);   // every vertex seen at every roll

  // above: every true elevation below the boresight plane at the first view.
  const AcousticSequence above = SimulateSonarPreset("above", 1);
  int positive = 0, total = 0;
  for (const SonarMeasurement& m : above.measurements) {
    if (m.step != 0) continue;
    ++total;
    positive += SonarPolarOf(above.truth->poses[0], above.truth->features[static_cast<std::size_t>(m.feature)])[2] > 0;
  }
  EXPECT_GE(total, 6);
  EXPECT_EQ(positive, total);
  EXPECT_THROW(SimulateSonarPreset("cube", 1), OptionError);
}

TEST(SonarSimulator, DeterministicFromTheSeed) {
  const AcousticSequence a = SimulateSonarPreset("prism", 42), b = SimulateSonarPreset("prism", 42),
                         c = SimulateSonarPreset("prism", 43);
  ASSERT_EQ(a.measurements.size(), b.measurements.size());
  for (std::size_t i = 0; i < a.measurements.size(); ++i) {
    EXPECT_EQ(a.measurements[i].range, b.measurements[i].range);
    EXPECT_EQ(a.measurements[i].azimuth, b.measurements[i].azimuth);
  }
  EXPECT_EQ(a.initial_pose, b.initial_pose);
  EXPECT_NE(a.measurements[0].range, c.measurements[0].range);
}

TEST(SonarSimulator, MeasurementsFollowTheModelAndTheFieldOfView) {
  for (const char* preset : {"prism", "tank", "above"}) {
    SonarSimulationOptions o;
    o.preset = ParseSonarPreset(preset);
    o.seed = 11;
    o.extra_features = 60;  // some outside the field of view at times
    const AcousticSequence seq = SimulateSonar(o);
    const SonarSensor& s = seq.sensor;
    std::set<std::pair<std::int64_t, std::int64_t>> seen;
    double sum_r = 0, sum_a = 0;
    for (const SonarMeasurement& m : seq.measurements) {
      seen.insert({m.step, m.feature});
      const Eigen::Vector3d polar = SonarPolarOf(seq.truth->poses[static_cast<std::size_t>(m.step)],
                                                 seq.truth->features[static_cast<std::size_t>(m.feature)]);
      EXPECT_TRUE(InSonarView(s, polar)) << preset;
      EXPECT_TRUE(m.range >= s.range_min && m.range <= s.range_max && std::fabs(m.azimuth) <= s.azimuth_fov / 2);
      const double nr = (m.range - polar[0]) / s.range_sigma, na = WrapAngle(m.azimuth - polar[1]) / s.azimuth_sigma;
      EXPECT_LE(std::fabs(nr), 4.0);
      EXPECT_LE(std::fabs(na), 4.0);
      sum_r += nr * nr;
      sum_a += na * na;
    }
    const double n = static_cast<double>(seq.measurements.size());
    EXPECT_NEAR(std::sqrt(sum_r / n), 1.0, 0.15) << preset;
    EXPECT_NEAR(std::sqrt(sum_a / n), 1.0, 0.15) << preset;
    // Every feature clearly inside (4 sigma from the range and azimuth limits) is measured.
    for (int k = 0; k < seq.num_steps(); ++k) {
      for (std::size_t i = 0; i < seq.truth->features.size(); ++i) {
        const Eigen::Vector3d p = SonarPolarOf(seq.truth->poses[static_cast<std::size_t>(k)], seq.truth->features[i]);
        const bool clear = InSonarView(s, p) && std::fabs(p[1]) <= s.azimuth_fov / 2 - 4 * s.azimuth_sigma &&
                           p[0] >= s.range_min + 4 * s.range_sigma && p[0] <= s.range_max - 4 * s.range_sigma;
        if (clear) {
          EXPECT_TRUE(seen.count({k, seq.truth->feature_ids[i]})) << preset << " step " << k << " feature " << i;
        }
      }
    }
    // Controls: the true relative motion plus noise proportional to it.
    double sum_u = 0;
    for (std::size_t k = 1; k < seq.truth->poses.size(); ++k) {
      const Vector6d ut = Oplus(Ominus(seq.truth->poses[k - 1]), seq.truth->poses[k]);
      const Vector6d sigma = ControlSigma(seq.motion_noise, ut);
      const Vector6d r = PoseVectorDifference(seq.controls[k - 1].u, ut).cwiseQuotient(sigma);
      EXPECT_LE(r.cwiseAbs().maxCoeff(), 4.0 + 1e-9);
      sum_u += r.squaredNorm();
    }
    EXPECT_NEAR(std::sqrt(sum_u / (6.0 * (seq.num_steps() - 1))), 1.0, 0.35) << preset;
    // The initial pose is within 4 sigma of the truth.
    const Vector6d e0 =
        PoseVectorDifference(seq.initial_pose, seq.truth->poses[0]).cwiseQuotient(seq.initial_pose_sigma);
    EXPECT_LE(e0.cwiseAbs().maxCoeff(), 4.0);
  }
}

TEST(SonarSimulator, OptionsAreChecked) {
  SonarSimulationOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.distance = 6;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("distance:", 0), 0u);
  EXPECT_THROW(SimulateSonar(o), OptionError);
  o = SonarSimulationOptions();
  o.motion_noise.rotation_floor = 0;
  EXPECT_FALSE(o.Check());
}

// The independent checker of ../shared/tools (python3 with numpy).
std::string CheckerPath() { return std::string(HI_SHARED_DATA_DIR) + "/../tools/check-bundle.py"; }

bool CheckerAvailable(std::string* why) {
  if (!std::filesystem::exists(CheckerPath())) {
    *why = "the contract checker " + CheckerPath() + " is absent";
    return false;
  }
  if (std::system("/usr/bin/python3 -c 'import numpy' > /dev/null 2>&1") != 0) {
    *why = "/usr/bin/python3 with numpy is not installed";
    return false;
  }
  return true;
}

int RunChecker(const std::string& dir, bool contract, std::string* output) {
  const std::string cmd = "/usr/bin/python3 " + CheckerPath() + (contract ? " --contract " : " ") + dir + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  char buf[4096];
  while (std::fgets(buf, sizeof(buf), pipe)) *output += buf;
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SonarSimulator, EveryPresetPassesTheContractChecker) {
  std::string why;
  if (!CheckerAvailable(&why)) GTEST_SKIP() << why;
  for (const char* preset : {"prism", "tank", "above"}) {
    testing::ScratchDir dir(std::string("check_") + preset);
    WriteAcousticSequence(SimulateSonarPreset(preset, 3), dir.path());
    for (bool contract : {true, false}) {
      std::string out;
      EXPECT_EQ(RunChecker(dir.path(), contract, &out), 0)
          << preset << (contract ? " --contract" : " (full check)") << ":\n"
          << out;
      EXPECT_NE(out.find("PASS"), std::string::npos) << out;
    }
  }
}

TEST(SonarSimulator, TheContractCheckerCatchesABrokenSequence) {
  std::string why;
  if (!CheckerAvailable(&why)) GTEST_SKIP() << why;
  // The checker must be able to fail here: drop every measurement of step 5.
  AcousticSequence seq = SimulateSonarPreset("prism", 3);
  std::vector<SonarMeasurement> kept;
  for (const SonarMeasurement& m : seq.measurements) {
    if (m.step != 5) kept.push_back(m);
  }
  seq.measurements = kept;
  testing::ScratchDir dir("check_broken");
  WriteAcousticSequence(seq, dir.path());
  std::string out;
  EXPECT_EQ(RunChecker(dir.path(), true, &out), 1) << out;
  EXPECT_NE(out.find("every feature inside the field of view is measured"), std::string::npos) << out;
}

}  // namespace
}  // namespace hull
