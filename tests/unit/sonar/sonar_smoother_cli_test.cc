// hullinspect-cli sonar --smoother as a user runs it: the smoother's files
// beside the filter's (given correspondences and from images), the summary's
// smoother block, and a bad option named.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.h"
#include "support/test_files.h"

namespace {

// Runs the CLI; returns the exit code and appends stdout and stderr to output.
int Cli(const std::vector<std::string>& args, std::string* output) {
  const hull::testing::CliRun r = hull::testing::RunProgram(HI_CLI_PATH, args);
  *output += r.output;
  return r.exit_code;
}

TEST(SonarSmootherCli, WritesTheSmoothersResultsBesideTheFilters) {
  const hull::testing::ScratchDir tmp("cli_sonar_smoother");
  const std::string seq = tmp / "tank";
  std::string out;
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-tank", "--images", "--seed", "5", "--out", seq, "--quiet"}, &out), 0)
      << out;
  // Without --smoother: the filter's files only.
  ASSERT_EQ(Cli({"sonar", seq, "--out", tmp / "ekf", "--quiet"}, &out), 0) << out;
  EXPECT_FALSE(std::filesystem::exists(tmp / "ekf/smoother_poses.csv"));
  EXPECT_EQ(hull::testing::ReadText(tmp / "ekf/summary.json").find("\"smoother\""), std::string::npos);

  for (const char* source : {"--from-measurements", "--from-images"}) {
    const std::string dir = tmp / (std::string("smoothed") + source);
    out.clear();
    ASSERT_EQ(Cli({"sonar", seq, source, "--smoother", "--out", dir, "--quiet"}, &out), 0) << out;
    EXPECT_NE(out.find("smoother: final mean feature error"), std::string::npos) << out;
    EXPECT_TRUE(std::filesystem::exists(dir + "/poses.csv"));  // the filter's stay
    EXPECT_TRUE(std::filesystem::exists(dir + "/features.csv"));
    const std::string poses = hull::testing::ReadText(dir + "/smoother_poses.csv");
    EXPECT_EQ(poses.rfind("step,x,y,z,roll,pitch,yaw,sigma_x", 0), 0u) << poses.substr(0, 200);
    EXPECT_NE(poses.find("pose_nees"), std::string::npos);
    EXPECT_EQ(std::count(poses.begin(), poses.end(), '\n'), 9);  // header and 8 steps
    const std::string features = hull::testing::ReadText(dir + "/smoother_features.csv");
    EXPECT_EQ(features.rfind("step,feature,smoothed,x,y,z,cov_x_x", 0), 0u) << features.substr(0, 200);
    const std::string summary = hull::testing::ReadText(dir + "/summary.json");
    EXPECT_NE(summary.find("\"smoother\""), std::string::npos);
    EXPECT_NE(summary.find("\"covariance_ok\": true"), std::string::npos) << summary;
    EXPECT_NE(summary.find("\"normalised_joint_nees\""), std::string::npos);
  }
  out.clear();
  EXPECT_EQ(Cli({"sonar", seq, "--smoother", "--smoother-iterations", "0", "--out", tmp / "x"}, &out), 2);
  EXPECT_NE(out.find("max_iterations"), std::string::npos) << out;
}

}  // namespace
