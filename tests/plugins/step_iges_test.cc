// The step-iges plugin as the programs use it: STEP and IGES files made by
// OpenCASCADE in the test (a box, a lofted hull) read back through LoadMesh
// with the plugin loaded from the build's plugin folder; bounds, area and
// volume against the exact B-rep's, the file's unit kept, the chord
// tolerance honoured, a bad file named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "base/error.h"
#include "cad_shapes.h"
#include "geometry/mesh_io.h"
#include "plugin/plugin_registry.h"
#include "support/test_files.h"

namespace hull {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

std::map<std::string, std::string> AsMap(const std::vector<std::pair<std::string, std::string>>& report) {
  return {report.begin(), report.end()};
}

class StepIges : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto& record =
        plugin::Registry::Global().LoadFile(std::string(HI_BINARY_DIR) + "/lib/hullinspect/plugins/step-iges.so");
    ASSERT_TRUE(record.loaded) << record.refused;
  }
  void TearDown() override { plugin::Registry::Global().SetOption("step-iges.chord-tolerance=0.005"); }

  // LoadMesh as the programs call it, with the importer's report.
  TriangleMesh Load(const std::string& path, std::map<std::string, std::string>* report = nullptr) {
    std::vector<std::pair<std::string, std::string>> r;
    MeshLoadOptions lo;
    lo.import_report = &r;
    lo.orientation = &orientation_;
    TriangleMesh m = LoadMesh(path, lo);
    if (report) *report = AsMap(r);
    return m;
  }

  ScratchDir tmp_{"step_iges"};
  OrientationReport orientation_;
};

TEST_F(StepIges, BoxFromStepInMillimetresArrivesInMetres) {
  const std::string step = tmp_ / "box.step";
  test::WriteCadShape(test::CadShape::kBox, {4000, 2000, 1000}, step);
  std::map<std::string, std::string> report;
  const TriangleMesh m = Load(step, &report);
  EXPECT_TRUE(orientation_.closed);
  EXPECT_EQ(orientation_.faces_flipped, 0);  // OpenCASCADE's face orientation kept the winding outward
  EXPECT_EQ(m.num_vertices(), 8u);
  EXPECT_EQ(m.num_faces(), 12u);
  EXPECT_NEAR(m.SignedVolume(), 8.0, 1e-9);
  EXPECT_NEAR(m.SurfaceArea(), 28.0, 1e-9);
  EXPECT_TRUE(m.Bounds().min().isZero(1e-6));
  EXPECT_TRUE(m.Bounds().max().isApprox(Eigen::Vector3d(4, 2, 1), 1e-6));
  EXPECT_EQ(report["format"], "STEP");
  EXPECT_THAT(report["file unit"], HasSubstr("millimetre"));
  EXPECT_EQ(report["surfaces"], "6");
  EXPECT_EQ(report["solids"], "1");
  EXPECT_THAT(report["tessellation"], HasSubstr("12 triangles at chord tolerance 0.005 m"));
}

TEST_F(StepIges, TheFilesUnitIsKept) {
  // The same numbers declared in metres: a box a thousand times larger.
  const std::string mm = tmp_ / "small.stp";
  test::WriteCadShape(test::CadShape::kBox, {4, 2, 1}, mm);
  EXPECT_TRUE(Load(mm).Bounds().max().isApprox(Eigen::Vector3d(0.004, 0.002, 0.001), 1e-6));
  std::string text = testing::ReadText(mm);
  const std::string milli = "SI_UNIT(.MILLI.,.METRE.)";
  ASSERT_NE(text.find(milli), std::string::npos);
  text.replace(text.find(milli), milli.size(), "SI_UNIT($,.METRE.)");
  const std::string metres = tmp_ / "metres.stp";
  testing::WriteText(metres, text);
  std::map<std::string, std::string> report;
  EXPECT_TRUE(Load(metres, &report).Bounds().max().isApprox(Eigen::Vector3d(4, 2, 1), 1e-6));
  EXPECT_THAT(report["file unit"], HasSubstr("metre"));
  EXPECT_THAT(report["file unit"], ::testing::Not(HasSubstr("millimetre")));

  // IGES in metres and in inches: the same 4 x 2 x 1 m box.
  for (const auto& [unit, name] : {std::pair<std::string, std::string>{"M", "M"}, {"IN", "INCH"}}) {
    const std::string iges = tmp_ / ("box_" + unit + ".igs");
    test::WriteCadShape(test::CadShape::kBox, {4000, 2000, 1000}, iges, unit);
    const TriangleMesh m = Load(iges, &report);
    EXPECT_TRUE(m.Bounds().max().isApprox(Eigen::Vector3d(4, 2, 1), 1e-6)) << unit << ": " << m.Bounds().max();
    EXPECT_NEAR(m.SignedVolume(), 8.0, 1e-6) << unit;
    EXPECT_EQ(report["format"], "IGES");
    EXPECT_EQ(report["file unit"], name + ", converted to metres");
  }
}

