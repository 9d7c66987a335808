// hullinspect-cli never reports what was not seen (issue 23, part 1): on a
// version 2 bundle whose images show nothing, or whose top and bottom images
// are swapped, `run` stops with "insufficient data" and exit 4 within
// seconds, writes no results folder and says why; `sonar --from-images` on
// blank images does the same; a bundle without a single feature observation
// maps nothing. The repros, one test each.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image_file.h"
#include "support/cli_run.h"
#include "support/test_files.h"
#include "support/test_surveys.h"

namespace {

namespace fs = std::filesystem;
using hull::testing::CliRun;
using hull::testing::ReadText;
using hull::testing::ScratchDir;
using hull::testing::WriteText;

CliRun Cli(const std::vector<std::string>& args) { return hull::testing::RunProgram(HI_CLI_PATH, args); }
bool Has(const CliRun& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

// A short stretch of the demo with its images (48 keyframes at half
// resolution) and no features.csv, made once for the suite.
class CliEvidence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_evidence");
    const CliRun r = Cli({"simulate", "--preset", "demo", "--images", "--start", "89", "--end", "90.5",
                          "--camera-scale", "0.5", "--out", *dir_ / "bundle", "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    fs::remove(*dir_ / "bundle/features.csv");
  }
  static void TearDownTestSuite() { delete dir_; }
  // A copy of the bundle under `name`.
  static std::string Copy(const std::string& name) {
    const std::string to = *dir_ / name;
    fs::remove_all(to);
    fs::copy(*dir_ / "bundle", to, fs::copy_options::recursive);
    return to;
  }
  // `run` on `bundle`: exit 4 in under 10 s, "insufficient data", no --out.
  static CliRun RunExpectingInsufficientData(const std::string& bundle) {
    const std::string out = *dir_ / "out";
    const auto t0 = std::chrono::steady_clock::now();
    const CliRun r = Cli({"run", bundle, "--out", out, "--quiet"});
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              hull::testing::RefusalSeconds());
    EXPECT_EQ(r.exit_code, 4) << r.output;
    EXPECT_TRUE(Has(r, "insufficient data (front end)")) << r.output;
    EXPECT_TRUE(Has(r, bundle + "/images")) << r.output;
    EXPECT_FALSE(fs::exists(out));
    return r;
  }
  static ScratchDir* dir_;
};
ScratchDir* CliEvidence::dir_ = nullptr;

TEST_F(CliEvidence, BlackImagesAreNotACleanHull) {
  const std::string b = Copy("black");
  for (const auto& e : fs::directory_iterator(fs::path(b) / "images")) {
    cv::Mat m = hull::ReadImageFile(e.path().string());
    m.setTo(0);
    hull::WriteImageFile(e.path().string(), m);
  }
  const CliRun r = RunExpectingInsufficientData(b);
  EXPECT_TRUE(Has(r, "the top camera's images show nothing")) << r.output;
  EXPECT_FALSE(Has(r, "objects detected")) << r.output;
}

TEST_F(CliEvidence, SwappedTopAndBottomImagesAreNamed) {
  const std::string b = Copy("swapped");
  const fs::path images = fs::path(b) / "images";
  std::vector<fs::path> tops;
  for (const auto& e : fs::directory_iterator(images)) {
    if (e.path().filename().string().find("_top") != std::string::npos) tops.push_back(e.path());
  }
  ASSERT_FALSE(tops.empty());
  for (const fs::path& top : tops) {
    std::string bottom = top.string();
    bottom.replace(bottom.find("_top"), 4, "_bottom");
    fs::rename(top, images / "swap");
    fs::rename(bottom, top);
    fs::rename(images / "swap", bottom);
  }
  const CliRun r = RunExpectingInsufficientData(b);
  EXPECT_TRUE(Has(r, "the top and bottom images appear swapped")) << r.output;
}

TEST_F(CliEvidence, ABundleWithoutObservationsMapsNothing) {
  // A version 1 bundle whose features.csv holds its header only.
  const ScratchDir tmp("cli_evidence_empty");
  hull::test::WriteSmallSurvey(tmp / "b");
  const std::string features = tmp / "b/features.csv";
  const std::string text = ReadText(features);
  WriteText(features, text.substr(0, text.find('\n') + 1));
  const CliRun r = Cli({"run", tmp / "b", "--out", tmp / "out", "--quiet"});
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_TRUE(Has(r, "insufficient data")) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "out"));
}

TEST_F(CliEvidence, SonarOnBlankImagesStops) {
  const ScratchDir tmp("cli_evidence_sonar");
  const std::string seq = tmp / "prism";
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--images", "--out", seq, "--quiet"}).exit_code, 0);
  for (const auto& e : fs::directory_iterator(fs::path(seq) / "images")) {
    cv::Mat m = hull::ReadImageFile(e.path().string());
    m.setTo(0);
    hull::WriteImageFile(e.path().string(), m);
  }
  const CliRun r = Cli({"sonar", seq, "--from-images", "--out", tmp / "out", "--quiet"});
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_TRUE(Has(r, "insufficient data (sonar images)")) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "out"));
  // From the given measurements the same sequence runs.
  EXPECT_EQ(Cli({"sonar", seq, "--from-measurements", "--out", tmp / "given", "--quiet"}).exit_code, 0);
}

}  // namespace
