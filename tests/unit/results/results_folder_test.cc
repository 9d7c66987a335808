// A results folder of ours: its manifest lists every file a run wrote and the
// run; --out must be absent, empty or ours (else refused unless forced);
// the user's files are never deleted or overwritten; readers refuse a folder
// that mixes files of different runs (issue 23, part 2).
#include "results/results_folder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "base/error.h"
#include "base/file_io.h"
#include "results/file_hash.h"
#include "support/test_files.h"

namespace hull {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::ScratchDir;

// A text file, its folders made as needed.
void WriteText(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  testing::WriteText(path, text);
}

// Every file under dir (relative path -> contents), the manifest left out.
std::map<std::string, std::string> Files(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file() || name == ResultsManifest::kFileName) continue;
    out[fs::relative(e.path(), dir).generic_string()] = ReadText(e.path().string());
  }
  return out;
}

// A run writing `files` (relative path -> text).
void Write(const std::string& out, const std::map<std::string, std::string>& files, bool force = false,
           const std::string& command = "test") {
  WriteResultsFolder({out, force}, NewResultsRun(command), [&](const std::string& tmp) {
    for (const auto& [rel, text] : files) WriteText((fs::path(tmp) / rel).string(), text);
  });
}

TEST(ResultsFolder, TheManifestListsEveryFileAndTheRun) {
  const ScratchDir tmp("results_manifest");
  const std::string out = tmp / "R";
  WriteText(tmp / "survey.json", "{}");
  ResultsRun run = NewResultsRun("adjust");
  run.AddFile("mesh", tmp / "survey.json");
  WriteResultsFolder({out, false}, run, [&](const std::string& t) {
    WriteText(t + "/a.json", "A");
    WriteText(t + "/sub/b.csv", "BB");
  });
  const auto m = ReadResultsManifest(out);
  ASSERT_TRUE(m);
  EXPECT_FALSE(m->legacy);
  EXPECT_EQ(m->run.id, run.id);
  EXPECT_EQ(m->run.command, "adjust");
  EXPECT_EQ(m->run.program.rfind("HullInspect ", 0), 0u) << m->run.program;
  ASSERT_NE(m->run.Input("mesh"), nullptr);
  EXPECT_EQ(m->run.Input("mesh")->hash, FileHash(tmp / "survey.json"));
  ASSERT_EQ(m->files.size(), 2u);
  EXPECT_EQ(m->files[0].path, "a.json");
  EXPECT_EQ(m->files[0].bytes, 1u);
  EXPECT_EQ(m->files[0].hash, HashText("A"));
  EXPECT_EQ(m->files[1].path, "sub/b.csv");
  EXPECT_EQ(ClassifyOutputFolder(out), OutputFolderState::kOurs);
  // Two runs have two ids.
  EXPECT_NE(NewResultsRun("x").id, NewResultsRun("x").id);
}

TEST(ResultsFolder, OurFilesAreReplacedTheUsersKeptEvenInsideOurFolders) {
  // A photo the user put into our mapping/ and notes beside the results: a
  // new run keeps both and drops the previous run's files it does not write.
  const ScratchDir tmp("results_keep");
  const std::string out = tmp / "R";
  Write(out, {{"summary.json", "run 1"}, {"mapping/model.ply", "run 1"}, {"old.csv", "run 1"}});
  WriteText(out + "/mapping/photo.jpg", "user photo");
  WriteText(out + "/notes.txt", "user note");
  fs::create_directories(out + "/empty-user-folder");
  Write(out, {{"summary.json", "run 2"}, {"mapping/model.ply", "run 2"}});
  const std::map<std::string, std::string> expect = {{"summary.json", "run 2"},
                                                     {"mapping/model.ply", "run 2"},
                                                     {"mapping/photo.jpg", "user photo"},
                                                     {"notes.txt", "user note"}};
  EXPECT_EQ(Files(out), expect);
  EXPECT_TRUE(fs::is_directory(out + "/empty-user-folder"));
  // The manifest lists this run's files only.
  const auto m = ReadResultsManifest(out);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->files.size(), 2u);
  EXPECT_EQ(m->Find("mapping/photo.jpg"), nullptr);
}

