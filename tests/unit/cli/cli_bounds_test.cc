// Bounded resources on every input (issue 23, part 3): the bombs that passed
// every check are refused before anything is allocated, each naming its
// file and field, with exit 3 in a few seconds: a 16384 x 16384 camera
// (validate said valid, features reached 5.7 GB), a 20 GB sparse file as an
// image (std::bad_alloc naming nothing), acoustic images of 16384 x 16384
// (past 300 s at 5.5 GB) and a 3 GB sparse controls.csv (validate busy past
// 120 s at 3.1 GB).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "support/cli_run.h"
#include "support/test_files.h"

namespace {

namespace fs = std::filesystem;
using hull::testing::CliRun;
using hull::testing::ReadText;
using hull::testing::ScratchDir;
using hull::testing::WriteText;

bool Has(const CliRun& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

// The CLI, which must end within 10 s (RefusalSeconds: more under the sanitizers).
CliRun Cli(const std::vector<std::string>& args) {
  const auto t0 = std::chrono::steady_clock::now();
  CliRun r = hull::testing::RunProgram(HI_CLI_PATH, args);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            hull::testing::RefusalSeconds())
      << args[0];
  return r;
}

// Replaces the first match of `pattern` in the file.
void Replace(const std::string& path, const std::string& pattern, const std::string& with) {
  WriteText(path,
            std::regex_replace(ReadText(path), std::regex(pattern), with, std::regex_constants::format_first_only));
}

TEST(CliBounds, AHugeCameraAndASparseImageAreRefusedBeforeAllocation) {
  const ScratchDir tmp("cli_bounds_camera");
  const std::string b = tmp / "b";
  ASSERT_EQ(Cli({"simulate", "--preset", "demo", "--images", "--start", "89", "--end", "89.4", "--camera-scale", "0.25",
                 "--out", b, "--quiet"})
                .exit_code,
            0);
  fs::copy(b, tmp / "huge", fs::copy_options::recursive);
  Replace(tmp / "huge/survey.json", "\"width\": *[0-9]+", "\"width\": 16384");
  Replace(tmp / "huge/survey.json", "\"height\": *[0-9]+", "\"height\": 16384");
  CliRun r = Cli({"validate", tmp / "huge"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, "survey.json")) << r.output;
  EXPECT_TRUE(Has(r, "(camera.width): 16384 x 16384 pixels is 268 megapixels")) << r.output;
  r = Cli({"features", tmp / "huge", "--out", tmp / "f.csv"});
  EXPECT_EQ(r.exit_code, 3) << r.output;

  // One image a 20 GB sparse file: refused from its size, naming it.
  std::string image;
  for (const auto& e : fs::directory_iterator(b + "/images")) image = e.path().string();
  ASSERT_FALSE(image.empty());
  fs::resize_file(image, std::uintmax_t{20} << 30);
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"validate", b}, {"features", b, "--out", tmp / "f.csv"}}) {
    r = Cli(args);
    EXPECT_EQ(r.exit_code, 3) << args[0] << ": " << r.output;
    EXPECT_TRUE(Has(r, image + ": refused: the file is 20480.0 MiB")) << args[0] << ": " << r.output;
  }
  fs::remove(image);  // the sparse file takes no disk, but nothing should keep it
}

TEST(CliBounds, HugeAcousticImagesAndASparseControlsFileAreRefused) {
  const ScratchDir tmp("cli_bounds_sonar");
  const std::string seq = tmp / "prism";
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--images", "--out", seq, "--quiet"}).exit_code, 0);
  fs::copy(seq, tmp / "huge", fs::copy_options::recursive);
  Replace(tmp / "huge/sonar.json", "\"range_bins\": *[0-9]+", "\"range_bins\": 16384");
  Replace(tmp / "huge/sonar.json", "\"beams\": *[0-9]+", "\"beams\": 16384");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"validate", tmp / "huge"}, {"sonar", tmp / "huge", "--from-images", "--out", tmp / "out", "--quiet"}}) {
    const CliRun r = Cli(args);
    EXPECT_EQ(r.exit_code, 3) << args[0] << ": " << r.output;
    EXPECT_TRUE(Has(r, "sonar.json")) << r.output;
    EXPECT_TRUE(Has(r, "(image.beams): 16384 range bins x 16384 beams")) << r.output;
  }
  EXPECT_FALSE(fs::exists(tmp / "out"));

  fs::resize_file(seq + "/controls.csv", std::uintmax_t{3} << 30);
  const CliRun r = Cli({"validate", seq});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, seq + "/controls.csv: refused: the file is 3072.0 MiB, more than the 256.0 MiB")) << r.output;
}

}  // namespace
