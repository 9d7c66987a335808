// hullinspect-cli as a user runs it: --help on every command, bad command
// lines (exit 2 naming the option), bad input (the file, line and field), and
// a simulate -> validate round trip.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
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

}  // namespace
