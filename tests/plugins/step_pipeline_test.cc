// STEP hull in, same pipeline out: hullinspect-cli, as a user runs it, with
// the plugins of the build's plugin folder. A lofted hull written as STEP by
// OpenCASCADE is surveyed (simulate --mesh), the whole pipeline runs on the
// STEP file itself (run --mesh), and the remeshed model is exported as glTF.
// Also `plugins` listing what loaded and what was refused, and why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cad_shapes.h"
#include "support/cli_run.h"
#include "support/test_files.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using hull::testing::CliRun;

CliRun Cli(const std::vector<std::string>& args) { return hull::testing::RunProgram(HI_CLI_PATH, args); }

TEST(StepPipeline, AStepHullRunsThroughTheWholePipeline) {
  const hull::testing::ScratchDir tmp("step_pipeline");
  const std::string step = tmp / "hull.step";
  hull::test::WriteCadShape(hull::test::CadShape::kHull, {40000, 8000, 4000}, step);  // mm: 40 x 8 x 4 m

  CliRun r = Cli({"info", step});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("file unit       millimetre, converted to metres"));
  EXPECT_THAT(r.output, HasSubstr("surfaces        4"));
  EXPECT_THAT(r.output, HasSubstr("closed          yes"));

  r = Cli({"simulate", "--preset", "demo", "--mesh", step, "--out", tmp / "survey", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"run", tmp / "survey", "--mesh", step, "--out", tmp / "results", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(tmp / "results/mapping/model.ply"));
  EXPECT_THAT(hull::testing::ReadText(tmp / "results/summary.json"), HasSubstr("hull.step"));

  r = Cli({"export", tmp / "results", "--out", tmp / "hull.glb"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("deviation as vertex colour"));
  EXPECT_GT(fs::file_size(tmp / "hull.glb"), 1000u);
  r = Cli({"export", tmp / "results", "--out", tmp / "hull.xyz"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("the formats are .ply .obj .stl .glb .gltf"));

  // A chord tolerance out of range is a bad command line naming the option.
  r = Cli({"info", step, "--plugin-option", "step-iges.chord-tolerance=0"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("step-iges.chord-tolerance"));
}

TEST(StepPipeline, PluginsListsWhatLoadedAndWhatWasRefusedAndWhy) {
  setenv("HULLINSPECT_PLUGIN_PATH", HI_PLUGIN_FIXTURE_DIR, 1);
  const CliRun r = Cli({"plugins"});
  unsetenv("HULLINSPECT_PLUGIN_PATH");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("plugin ABI version 1"));
  EXPECT_THAT(r.output, HasSubstr("  step-iges "));
  EXPECT_THAT(r.output, HasSubstr("mesh importer   STEP (OpenCASCADE)  [.step .stp]"));
  EXPECT_THAT(r.output, HasSubstr("option          step-iges.chord-tolerance = 0.005"));
  EXPECT_THAT(r.output, HasSubstr("exporter        glTF 2.0 (assimp)  [.glb .gltf]"));
  EXPECT_THAT(r.output, HasSubstr("  fixture 1.2.3  " + std::string(HI_PLUGIN_FIXTURE_DIR) + "/fixture.so"));
  EXPECT_THAT(r.output, HasSubstr("refused (2):"));
  EXPECT_THAT(r.output, HasSubstr("built for plugin ABI version 999, but this HullInspect loads version 1 only"));
  EXPECT_THAT(r.output, HasSubstr("not a HullInspect plugin"));

  const CliRun version = Cli({"--version"});
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_THAT(version.output, HasSubstr("hullinspect-cli 0.1.0 (plugin ABI 1)"));
}

}  // namespace
