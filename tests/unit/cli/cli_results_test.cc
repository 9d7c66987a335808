// hullinspect-cli's results folders as a user meets them (issue 23, part 2,
// and the pairings of part 5): a folder of the user's is refused before any
// work and never loses a file; `adjust` and `sonar` replace their folder as
// a whole, so a kill at any rename leaves the previous folder whole; `map`,
// `mosaic` and `compare` refuse a folder mixing files of different runs,
// and a bundle or mesh that is not the one the results came from.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "geometry/mesh_io.h"
#include "support/cli_run.h"
#include "support/test_files.h"
#include "support/test_meshes.h"
#include "support/test_surveys.h"

namespace {

namespace fs = std::filesystem;
using hull::testing::CliRun;
using hull::testing::ReadText;
using hull::testing::ScratchDir;
using hull::testing::WriteText;

CliRun Cli(const std::vector<std::string>& args) { return hull::testing::RunProgram(HI_CLI_PATH, args); }

// The CLI under `env` with the variables given ("NAME=value"). In a
// sanitizer build the CLI loads ASan's runtime, which refuses to start when
// a preloaded library (the rename shim) comes before it; the shim intercepts
// only rename(), which ASan leaves alone, so the order check is turned off.
CliRun CliWith(const std::vector<std::string>& env, const std::vector<std::string>& args) {
  std::vector<std::string> all = env;
  const char* asan = std::getenv("ASAN_OPTIONS");
  all.push_back(std::string("ASAN_OPTIONS=") + (asan != nullptr && *asan != '\0' ? std::string(asan) + ":" : "") +
                "verify_asan_link_order=0");
  all.push_back(HI_CLI_PATH);
  all.insert(all.end(), args.begin(), args.end());
  return hull::testing::RunProgram("env", all);
}

// Every file under dir with its contents, hidden ones (the manifest) included.
std::map<std::string, std::string> Files(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).generic_string()] = ReadText(e.path().string());
  }
  return out;
}

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool Has(const CliRun& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

// The small survey, and the pipeline's results of it, made once for the suite.
class CliResults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_results");
    hull::test::WriteSmallSurvey(*dir_ / "bundle");
    const CliRun r = Cli({"run", *dir_ / "bundle", "--out", *dir_ / "R", "--threads", "1", "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Bundle() { return *dir_ / "bundle"; }
  static std::string Results() { return *dir_ / "R"; }
  static ScratchDir* dir_;
};
ScratchDir* CliResults::dir_ = nullptr;

TEST_F(CliResults, RunIntoAFolderOfTheUsersIsRefusedAndNothingIsLost) {
  // The issue's repro: mkdir -p U/mapping; echo x > U/mapping/photo.jpg; run B --out U.
  const ScratchDir tmp("cli_results_user");
  const std::string u = tmp / "U";
  fs::create_directories(u + "/mapping");
  WriteText(u + "/mapping/photo.jpg", "x");
  const auto t0 = std::chrono::steady_clock::now();
  CliRun r = Cli({"run", Bundle(), "--out", u, "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_LT(SecondsSince(t0), hull::testing::RefusalSeconds());
  EXPECT_TRUE(Has(r, "--out " + u + ": ")) << r.output;
  EXPECT_TRUE(Has(r, "holds files HullInspect did not write")) << r.output;
  EXPECT_TRUE(Has(r, "--force")) << r.output;
  EXPECT_EQ(Files(u), (std::map<std::string, std::string>{{"mapping/photo.jpg", "x"}}));
  // Forced: the results go in beside the photo, which stays.
  r = Cli({"run", Bundle(), "--out", u, "--force", "--threads", "1", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadText(u + "/mapping/photo.jpg"), "x");
  EXPECT_TRUE(fs::exists(u + "/mapping/model.ply"));
  const std::string manifest = ReadText(u + "/.hullinspect-results.json");
  EXPECT_NE(manifest.find("\"mapping/model.ply\""), std::string::npos);
  EXPECT_EQ(manifest.find("photo.jpg"), std::string::npos);
  // Now a results folder of ours: a new run needs no --force and keeps the photo.
  r = Cli({"run", Bundle(), "--out", u, "--threads", "1", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadText(u + "/mapping/photo.jpg"), "x");
}

TEST_F(CliResults, AdjustNeverOverwritesTheUsersOwnLandmarks) {
  const ScratchDir tmp("cli_results_landmarks");
  const std::string u = tmp / "U";
  fs::create_directories(u);
  WriteText(u + "/landmarks.csv", "my own landmarks\n");
  CliRun r = Cli({"adjust", Bundle(), "--out", u, "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, "holds files HullInspect did not write")) << r.output;
  // Even forced, a file of the user's is not replaced: the run stops before
  // its folder goes in, naming it.
  r = Cli({"adjust", Bundle(), "--out", u, "--force", "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, u + "/landmarks.csv")) << r.output;
  EXPECT_TRUE(Has(r, "not replaced")) << r.output;
  EXPECT_EQ(Files(u), (std::map<std::string, std::string>{{"landmarks.csv", "my own landmarks\n"}}));
}

TEST_F(CliResults, AWritableOutUnderAReadOnlyFolderIsRefusedBeforeAnyWork) {
  // The results are written beside --out and swapped in: the parent must
  // take a new folder. Root writes anywhere, so the CLI runs as nobody then.
  const ScratchDir tmp("cli_results_readonly");
  const std::string parent = tmp / "ro";
  const std::string out = parent + "/out";
  fs::create_directories(out);
  for (const std::string& d : {tmp.path(), Bundle(), *dir_ / ""}) {
    fs::permissions(d, fs::perms::others_read | fs::perms::others_exec, fs::perm_options::add);
  }
  fs::permissions(out, fs::perms::all);
  fs::permissions(parent, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  std::vector<std::string> as_user;
  if (::geteuid() == 0) {
    if (!fs::exists("/usr/bin/setpriv")) GTEST_SKIP() << "running as root without setpriv";
    as_user = {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"};
  }
  std::vector<std::string> args = as_user;
  args.insert(args.end(), {HI_CLI_PATH, "adjust", Bundle(), "--out", out, "--quiet"});
  const auto t0 = std::chrono::steady_clock::now();
  const CliRun r = hull::testing::RunProgram(args[0], std::vector<std::string>(args.begin() + 1, args.end()));
  fs::permissions(parent, fs::perms::owner_all, fs::perm_options::add);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_LT(SecondsSince(t0), hull::testing::RefusalSeconds());
  EXPECT_TRUE(Has(r, "cannot write in '" + parent + "'")) << r.output;
  EXPECT_TRUE(fs::is_empty(out));
}

// Runs `args` (which write into `dir`) once to count its renames, then once
// per rename killed just before it: after each kill `dir` is as the counted
// run left it, whole, and readable by `check` (when given).
void KillAtEveryRename(const std::string& dir, const std::vector<std::string>& args, const std::string& log) {
  fs::remove(log);
  CliRun r = CliWith({"LD_PRELOAD=" + std::string(HI_KILL_AT_RENAME), "HI_RENAME_LOG=" + log}, args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto before = Files(dir);
  int renames = 0;
  for (std::size_t at = 0; (at = ReadText(log).find('\n', at)) != std::string::npos; ++at) ++renames;
  ASSERT_GE(renames, 3) << "the run renamed " << renames << " times";
  for (int k = 1; k <= renames; ++k) {
    r = CliWith({"LD_PRELOAD=" + std::string(HI_KILL_AT_RENAME), "HI_KILL_AT_RENAME=" + std::to_string(k)}, args);
    // Killed: the shell that ran it reports 128 + SIGKILL.
    EXPECT_TRUE(r.exit_code == 137 || r.exit_code == -1) << "not killed at rename " << k << ": " << r.output;
    EXPECT_EQ(Files(dir), before) << "killed at rename " << k << " of " << renames;
  }
}

TEST_F(CliResults, AdjustKilledAtAnyRenameLeavesThePreviousFolderWhole) {
  const ScratchDir tmp("cli_results_kill_adjust");
  const std::string r = tmp / "R";
  ASSERT_EQ(Cli({"adjust", Bundle(), "--out", r, "--model", "naive", "--quiet"}).exit_code, 0);
  KillAtEveryRename(r, {"adjust", Bundle(), "--out", r, "--quiet"}, tmp / "renames");
  // What is left is one run's adjustment, which map reads.
  const CliRun m = Cli({"map", r, "--quiet"});
  EXPECT_EQ(m.exit_code, 0) << m.output;
}

TEST_F(CliResults, SonarKilledAtAnyRenameLeavesThePreviousFolderWhole) {
  const ScratchDir tmp("cli_results_kill_sonar");
  const std::string seq = tmp / "prism";
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--out", seq, "--quiet"}).exit_code, 0);
  const std::string r = tmp / "R";
  ASSERT_EQ(Cli({"sonar", seq, "--out", r, "--init", "paper", "--quiet"}).exit_code, 0);
  KillAtEveryRename(r, {"sonar", seq, "--out", r, "--quiet"}, tmp / "renames");
}

TEST_F(CliResults, MapRefusesAFolderMixingTwoAdjustments) {
  // A naive run's landmarks.csv beside a max-mixture adjustment.json: map
  // would map a mixture; it names the file instead.
  const ScratchDir tmp("cli_results_mixed");
  ASSERT_EQ(Cli({"adjust", Bundle(), "--out", tmp / "naive", "--model", "naive", "--quiet"}).exit_code, 0);
  ASSERT_EQ(Cli({"adjust", Bundle(), "--out", tmp / "mm", "--quiet"}).exit_code, 0);
  fs::copy_file(tmp / "naive/landmarks.csv", tmp / "mm/landmarks.csv", fs::copy_options::overwrite_existing);
  const CliRun r = Cli({"map", tmp / "mm", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, tmp / "mm/landmarks.csv")) << r.output;
  EXPECT_TRUE(Has(r, "has changed since run")) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "mm/mapping"));
}

TEST_F(CliResults, MosaicRefusesTheBundleOfAnotherSurvey) {
  // Another survey of the same plan: the same keyframe ids, another
  // navigation. Its images would be textured with this survey's poses.
  const ScratchDir tmp("cli_results_other_survey");
  hull::NullProgress quiet;
  hull::WriteSimulatedSurvey(hull::SimulateSurvey(hull::test::SmallSurveyOptions(8), quiet), tmp / "other");
  const CliRun r = Cli({"mosaic", Results(), "--bundle", tmp / "other", "--out", tmp / "mosaic", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, tmp / "other/survey.json")) << r.output;
  EXPECT_TRUE(Has(r, Results() + "/adjustment/adjustment.json")) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "mosaic"));
}

TEST_F(CliResults, CompareRefusesAMeshTheResultsWereNotMappedAgainst) {
  const ScratchDir tmp("cli_results_other_mesh");
  hull::SaveMesh(hull::test::MakeBox({0, 0, 0}, {1, 1, 1}), tmp / "box.ply");
  CliRun r = Cli({"compare", Results(), Results(), "--mesh", tmp / "box.ply", "--out", tmp / "change"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, tmp / "box.ply")) << r.output;
  EXPECT_TRUE(Has(r, Results() + "/mapping/model.ply")) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "change"));
  // With the right mesh (the one A names) the comparison runs.
  r = Cli({"compare", Results(), Results(), "--out", tmp / "change"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(ReadText(tmp / "change/.hullinspect-results.json").find("\"command\": \"compare\""), std::string::npos);
}

}  // namespace

// hullinspect-cli report (issue 24, part 2): the report of a pipeline's, a
// comparison's and a sonar run's results, each a results folder of its own.
// The command exists where the report library is built (not with
// -DHI_BUILD_GUI=OFF, as in the sanitizer build).
bool IsPdf(const std::string& path) { return fs::exists(path) && ReadText(path).rfind("%PDF-", 0) == 0; }
#ifdef HI_CLI_HAS_REPORT
#define SKIP_WITHOUT_REPORT()
#else
#define SKIP_WITHOUT_REPORT() GTEST_SKIP() << "hullinspect-cli built without its report command (HI_BUILD_GUI=OFF)"
#endif

TEST_F(CliResults, ReportOfPipelineComparisonAndSonarResults) {
  SKIP_WITHOUT_REPORT();
  const ScratchDir tmp("cli_results_report");
  CliRun r = Cli({"report", Results(), "--out", tmp / "hull", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(IsPdf(tmp / "hull/report.pdf"));
  const std::string html = ReadText(tmp / "hull/report.html");
  EXPECT_NE(html.find("What was not inspected"), std::string::npos);
  EXPECT_NE(ReadText(tmp / "hull/.hullinspect-results.json").find("\"command\": \"report\""), std::string::npos);
  // A pipeline's mapping/ alone stands for its pipeline.
  EXPECT_EQ(Cli({"report", Results() + "/mapping", "--out", tmp / "from-mapping", "--quiet"}).exit_code, 0);

  ASSERT_EQ(Cli({"compare", Results(), Results(), "--out", tmp / "change"}).exit_code, 0);
  r = Cli({"report", tmp / "change", "--out", tmp / "change-report", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(IsPdf(tmp / "change-report/report.pdf"));
  EXPECT_NE(ReadText(tmp / "change-report/report.html").find("Survey A (earlier)"), std::string::npos);

  const std::string seq = tmp / "prism";
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--images", "--out", seq, "--quiet"}).exit_code, 0);
  ASSERT_EQ(Cli({"sonar", seq, "--from-images", "--smoother", "--out", tmp / "sonar", "--quiet"}).exit_code, 0);
  r = Cli({"report", tmp / "sonar", "--out", tmp / "sonar-report", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(IsPdf(tmp / "sonar-report/report.pdf"));
  const std::string sonar = ReadText(tmp / "sonar-report/report.html");
  for (const char* section : {"Imaging-sonar report", "Consistency of the estimate", "Smoother", "Acoustic images",
                              "Evaluation against truth"}) {
    EXPECT_NE(sonar.find(section), std::string::npos) << section;
  }
  EXPECT_TRUE(fs::exists(tmp / "sonar-report/figures/sonar-plan.png"));
}

TEST_F(CliResults, ReportRefusesToReplaceItsResultsOrAUsersFolder) {
  SKIP_WITHOUT_REPORT();
  const ScratchDir tmp("cli_results_report_refused");
  const auto before = Files(Results());
  for (const std::string& out : {Results(), Results() + "/mapping", std::string(fs::path(Results()).parent_path())}) {
    const CliRun r = Cli({"report", Results(), "--out", out, "--quiet"});
    EXPECT_EQ(r.exit_code, 2) << out << ": " << r.output;
    EXPECT_TRUE(Has(r, "--out " + out)) << r.output;
  }
  EXPECT_EQ(Files(Results()), before);
  fs::create_directories(tmp / "mine");
  WriteText(tmp / "mine/notes.txt", "mine");
  CliRun r = Cli({"report", Results(), "--out", tmp / "mine", "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(ReadText(tmp / "mine/notes.txt"), "mine");
  r = Cli({"report", tmp / "nothing-here", "--out", tmp / "x", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, "nothing-here: no such results folder")) << r.output;
  r = Cli({"report", Bundle(), "--out", tmp / "x", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r, "holds no results a report can be written from")) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "x"));
}

TEST_F(CliResults, ReportKilledAtAnyRenameLeavesThePreviousReportWhole) {
  SKIP_WITHOUT_REPORT();
  const ScratchDir tmp("cli_results_kill_report");
  const std::string out = tmp / "report";
  ASSERT_EQ(Cli({"report", Results(), "--out", out, "--quiet"}).exit_code, 0);
  KillAtEveryRename(out, {"report", Results(), "--out", out, "--quiet"}, tmp / "renames");
}