TEST(ResultsFolder, ResultsOfOursNestedInOursAreDroppedWithThem) {
  // 'map' wrote R/mapping from R's adjustment; a new adjustment into R makes
  // it stale: it goes with the folder it was made from.
  const ScratchDir tmp("results_nested");
  const std::string out = tmp / "R";
  Write(out, {{"adjustment.json", "adjust 1"}}, false, "adjust");
  Write(out + "/mapping", {{"model.ply", "map of adjust 1"}}, false, "map");
  Write(out, {{"adjustment.json", "adjust 2"}}, false, "adjust");
  EXPECT_EQ(Files(out), (std::map<std::string, std::string>{{"adjustment.json", "adjust 2"}}));
}

TEST(ResultsFolder, AFolderOfTheUsersIsRefusedBeforeAnyWork) {
  // The issue's repro: U/mapping/photo.jpg; `run --out U` deleted it.
  const ScratchDir tmp("results_foreign");
  const std::string out = tmp / "U";
  WriteText(out + "/mapping/photo.jpg", "photo");
  EXPECT_EQ(ClassifyOutputFolder(out), OutputFolderState::kForeign);
  try {
    CheckResultsFolder({out, false});
    FAIL() << "a folder of the user's was accepted";
  } catch (const OutputFolderRefused& e) {
    EXPECT_NE(std::string(e.what()).find("--out " + out + ": "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mapping/"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--force"), std::string::npos) << e.what();
  }
  bool wrote = false;
  EXPECT_THROW(WriteResultsFolder({out, false}, NewResultsRun("run"), [&](const std::string&) { wrote = true; }),
               OutputFolderRefused);
  EXPECT_FALSE(wrote);
  EXPECT_EQ(Files(out), (std::map<std::string, std::string>{{"mapping/photo.jpg", "photo"}}));
  // Absent and empty folders are fine.
  fs::create_directories(tmp / "empty");
  EXPECT_EQ(ClassifyOutputFolder(tmp / "empty"), OutputFolderState::kEmpty);
  EXPECT_EQ(ClassifyOutputFolder(tmp / "absent"), OutputFolderState::kAbsent);
  EXPECT_NO_THROW(CheckResultsFolder({tmp / "empty", false}));
  EXPECT_NO_THROW(CheckResultsFolder({tmp / "absent", false}));
}

TEST(ResultsFolder, ForcedTheUsersFilesAreKeptAndNoneIsReplaced) {
  const ScratchDir tmp("results_force");
  const std::string out = tmp / "U";
  WriteText(out + "/mapping/photo.jpg", "photo");
  WriteText(out + "/landmarks.csv", "the user's own landmarks");
  Write(out, {{"mapping/model.ply", "ours"}}, true);
  EXPECT_EQ(Files(out), (std::map<std::string, std::string>{{"mapping/model.ply", "ours"},
                                                            {"mapping/photo.jpg", "photo"},
                                                            {"landmarks.csv", "the user's own landmarks"}}));
  // A run that writes a file of the user's name stops before the swap,
  // naming it: nothing changes.
  const auto before = Files(out);
  try {
    Write(out, {{"mapping/model.ply", "ours 2"}, {"landmarks.csv", "ours"}}, true);
    FAIL() << "the user's landmarks.csv was replaced";
  } catch (const OutputFolderRefused& e) {
    EXPECT_NE(std::string(e.what()).find("landmarks.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not replaced"), std::string::npos) << e.what();
  }
  EXPECT_EQ(Files(out), before);
  int siblings = 0;
  for (const auto& e : fs::directory_iterator(tmp.path())) siblings += e.path().filename() != "U";
  EXPECT_EQ(siblings, 0);
}

