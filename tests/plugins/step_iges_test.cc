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
#include "step_iges/step_references.h"
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
  void TearDown() override {
    plugin::Registry::Global().SetOption("step-iges.chord-tolerance=0.005");
    plugin::Registry::Global().SetOption("step-iges.sewing-tolerance=0.001");
  }

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

TEST_F(StepIges, UnsewnSurfacePatchesAreSewnIntoAClosedMesh) {
  const std::string step = tmp_ / "patches.step";
  const test::CadFacts exact = test::WriteCadShape(test::CadShape::kHullPatches, {20000, 4000, 2000}, step);
  std::map<std::string, std::string> report;
  plugin::Registry::Global().SetOption("step-iges.sewing-tolerance=0");
  Load(step, &report);
  EXPECT_FALSE(orientation_.closed);  // holes along every patch border
  EXPECT_GT(orientation_.boundary_edges, 100);
  EXPECT_THAT(report["free edges"], ::testing::Not(HasSubstr("sewing")));
  EXPECT_GT(std::stoi(report["free edges"]), 0);

  plugin::Registry::Global().SetOption("step-iges.sewing-tolerance=0.001");
  const TriangleMesh m = Load(step, &report);
  EXPECT_TRUE(orientation_.closed) << orientation_.boundary_edges << " boundary edges";
  EXPECT_EQ(orientation_.components, 1);
  EXPECT_THAT(report["free edges"], HasSubstr(", 0 after sewing at 0.001 m"));
  EXPECT_NEAR(m.SignedVolume(), exact.volume * 1e-9, 0.005 * exact.area * 1e-6);
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

// The message LoadMesh refuses a fuzzing finding with (the checked-in input
// tests/fuzz/regressions/mesh_step/<name>), the error naming the file.
std::string RefusalOfFinding(const ScratchDir& tmp, const std::string& name) {
  const std::string path = tmp / name;
  testing::WriteText(path, testing::ReadText(std::string(HI_SOURCE_DIR) + "/tests/fuzz/regressions/mesh_step/" + name));
  try {
    LoadMesh(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path);
    return e.what();
  }
  ADD_FAILURE() << name << " was read";
  return {};
}

// Found by fuzzing (tests/fuzz, docs/reliability.md): an entity whose
// parameters do not parse ("#89 = VECTOR('' <garbage>;") was kept by
// OpenCASCADE with a null direction, and translating the shape crashed
// inside OpenCASCADE (SEGV in StepGeom_Direction::NbDirectionRatios). The
// plugin now refuses a file with load failures before translating it.
TEST_F(StepIges, AnEntityThatFailedToLoadIsRefusedBeforeTranslation) {
  const std::string message = RefusalOfFinding(tmp_, "vector-without-direction.step");
  EXPECT_THAT(message, HasSubstr("malformed STEP file: "));
  EXPECT_THAT(message, HasSubstr("entities failed to load"));
}

// Found by fuzzing: "#77 = ORIENTED_EDGE('',*,*,#77,.T.)", an oriented edge
// of itself. OpenCASCADE's reader checks an edge loop while it loads the
// file and follows the edge's start through its edge element, forever: a
// stack overflow inside OpenCASCADE. The plugin now reads the references
// from the text first and refuses a cycle, naming its line.
TEST_F(StepIges, AReferenceCycleIsRefusedBeforeOpenCascadeFollowsIt) {
  EXPECT_THAT(RefusalOfFinding(tmp_, "oriented-edge-of-itself.step"),
              HasSubstr("malformed STEP file, line 97: entity #77 refers to itself (#77 -> #77)"));
}

TEST(StepReferences, CyclesAreFoundThroughStringsCommentsAndComplexInstances) {
  using step_iges::FindReferenceCycle;
  const std::string header = "ISO-10303-21;\nHEADER;\nFILE_NAME('a;#1=b','',('x'),(''),'','','');\nENDSEC;\nDATA;\n";
  // Acyclic: references inside strings and comments are not references.
  const std::string dag = header +
                          "#1 = A('#2', #2, (#3, #3));\n"
                          "/* #3 = B(#1); */\n"
                          "#2 = ( C(#3) D('it''s #1;') );\n"
                          "#3 = E(#99, .T., 'x');\nENDSEC;\nEND-ISO-10303-21;\n";
  EXPECT_TRUE(FindReferenceCycle(dag).entities.empty());
  // A cycle through three entities, reported from where the search entered it.
  const std::string cycle = header +
                            "#1 = A(#2);\n"
                            "#2 = B('#9;', #3);\n"
                            "#3 =\n C(#4);\n"
                            "#4 = D(#2);\nENDSEC;\n";
  const auto found = FindReferenceCycle(cycle);
  EXPECT_EQ(found.entities, (std::vector<long>{2, 3, 4, 2}));
  EXPECT_EQ(found.line, 7);
  // The shape made by OpenCASCADE has none.
  const std::string cyl = testing::ReadText(std::string(HI_SOURCE_DIR) + "/tests/fuzz/corpus/mesh_step/cyl.step");
  EXPECT_TRUE(FindReferenceCycle(cyl).entities.empty());
}

}  // namespace
}  // namespace hull
