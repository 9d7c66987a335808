// hullinspect-cli as a user runs it: --help on every command, bad command
// lines (exit 2 naming the option), bad input (the file, line and field), and
// a simulate -> validate round trip.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

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

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("hi-cli-test-" + std::to_string(::getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

const std::vector<std::string> kCommands = {"simulate", "validate", "info", "align", "run", "adjust", "map", "sonar"};

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
  TempDir tmp;
  const std::string missing = (tmp.path() / "no-such-bundle").string();
  const CliRun r = Cli({"validate", missing});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(missing), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INVALID"), std::string::npos) << r.output;
}

// Replaces field `column` (0-based) of line `line` (1-based) of a CSV file.
void CorruptCsv(const fs::path& file, int line, int column, const std::string& value) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_GT(static_cast<int>(lines.size()), line);
  std::string& l = lines[static_cast<std::size_t>(line - 1)];
  std::vector<std::string> fields;
  std::stringstream ss(l);
  for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
  ASSERT_GT(static_cast<int>(fields.size()), column);
  fields[static_cast<std::size_t>(column)] = value;
  l.clear();
  for (std::size_t i = 0; i < fields.size(); ++i) l += (i ? "," : "") + fields[i];
  std::ofstream out(file, std::ios::trunc);
  for (const std::string& x : lines) out << x << "\n";
}

std::string HeaderField(const fs::path& file, int column) {
  std::ifstream in(file);
  std::string header;
  std::getline(in, header);
  std::stringstream ss(header);
  std::string f;
  for (int i = 0; i <= column && std::getline(ss, f, ','); ++i) {
  }
  return f;
}

TEST(Cli, SimulateThenValidateAndNameACorruptField) {
  TempDir tmp;
  const std::string bundle = (tmp.path() / "demo").string();
  CliRun r = Cli({"simulate", "--preset", "demo", "--out", bundle, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("valid (0 errors"), std::string::npos) << r.output;
  r = Cli({"info", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;

  // A number that is not one, on line 7 of nav.csv: the file, the line and
  // the field are named, and nothing else is reported broken.
  const fs::path nav = fs::path(bundle) / "nav.csv";
  const std::string field = HeaderField(nav, 1);
  ASSERT_FALSE(field.empty());
  CorruptCsv(nav, 7, 1, "12.5x");
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("nav.csv:7"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(" + field + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INVALID (1 errors"), std::string::npos) << r.output;
  // The other commands refuse the bundle with the same location (exit 3).
  r = Cli({"info", bundle});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("nav.csv:7"), std::string::npos) << r.output;
}

}  // namespace
