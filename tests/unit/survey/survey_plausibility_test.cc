// Issue 14: values that are finite and well-formed yet absurd are refused
// by the validator with their reason, naming file, line, column and field;
// the same rules refuse the bundle when it is read for the pipeline.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "geometry/mesh_io.h"
#include "support/test_files.h"
#include "support/test_surveys.h"
#include "survey/survey_io.h"

namespace hull {
namespace {

using testing::CsvColumn;
using testing::LineOf;
using testing::ReadText;
using testing::ScratchDir;

// Writes the small survey after `edit` and validates it.
struct Edited {
  std::string dir;
  std::vector<Problem> problems;
  int errors() const {
    int n = 0;
    for (const auto& p : problems) n += p.severity == Severity::kError;
    return n;
  }
  std::string Text() const {
    std::string s;
    for (const auto& p : problems) s += p.ToString() + "\n";
    return s;
  }
  // The first error's printed form.
  std::string First() const {
    for (const auto& p : problems) {
      if (p.severity == Severity::kError) return p.ToString();
    }
    return "";
  }
};

std::vector<Problem> Errors(const std::vector<Problem>& all) {
  std::vector<Problem> out;
  for (const auto& p : all) {
    if (p.severity == Severity::kError) out.push_back(p);
  }
  return out;
}

Edited Validate(const ScratchDir& tmp, const std::function<void(SurveyBundle&)>& edit) {
  SurveyBundle b = test::SmallSurvey().bundle;
  edit(b);
  Edited e;
  e.dir = tmp / "bundle";
  WriteSurveyBundle(b, e.dir);
  SaveMesh(test::SmallSurvey().cad, e.dir + "/hull.ply");
  e.problems = ValidateSurveyBundle(e.dir);
  return e;
}

// "nav.csv:LINE:COLUMN (field)" of data row `row` (0-based) and CSV field `field`.
std::string NavPlace(const std::string& dir, int row, int field, const std::string& name) {
  const std::string line = LineOf(ReadText(dir + "/nav.csv"), row + 2);
  return "nav.csv:" + std::to_string(row + 2) + ":" + std::to_string(CsvColumn(line, field)) + " (" + name + ")";
}

TEST(SurveyPlausibility, TheSmallSurveyIsValid) {
  const ScratchDir tmp("plaus_clean");
  const Edited e = Validate(tmp, [](SurveyBundle&) {});
  EXPECT_EQ(e.errors(), 0) << e.Text();
  EXPECT_GE(test::SmallSurvey().bundle.nav.size(), 20u);
  EXPECT_NO_THROW(ReadSurveyBundle(e.dir));
}

TEST(SurveyPlausibility, AbsurdNavPositionsAreRefusedAtTheirField) {
  // The values: x on the second data row, and z = 2e9.
  for (double x : {1e308, 1e30, 1e10, 1e6}) {
    const ScratchDir tmp("plaus_nav");
    const Edited e = Validate(tmp, [x](SurveyBundle& b) { b.nav[1].x_gv[0] = x; });
    ASSERT_GE(e.errors(), 1) << x;
    EXPECT_NE(e.First().find(NavPlace(e.dir, 1, 2, "x")), std::string::npos) << x << "\n" << e.Text();
    EXPECT_NE(e.First().find("plausible") == std::string::npos ? e.First().find("median keyframe position")
                                                               : e.First().find("plausible"),
              std::string::npos)
        << e.First();
    // The pipeline's reader refuses it too (exit 3 in the CLI).
    EXPECT_THROW(ReadSurveyBundle(e.dir), InputError) << x;
  }
  const ScratchDir tmp("plaus_nav_z");
  const Edited e = Validate(tmp, [](SurveyBundle& b) { b.nav[1].x_gv[2] = 2e9; });
  EXPECT_NE(e.First().find(NavPlace(e.dir, 1, 4, "z")), std::string::npos) << e.Text();
  EXPECT_NE(e.First().find("1e+07"), std::string::npos) << e.First();
}

TEST(SurveyPlausibility, AFarPositionNamesTheSurveysBound) {
  const ScratchDir tmp("plaus_far");
  const Edited e = Validate(tmp, [](SurveyBundle& b) { b.nav[3].x_gv[1] += 5000; });
  ASSERT_GE(e.errors(), 1);
  EXPECT_NE(e.First().find(NavPlace(e.dir, 3, 3, "y")), std::string::npos) << e.Text();
  EXPECT_NE(e.First().find("the keyframes lie within"), std::string::npos) << e.First();
  EXPECT_NE(e.First().find("DVL"), std::string::npos) << e.First();
}

TEST(SurveyPlausibility, ManifestValuesOutsideTheirScaleAreRefused) {
  struct Case {
    std::function<void(SurveyBundle&)> edit;
    std::string field, reason;
  };
  const std::vector<Case> cases = {
      {[](SurveyBundle& b) { b.manifest.camera.top.fx = 2e9; }, "(camera.top.fx)", "image's larger side"},
      {[](SurveyBundle& b) { b.manifest.camera.servo_to_top[3] = 1.8e19; }, "(camera.servo_to_top)", "one turn"},
      {[](SurveyBundle& b) { b.manifest.noise.pixel_sigma = 2e9; }, "(noise.pixel_sigma)", "5 % of the image"},
      {[](SurveyBundle& b) { b.manifest.noise.dvl_range_sigma = 2e9; }, "(noise.dvl_range_sigma)", "10 m"},
      {[](SurveyBundle& b) { b.manifest.noise.odometry_translation_rate = 1e-300; },
       "(noise.odometry_translation_rate)", "drift rate"},
      {[](SurveyBundle& b) { b.manifest.camera.top.cx = -1e7; }, "(camera.top.cx)", "principal point"},
      {[](SurveyBundle& b) { b.manifest.servo_mount[0] = 1e12; }, "(servo.mount)", "lever arm"},
      {[](SurveyBundle& b) { b.manifest.model_pose_guess = (Vector6d() << 1e30, 0, 0, 0, 0, 0).finished(); },
       "(model_pose_guess)", "1e7"},
  };
  for (const Case& c : cases) {
    const ScratchDir tmp("plaus_manifest");
    const Edited e = Validate(tmp, c.edit);
    ASSERT_GE(e.errors(), 1) << c.field;
    EXPECT_NE(e.First().find("survey.json:"), std::string::npos) << e.First();
    EXPECT_NE(e.First().find(c.field), std::string::npos) << e.First();
    EXPECT_NE(e.First().find(c.reason), std::string::npos) << e.First();
    EXPECT_THROW(ReadSurveyBundle(e.dir), InputError) << c.field;
  }
}

TEST(SurveyPlausibility, AModelPoseGuessFarFromTheSurveyIsRefused) {
  const ScratchDir tmp("plaus_guess");
  const Edited e = Validate(tmp, [](SurveyBundle& b) { (*b.manifest.model_pose_guess)[0] += 1e5; });
  ASSERT_EQ(e.errors(), 1) << e.Text();
  EXPECT_NE(e.First().find("(model_pose_guess)"), std::string::npos) << e.First();
  EXPECT_NE(e.First().find("longest hull"), std::string::npos) << e.First();
}

TEST(SurveyPlausibility, DuplicatedOdometryEdgesAreRefused) {
  for (bool reversed : {false, true}) {
    const ScratchDir tmp("plaus_dup");
    const Edited e = Validate(tmp, [reversed](SurveyBundle& b) {
      OdometryRecord o = b.odometry[4];
      if (reversed) {
        std::swap(o.from, o.to);
        o.z = Ominus(o.z);
      }
      b.odometry.push_back(o);
    });
    ASSERT_EQ(e.errors(), 1) << e.Text();
    const int last = static_cast<int>(test::SmallSurvey().bundle.odometry.size()) + 2;
    EXPECT_NE(e.First().find("odometry.csv:" + std::to_string(last) + ":"), std::string::npos) << e.First();
    EXPECT_NE(e.First().find("duplicates line 6"), std::string::npos) << e.First();
  }
}

TEST(SurveyPlausibility, OdometryThatDisagreesWithConsecutiveNavIsRefused) {
  const ScratchDir tmp("plaus_odo");
  const Edited e = Validate(tmp, [](SurveyBundle& b) { b.odometry[2].z[0] += 25; });
  ASSERT_EQ(e.errors(), 1) << e.Text();
  EXPECT_NE(e.First().find("odometry.csv:4:"), std::string::npos) << e.First();
  EXPECT_NE(e.First().find("(dx)"), std::string::npos) << e.First();
  EXPECT_NE(e.First().find("disagrees with nav.csv lines"), std::string::npos) << e.First();
  // A rotation that disagrees.
  const ScratchDir tmp2("plaus_odo_rot");
  const Edited r = Validate(tmp2, [](SurveyBundle& b) { b.odometry[2].z[5] += 1.0; });
  ASSERT_EQ(r.errors(), 1) << r.Text();
  EXPECT_NE(r.First().find("(dyaw)"), std::string::npos) << r.First();
  EXPECT_NE(r.First().find(" deg;"), std::string::npos) << r.First();
}

TEST(SurveyPlausibility, AbsurdDvlRangesAreRefused) {
  const ScratchDir tmp("plaus_dvl");
  const Edited e = Validate(tmp, [](SurveyBundle& b) { b.dvl[5].range[2] = 1e6; });
  ASSERT_EQ(e.errors(), 1) << e.Text();
  EXPECT_NE(e.First().find("dvl.csv:7:"), std::string::npos) << e.First();
  EXPECT_NE(e.First().find("(r3)"), std::string::npos) << e.First();
  EXPECT_NE(e.First().find("median return"), std::string::npos) << e.First();
}

TEST(SurveyPlausibility, TheModelHintMeshIsOpenedAndChecked) {
  const ScratchDir tmp("plaus_mesh");
  const Edited clean = Validate(tmp, [](SurveyBundle&) {});
  ASSERT_EQ(clean.errors(), 0) << clean.Text();
  // A corrupted face index (the 50331658), written as ASCII PLY.
  TriangleMesh bad = test::SmallSurvey().cad;
  MeshSaveOptions ascii;
  ascii.binary = false;
  SaveMesh(bad, clean.dir + "/hull.ply", ascii);
  std::string text = ReadText(clean.dir + "/hull.ply");
  const std::string face = "\n3 " + std::to_string(bad.faces[0][0]) + " ";
  const auto at = text.find(face, text.find("end_header"));
  ASSERT_NE(at, std::string::npos);
  text.replace(at, face.size(), "\n3 50331658 ");
  testing::WriteText(clean.dir + "/hull.ply", text);
  std::vector<Problem> problems = Errors(ValidateSurveyBundle(clean.dir));
  ASSERT_EQ(problems.size(), 1u);
  const std::string msg = problems[0].ToString();
  EXPECT_NE(msg.find("survey.json:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(model_hint)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("50331658"), std::string::npos) << msg;
  EXPECT_NE(msg.find("hull.ply"), std::string::npos) << msg;
  // A mesh of degenerate triangles only: zero area.
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.faces = {{0, 1, 2}, {2, 1, 0}};
  SaveMesh(flat, clean.dir + "/hull.ply");
  problems = Errors(ValidateSurveyBundle(clean.dir));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].ToString().find("zero area"), std::string::npos) << problems[0].ToString();
}

}  // namespace
}  // namespace hull