TEST_F(StepIges, LoftedHullMatchesTheExactSolidWithinTheChordTolerance) {
  const Eigen::Vector3d size(20000, 4000, 2000);  // mm: a 20 m hull
  for (const char* name : {"hull.step", "hull.iges"}) {
    const test::CadFacts exact = test::WriteCadShape(test::CadShape::kHull, size, tmp_ / name);
    std::map<std::string, std::string> report;
    const TriangleMesh m = Load(tmp_ / name, &report);
    SCOPED_TRACE(name);
    EXPECT_TRUE(orientation_.closed) << orientation_.boundary_edges << " boundary edges";
    EXPECT_EQ(orientation_.non_manifold_edges, 0);
    EXPECT_EQ(orientation_.components, 1);
    // Exact: B-spline surfaces and planar caps, in mm^3 / mm^2.
    const double volume = exact.volume * 1e-9, area = exact.area * 1e-6;
    // Every vertex lies on the surface and chords cut inside: the mesh is a
    // little smaller; at most the chord tolerance (5 mm) times the area.
    EXPECT_LT(m.SignedVolume(), volume);
    EXPECT_GT(m.SignedVolume(), volume - 0.005 * area);
    EXPECT_NEAR(m.SurfaceArea(), area, 0.002 * area);
    EXPECT_TRUE(m.Bounds().min().isApprox(exact.bounds.min() * 1e-3, 1e-3)) << m.Bounds().min();
    EXPECT_TRUE(m.Bounds().max().isApprox(exact.bounds.max() * 1e-3, 1e-3)) << m.Bounds().max();
    EXPECT_EQ(report["surfaces"], "4");  // the lofted side, the deck, two end caps
  }
}

TEST_F(StepIges, AFinerChordToleranceGivesMoreTrianglesAndASmallerError) {
  const std::string step = tmp_ / "hull.stp";
  const test::CadFacts exact = test::WriteCadShape(test::CadShape::kHull, {20000, 4000, 2000}, step);
  const double volume = exact.volume * 1e-9;
  plugin::Registry::Global().SetOption("step-iges.chord-tolerance=0.05");
  std::map<std::string, std::string> report;
  const TriangleMesh coarse = Load(step, &report);
  EXPECT_THAT(report["tessellation"], HasSubstr("chord tolerance 0.05 m"));
  plugin::Registry::Global().SetOption("step-iges.chord-tolerance=0.005");
  const TriangleMesh fine = Load(step);
  EXPECT_GT(fine.num_faces(), 2 * coarse.num_faces());
  EXPECT_LT(volume - fine.SignedVolume(), 0.5 * (volume - coarse.SignedVolume()));
}

TEST_F(StepIges, ABadFileIsAnInputErrorNamingItAndThePlugin) {
  const std::string bad = tmp_ / "bad.step";
  testing::WriteText(bad, "ISO-10303-21;\nHEADER;\nthis is not STEP\n");
  try {
    LoadMesh(bad);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, bad);
    EXPECT_THAT(e.what(), HasSubstr("STEP (OpenCASCADE) (plugin step-iges): not a readable STEP file"));
    EXPECT_THAT(e.what(), HasSubstr("(OpenCASCADE: "));  // its reason, with the line
    EXPECT_THAT(e.what(), HasSubstr("Line 4"));
  }
  const std::string empty = tmp_ / "empty.igs";
  testing::WriteText(empty, "\n");
  EXPECT_THROW(LoadMesh(empty), InputError);
}

}  // namespace
}  // namespace hull
