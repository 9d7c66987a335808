// hullinspect-cli as a user runs it: --help on every command, bad command
// lines (exit 2 naming the option), bad input (the file, line and field), and
// a simulate -> validate round trip.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "support/test_files.h"

namespace {

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

CliRun Cli(const std::vector<std::string>& args) {
  std::string cmd = Quote(HI_CLI_PATH);
  for (const std::string& a : args) cmd += " " + Quote(a);
  cmd += " 2>&1";
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

const std::vector<std::string> kCommands = {"simulate", "validate", "info",  "align",  "run",
                                            "adjust",   "map",      "sonar", "export", "plugins"};

TEST(Cli, EveryCommandHasHelp) {
  for (const std::string& c : kCommands) {
    for (const char* flag : {"--help", "-h"}) {
      const CliRun r = Cli({c, flag});
      EXPECT_EQ(r.exit_code, 0) << c << " " << flag << ":\n" << r.output;
      EXPECT_NE(r.output.find("usage: hullinspect-cli " + c), std::string::npos) << c << " " << flag << ":\n"
                                                                                 << r.output;
    }
  }
  const CliRun top = Cli({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  for (const std::string& c : kCommands) EXPECT_NE(top.output.find("  " + c + " "), std::string::npos) << c;
}

TEST(Cli, BadCommandLinesExitTwoNamingTheProblem) {
  CliRun r = Cli({});
  EXPECT_EQ(r.exit_code, 2);
  r = Cli({"frobnicate"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("frobnicate"), std::string::npos) << r.output;
  r = Cli({"validate", "somewhere", "--bogus", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("unknown option --bogus"), std::string::npos) << r.output;
  r = Cli({"adjust", "somewhere", "--mesh"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("option --mesh needs a value"), std::string::npos) << r.output;
  r = Cli({"simulate", "--preset", "demo", "--out", "x", "--seed", "seven"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--seed expects an integer, got 'seven'"), std::string::npos) << r.output;
  r = Cli({"adjust", "somewhere", "--out", "x", "--linear-solver", "magic"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--linear-solver expects sparse-schur or iterative-schur"), std::string::npos) << r.output;
}

TEST(Cli, MissingBundleIsNamed) {
  const hull::testing::ScratchDir tmp("cli_missing");
  const std::string missing = tmp / "no-such-bundle";
  const CliRun r = Cli({"validate", missing});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(missing), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INVALID"), std::string::npos) << r.output;
}

// Field `field` (0-based) of a CSV line (no quoting in survey files).
std::string CsvField(const std::string& line, int field) {
  const auto start = static_cast<std::size_t>(hull::testing::CsvColumn(line, field) - 1);
  return line.substr(start, line.find(',', start) - start);
}

TEST(Cli, SimulateThenValidateAndNameACorruptField) {
  const hull::testing::ScratchDir tmp("cli_round_trip");
  const std::string bundle = tmp / "demo";
  CliRun r = Cli({"simulate", "--preset", "demo", "--out", bundle, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("valid (0 errors"), std::string::npos) << r.output;
  r = Cli({"info", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;

  // A number that is not one, on line 7 of nav.csv: the file, the line and
  // the field are named, and nothing else is reported broken.
  const std::string nav = bundle + "/nav.csv";
  const std::string text = hull::testing::ReadText(nav);
  const std::string field = CsvField(hull::testing::LineOf(text, 1), 1);
  ASSERT_FALSE(field.empty());
  const std::string line = hull::testing::LineOf(text, 7);
  const int column = hull::testing::CsvColumn(line, 1);
  const std::string value = CsvField(line, 1);
  hull::testing::ReplaceLine(nav, 7,
                             line.substr(0, static_cast<std::size_t>(column - 1)) + "12.5x" +
                                 line.substr(static_cast<std::size_t>(column - 1) + value.size()));
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("nav.csv:7:" + std::to_string(column)), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(" + field + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INVALID (1 errors"), std::string::npos) << r.output;
  // The other commands refuse the bundle with the same location (exit 3).
  r = Cli({"info", bundle});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("nav.csv:7"), std::string::npos) << r.output;
}

TEST(Cli, SonarFromImages) {
  const hull::testing::ScratchDir tmp("cli_sonar_images");
  const std::string seq = tmp / "tank";
  CliRun r = Cli({"simulate", "--preset", "sonar-tank", "--images", "--out", seq, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(seq + "/images/7.png"));
  EXPECT_TRUE(std::filesystem::exists(seq + "/truth/scene.ply"));
  r = Cli({"validate", seq});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"info", seq});
  EXPECT_NE(r.output.find("512 range bins x 128 beams"), std::string::npos) << r.output;

  // With measurements.csv the default is the given correspondences...
  r = Cli({"sonar", seq, "--out", tmp / "given", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(hull::testing::ReadText(tmp / "given/summary.json").find("\"source\": \"measurements\""),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(tmp / "given/detections.csv"));
  // ... --from-images runs the whole chain ...
  r = Cli({"sonar", seq, "--from-images", "--out", tmp / "images", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("of the visible true features detected per frame"), std::string::npos) << r.output;
  const std::string summary = hull::testing::ReadText(tmp / "images/summary.json");
  EXPECT_NE(summary.find("\"source\": \"images\""), std::string::npos);
  EXPECT_NE(summary.find("\"mean_detection_rate\""), std::string::npos);
  EXPECT_NE(hull::testing::ReadText(tmp / "images/detections.csv").find("step,detection,row,col"), std::string::npos);
  // ... and without measurements.csv the images are the default.
  std::filesystem::remove(seq + "/measurements.csv");
  r = Cli({"sonar", seq, "--out", tmp / "default", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(hull::testing::ReadText(tmp / "default/summary.json").find("\"source\": \"images\""), std::string::npos);
  r = Cli({"sonar", seq, "--from-measurements", "--out", tmp / "x", "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("measurements.csv"), std::string::npos) << r.output;
  r = Cli({"sonar", seq, "--from-images", "--from-measurements", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;

  // A truncated image is named (exit 3).
  const std::string image = seq + "/images/3.png";
  const std::string bytes = hull::testing::ReadText(image);
  hull::testing::WriteText(image, bytes.substr(0, bytes.size() / 3));
  r = Cli({"sonar", seq, "--out", tmp / "x", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("images/3.png"), std::string::npos) << r.output;

  // Images need a sonar preset; a version 1 sequence has none to use.
  r = Cli({"simulate", "--preset", "demo", "--images", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string v1 = tmp / "v1";
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--out", v1}).exit_code, 0);
  r = Cli({"sonar", v1, "--from-images", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no images"), std::string::npos) << r.output;
}

}  // namespace