TEST(ResultsFolder, AFileAsOutAndAMissingParentAreRefused) {
  const ScratchDir tmp("results_out_checks");
  WriteText(tmp / "a-file", "x");
  EXPECT_THROW(CheckResultsFolder({tmp / "a-file", true}), OutputFolderRefused);
  try {
    CheckResultsFolder({tmp / "no/such/out", false});
    FAIL();
  } catch (const OutputFolderRefused& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST(ResultsFolder, AnOlderFoldersListIsOurs) {
  // Folders written before the manifest listed their top-level names in
  // .hullinspect-results: they are ours, and those entries are replaced.
  const ScratchDir tmp("results_legacy");
  const std::string out = tmp / "R";
  WriteText(out + "/summary.json", "old");
  WriteText(out + "/mapping/model.ply", "old");
  WriteText(out + "/notes.txt", "user");
  WriteText(out + "/" + ResultsManifest::kLegacyFileName, "summary.json\nmapping\n");
  EXPECT_EQ(ClassifyOutputFolder(out), OutputFolderState::kOurs);
  Write(out, {{"summary.json", "new"}});
  EXPECT_EQ(Files(out), (std::map<std::string, std::string>{{"summary.json", "new"}, {"notes.txt", "user"}}));
  EXPECT_FALSE(fs::exists(out + "/" + ResultsManifest::kLegacyFileName));
}

TEST(ResultsFolder, ReadersRefuseAFolderThatMixesRuns) {
  const ScratchDir tmp("results_mixed");
  const std::string r = tmp / "R";
  Write(r, {{"a.json", "A"}, {"b.csv", "B"}});
  // As written: one run, returned.
  const auto m = CheckResultsFiles({r + "/a.json", r + "/b.csv"}, "the test's results");
  ASSERT_TRUE(m);
  // A file changed since (copied in from another run).
  WriteText(r + "/b.csv", "B of another run");
  try {
    CheckResultsFiles({r + "/a.json", r + "/b.csv"}, "the test's results");
    FAIL() << "a changed file was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, r + "/b.csv");
    EXPECT_NE(e.detail().find("has changed since run " + m->run.id), std::string::npos) << e.what();
  }
  // A file no run listed, beside listed ones.
  Write(r, {{"a.json", "A"}});
  WriteText(r + "/b.csv", "B by hand");
  try {
    CheckResultsFiles({r + "/a.json", r + "/b.csv"}, "the test's results");
    FAIL() << "an unlisted file was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, r + "/b.csv");
    EXPECT_NE(e.detail().find("is not listed in"), std::string::npos) << e.what();
  }
  // Files of two runs (a nested folder of another run read as one set).
  Write(r + "/sub", {{"c.json", "C"}});
  EXPECT_THROW(CheckResultsFiles({r + "/a.json", r + "/sub/c.json"}, "the test's results"), InputError);
  // Results without a manifest (older, or made by hand) are read as they are.
  WriteText(tmp / "plain/a.json", "A");
  EXPECT_FALSE(CheckResultsFiles({tmp / "plain/a.json"}, "plain results"));
}

TEST(ResultsFolder, AManifestDoesNotClaimFoldersItDidNotWrite) {
  // With --force into a folder of the user's, the user's own results-like
  // files in their own subfolders are not ours: read as they are.
  const ScratchDir tmp("results_unclaimed");
  const std::string u = tmp / "U";
  WriteText(u + "/mine/adjustment.json", "the user's");
  Write(u, {{"summary.json", "ours"}}, true);
  EXPECT_FALSE(ManifestOf(u + "/mine/adjustment.json"));
  EXPECT_FALSE(CheckResultsFiles({u + "/mine/adjustment.json"}, "the user's"));
  ASSERT_TRUE(ManifestOf(u + "/summary.json"));
}

TEST(ResultsFolder, SurveyFingerprintsSeeTheSurveyNotItsFeatures) {
  const ScratchDir tmp("results_survey_hash");
  WriteText(tmp / "b/survey.json", "{\"format\": \"hull-survey\"}");
  WriteText(tmp / "b/nav.csv", "keyframe,t\n1,0\n");
  const std::string h = SurveyHash(tmp / "b");
  WriteText(tmp / "b/features.csv", "landmark,keyframe\n");
  EXPECT_EQ(SurveyHash(tmp / "b"), h);
  WriteText(tmp / "b/nav.csv", "keyframe,t\n1,0.5\n");
  EXPECT_NE(SurveyHash(tmp / "b"), h);
}

}  // namespace
}  // namespace hull
