// The plugin registry with the fixture plugins (tests/plugins/fixture_*.cc):
// loading and refusing (another ABI version, no tag, not ELF, a second
// plugin of a name), the choice by score against the built-in readers, the
// host's checks of what an importer returns, options, exports and survey
// import, all through the functions the programs use (LoadMesh,
// ExportModel, OpenSurveyBundle).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "base/error.h"
#include "base/progress.h"
#include "geometry/mesh_io.h"
#include "pipeline/model_export.h"
#include "plugin/plugin_registry.h"
#include "plugin/plugin_tag.h"
#include "simulate/survey_simulator.h"
#include "support/test_files.h"
#include "support/test_meshes.h"
#include "survey/survey_import.h"

namespace hull {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::ScratchDir;
using testing::WriteText;

const char* kTetra =
    "HITRI\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 0 2 1\nf 0 1 3\nf 0 3 2\nf 1 2 3\n";

const plugin::PluginRecord* Record(const std::string& name) {
  for (const auto& r : plugin::Registry::Global().Records()) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

class PluginRegistry : public ::testing::Test {
 protected:
  // The fixtures load into the programs' registry once, as the programs
  // load theirs: LoadMesh and the others consult Global().
  static void SetUpTestSuite() {
    marker_ = new ScratchDir("plugin_marker");
    setenv("HI_WRONG_ABI_MARKER", (*marker_ / "loaded").c_str(), 1);
    WriteText(*marker_ / "fake.so", "not a shared object\n");
    plugin::Registry::Global().LoadFolder(HI_PLUGIN_FIXTURE_DIR);
    plugin::Registry::Global().LoadFile(*marker_ / "fake.so");
  }
  static void TearDownTestSuite() {
    delete marker_;
    marker_ = nullptr;
  }
  void TearDown() override { plugin::Registry::Global().SetOption("fixture", "scale", "1"); }

  static ScratchDir* marker_;
  ScratchDir tmp_{"plugin_registry"};
};
ScratchDir* PluginRegistry::marker_ = nullptr;

TEST_F(PluginRegistry, LoadsTheFixtureAndRefusesWhatIsNoPluginForThisVersion) {
  const plugin::PluginRecord* fixture = Record("fixture");
  ASSERT_NE(fixture, nullptr);
  EXPECT_TRUE(fixture->loaded) << fixture->refused;

  const plugin::PluginRecord* old = Record("old-abi");
  ASSERT_NE(old, nullptr);
  EXPECT_FALSE(old->loaded);
  EXPECT_EQ(old->abi, 999);
  EXPECT_THAT(old->refused, HasSubstr("built for plugin ABI version 999"));
  EXPECT_THAT(old->refused, HasSubstr("loads version " + std::to_string(plugin::kAbiVersion) + " only"));
  // Never loaded: its constructor would have left the marker.
  EXPECT_FALSE(fs::exists(*marker_ / "loaded"));

  const plugin::PluginRecord* not_plugin = Record("not-a-plugin.so");
  ASSERT_NE(not_plugin, nullptr);
  EXPECT_THAT(not_plugin->refused, HasSubstr("no .hullinspect_plugin section"));
  const plugin::PluginRecord* fake = Record("fake.so");
  ASSERT_NE(fake, nullptr);
  EXPECT_THAT(fake->refused, HasSubstr("not an ELF shared object"));

  // A second plugin of a loaded name (the user's copy shadows the installed one).
  const plugin::PluginRecord& again =
      plugin::Registry::Global().LoadFile(std::string(HI_PLUGIN_FIXTURE_DIR) + "/fixture.so");
  EXPECT_FALSE(again.loaded);
  EXPECT_THAT(again.refused, HasSubstr("a plugin named 'fixture' is already loaded from"));
}

TEST_F(PluginRegistry, TagsAreParsedStrictly) {
  plugin::PluginTag tag;
  std::string why;
  EXPECT_TRUE(plugin::ParsePluginTag("HULLINSPECT_PLUGIN abi=12 name=step-iges", &tag, &why)) << why;
  EXPECT_EQ(tag.abi, 12);
  EXPECT_EQ(tag.name, "step-iges");
  for (const char* bad : {"", "HULLINSPECT_PLUGIN", "HULLINSPECT_PLUGIN abi= name=x", "HULLINSPECT_PLUGIN abi=1",
                          "HULLINSPECT_PLUGIN abi=1 name=", "HULLINSPECT_PLUGIN abi=1 name=a b",
                          "HULLINSPECT_PLUGIN abi=99999999 name=x", "OTHER abi=1 name=x"}) {
    EXPECT_FALSE(plugin::ParsePluginTag(bad, &tag, &why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
}

TEST_F(PluginRegistry, LoadMeshUsesAnImporterThatOutbidsTheBuiltInReaders) {
  const std::string tri = tmp_ / "tetra.hitri";
  WriteText(tri, kTetra);
  EXPECT_TRUE(IsMeshFile(tri));
  std::vector<std::pair<std::string, std::string>> report;
  MeshLoadOptions lo;
  lo.import_report = &report;
  const TriangleMesh m = LoadMesh(tri, lo);
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.num_faces(), 4u);
  EXPECT_NEAR(m.SignedVolume(), 1.0 / 6.0, 1e-12);
  ASSERT_NE(m.FindScalar("height"), nullptr);
  EXPECT_EQ((*m.FindScalar("height"))[3], 1.0);
  EXPECT_THAT(report, ::testing::Contains(std::make_pair(std::string("unit"), std::string("toy units x 1"))));

  // An STL: the fixture bids below the built-in reader, which reads it.
  const std::string stl = tmp_ / "box.stl";
  SaveMesh(test::MakeBox({0, 0, 0}, {1, 2, 3}), stl);
  report.clear();
  EXPECT_NEAR(LoadMesh(stl, lo).SignedVolume(), 6.0, 1e-9);
  EXPECT_TRUE(report.empty());
  // Toy content under an .stl name: recognised by content, the fixture wins.
  const std::string disguised = tmp_ / "disguised.stl";
  WriteText(disguised, kTetra);
  EXPECT_EQ(LoadMesh(disguised, lo).num_faces(), 4u);
  EXPECT_FALSE(report.empty());

  // Options reach the importer.
  plugin::Registry::Global().SetOption("fixture.scale=2");
  EXPECT_NEAR(LoadMesh(tri).SignedVolume(), 8.0 / 6.0, 1e-12);
}

TEST_F(PluginRegistry, ImporterErrorsAndBrokenMeshesAreInputErrorsNamingFileAndPlugin) {
  const std::string bad = tmp_ / "bad.hitri";
  WriteText(bad, "HITRI\nv 0 0 0\nv 1 x 0\n");
  try {
    LoadMesh(bad);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, bad);
    EXPECT_THAT(e.what(), HasSubstr("toy triangles (plugin fixture): line 3: expected x y z"));
  }
  const std::string broken = tmp_ / "x.hibad";
  WriteText(broken, "anything");
  try {
    LoadMesh(broken);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, broken);
    EXPECT_EQ(e.where().field, "triangle 0");
    EXPECT_THAT(e.what(), HasSubstr("vertex index 7 out of range"));
  }
  // No file: the built-in reader names it, as without plugins.
  EXPECT_THROW(LoadMesh(tmp_ / "absent.hitri"), InputError);
}

TEST_F(PluginRegistry, OptionsAreCheckedAndTakenFromTheCommandLine) {
  auto& registry = plugin::Registry::Global();
  auto field_of = [&](const std::string& assignment) {
    try {
      registry.SetOption(assignment);
    } catch (const OptionError& e) {
      return e.field() + ": " + e.what();
    }
    return std::string("accepted");
  };
  EXPECT_THAT(field_of("fixture.scale=abc"), HasSubstr("fixture.scale"));
  EXPECT_THAT(field_of("fixture.scale=0"), HasSubstr("expected a number from"));
  EXPECT_THAT(field_of("fixture.nope=1"), HasSubstr("it has scale, label"));
  EXPECT_THAT(field_of("nosuch.scale=1"), HasSubstr("no plugin named 'nosuch'"));
  EXPECT_THAT(field_of("scale=1"), HasSubstr("expected <plugin>.<key>=<value>"));
  EXPECT_EQ(field_of("fixture.label=any text"), "accepted");

  const std::vector<std::string> rest = plugin::TakePluginOptions(
      {"info", "--plugin-option", "fixture.scale=3", "x.hitri", "--plugin-option=fixture.label=y"}, registry);
  EXPECT_EQ(rest, (std::vector<std::string>{"info", "x.hitri"}));
  EXPECT_EQ(registry.Plugins().front()->settings.at("scale"), "3");
  EXPECT_THROW(plugin::TakePluginOptions({"--plugin-option"}, registry), OptionError);
}

TEST_F(PluginRegistry, ExportModelWritesPluginFormatsByExtension) {
  TriangleMesh model = test::MakeBox({0, 0, 0}, {1, 1, 1});
  model.SetScalar("deviation", std::vector<double>(model.num_vertices(), 0.01));
  const auto formats = ModelExportExtensions();
  EXPECT_THAT(formats, ::testing::IsSupersetOf({".ply", ".obj", ".stl", ".hisum"}));
  const std::string target = tmp_ / "model.hisum";
  const auto report = ExportModel(model, "/results/here", target);
  EXPECT_EQ(testing::ReadText(target), "vertices 8\ntriangles 12\nresults /results/here\n");
  EXPECT_EQ(report.size(), 1u);
  EXPECT_TRUE(ExportModel(model, "", tmp_ / "model.ply").empty());  // built in
  EXPECT_THROW(ExportModel(model, "", tmp_ / "model.xyz"), std::invalid_argument);
}

TEST_F(PluginRegistry, OpenSurveyBundleConvertsWhatASurveyImporterReads) {
  setenv("XDG_CACHE_HOME", (tmp_ / "cache").c_str(), 1);
  SurveySimulationOptions o = SurveyPreset("demo");
  NullProgress progress;
  WriteSimulatedSurvey(SimulateSurvey(o, progress), tmp_ / "bundle");
  const std::string log = tmp_ / "survey.hisurvey";
  WriteText(log, "bundle " + (tmp_ / "bundle") + "\n");
  EXPECT_TRUE(IsSurveyPath(log));
  std::vector<std::pair<std::string, std::string>> report;
  const SurveyBundle converted = OpenSurveyBundle(log, &report);
  const SurveyBundle original = OpenSurveyBundle(tmp_ / "bundle");
  EXPECT_EQ(converted.nav.size(), original.nav.size());
  EXPECT_EQ(converted.features.size(), original.features.size());
  EXPECT_THAT(converted.directory, HasSubstr(tmp_ / "cache/hullinspect/imported/survey.hisurvey-"));
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].first, "copied from");

  // Nothing reads it: the message says so; a failed conversion leaves nothing.
  WriteText(tmp_ / "other.txt", "text");
  EXPECT_FALSE(IsSurveyPath(tmp_ / "other.txt"));
  EXPECT_THROW(OpenSurveyBundle(tmp_ / "other.txt"), InputError);
  WriteText(log, "bundle " + (tmp_ / "missing") + "\n");
  EXPECT_THROW(OpenSurveyBundle(log), InputError);
  EXPECT_FALSE(fs::exists(converted.directory + ".partial"));
  unsetenv("XDG_CACHE_HOME");
}

}  // namespace
}  // namespace hull
