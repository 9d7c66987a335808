// The survey contract (../shared/survey-format.md), rule by rule: a valid
// bundle round-trips exactly, and every malformed file is refused with its
// file, line, column and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "base/file_io.h"
#include "survey/survey_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

SurveyBundle TinyBundle(bool stereo) {
  SurveyBundle b;
  b.manifest.name = "tiny";
  b.manifest.vehicle = "HAUV";
  b.manifest.camera.type = stereo ? CameraType::kStereo : CameraType::kMono;
  b.manifest.model_pose_guess = (Vector6d() << 1, 2, 9.1, M_PI, 0, 0.3).finished();
  b.manifest.model_axes = ModelAxes{};
  for (int k = 0; k < 3; ++k) {
    NavRecord n;
    n.keyframe = 10 + k;
    n.t = 0.1 + 1.25 * k;
    n.x_gv << 0.1 * k, 1.0 / 3.0, 10.5, 0.01, -0.02, 0.3 + k;
    n.depth = 10.49;
    n.roll_meas = 0.011;
    n.pitch_meas = -0.019;
    n.servo = 1.5;
    b.nav.push_back(n);
    DvlRecord d;
    d.keyframe = n.keyframe;
    d.range = {1.5, k == 1 ? kNoReturn : 1.6, 1.7, 1.8};
    b.dvl.push_back(d);
    if (k > 0) b.odometry.push_back({10 + k - 1, 10 + k, (Vector6d() << 0.1, 0, 0, 0, 0, 1).finished()});
    for (int l = 0; l < 2; ++l) {
      FeatureObservation f;
      f.keyframe = n.keyframe;
      f.landmark = 100 + l;
      f.top = {600.25 + k, 500.5 - l};
      f.has_bottom = stereo && !(k == 2 && l == 1);
      if (f.has_bottom) f.bottom = {601.0, 420.0};
      b.features.push_back(f);
    }
  }
  b.landmarks = std::vector<LandmarkRecord>{{100, {1, 2, 3}}, {101, {1.5, 2.5, 3.5}}};
  SurveyTruth t;
  for (const auto& n : b.nav) t.poses.push_back({n.keyframe, n.x_gv, n.servo + 0.03});
  t.landmarks.push_back({100, {1, 2, 3}, 0.0, ""});
  t.landmarks.push_back({101, {1.5, 2.5, 3.5}, 0.11, "cyl-1"});
  TrueObject cyl;
  cyl.id = "cyl-1";
  cyl.kind = ObjectKind::kCylinder;
  cyl.center = {90, 1, 0};
  cyl.normal = {0, 0, -1};
  cyl.radius = 0.15;
  cyl.height = 0.11;
  t.objects.push_back(cyl);
  TrueObject box;
  box.id = "box-1";
  box.kind = ObjectKind::kBox;
  box.center = {91, -1, 0};
  box.normal = {0, 0, -1};
  box.size = {0.4, 0.25, 0.08};
  box.height = 0.08;
  box.radius = 0.5 * std::hypot(0.4, 0.25);
  t.objects.push_back(box);
  t.x_gM << -90, 0, 9.1, M_PI, 0, 0.35;
  t.x_s_cT << 0.31, 0.001, -0.002, 1.58, 0.01, 1.56;
  b.truth = t;
  return b;
}

class SurveyIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::path(::testing::TempDir()) /
            ("hi_survey_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name())))
               .string();
    fs::remove_all(dir_);
    WriteSurveyBundle(TinyBundle(true), dir_);
  }
  std::string File(const std::string& name) const { return (fs::path(dir_) / name).string(); }
  std::string Read(const std::string& name) const { return ReadFileToString(File(name)); }
  void Write(const std::string& name, const std::string& text) const { WriteFileAtomic(File(name), text); }
  void Replace(const std::string& name, const std::string& from, const std::string& to) const {
    std::string s = Read(name);
    const auto pos = s.find(from);
    ASSERT_NE(pos, std::string::npos) << from << " not in " << name;
    s.replace(pos, from.size(), to);
    Write(name, s);
  }
  // Reading must fail with an error at file (suffix), line, field; column > 0 when line > 0.
  void ExpectError(const std::string& file, int line, const std::string& field, const std::string& words) const {
    try {
      ReadSurveyBundle(dir_);
      FAIL() << "bundle accepted; expected an error in " << file;
    } catch (const InputError& e) {
      EXPECT_TRUE(EndsWith(e.where().file, file)) << e.what();
      EXPECT_EQ(e.where().line, line) << e.what();
      if (line > 0) {
        EXPECT_GT(e.where().column, 0) << e.what();
      }
      EXPECT_EQ(e.where().field, field) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    // The validator reports the same problem among its errors.
    bool found = false;
    for (const auto& p : ValidateSurveyBundle(dir_)) {
      found = found || (p.severity == Severity::kError && EndsWith(p.where.file, file) && p.where.line == line);
    }
    EXPECT_TRUE(found) << "validator missed the error in " << file << ":" << line;
  }
  std::string dir_;
};

void ExpectSameBundle(const SurveyBundle& a, const SurveyBundle& b) {
  EXPECT_EQ(SurveyManifestToJson(a.manifest), SurveyManifestToJson(b.manifest));
  ASSERT_EQ(a.nav.size(), b.nav.size());
  for (std::size_t i = 0; i < a.nav.size(); ++i) {
    EXPECT_EQ(a.nav[i].keyframe, b.nav[i].keyframe);
    EXPECT_EQ(a.nav[i].t, b.nav[i].t);
    EXPECT_EQ(a.nav[i].x_gv, b.nav[i].x_gv);
    EXPECT_EQ(a.nav[i].servo, b.nav[i].servo);
    EXPECT_EQ(a.nav[i].depth, b.nav[i].depth);
  }
  ASSERT_EQ(a.odometry.size(), b.odometry.size());
  for (std::size_t i = 0; i < a.odometry.size(); ++i) EXPECT_EQ(a.odometry[i].z, b.odometry[i].z);
  ASSERT_EQ(a.dvl.size(), b.dvl.size());
  for (std::size_t i = 0; i < a.dvl.size(); ++i) {
    for (int k = 0; k < 4; ++k) {
      const double x = a.dvl[i].range[k], y = b.dvl[i].range[k];
      EXPECT_TRUE((x == y) || (x != x && y != y));
    }
  }
  ASSERT_EQ(a.features.size(), b.features.size());
  for (std::size_t i = 0; i < a.features.size(); ++i) {
    EXPECT_EQ(a.features[i].top, b.features[i].top);
    EXPECT_EQ(a.features[i].has_bottom, b.features[i].has_bottom);
    if (a.features[i].has_bottom) {
      EXPECT_EQ(a.features[i].bottom, b.features[i].bottom);
    }
  }
  ASSERT_EQ(a.landmarks.has_value(), b.landmarks.has_value());
  ASSERT_EQ(a.truth.has_value(), b.truth.has_value());
  if (a.truth) {
    EXPECT_EQ(a.truth->x_gM, b.truth->x_gM);
    EXPECT_EQ(a.truth->x_s_cT, b.truth->x_s_cT);
    ASSERT_EQ(a.truth->landmarks.size(), b.truth->landmarks.size());
    for (std::size_t i = 0; i < a.truth->landmarks.size(); ++i) {
      EXPECT_EQ(a.truth->landmarks[i].p, b.truth->landmarks[i].p);
      EXPECT_EQ(a.truth->landmarks[i].object, b.truth->landmarks[i].object);
      EXPECT_EQ(a.truth->landmarks[i].deviation, b.truth->landmarks[i].deviation);
    }
    ASSERT_EQ(a.truth->objects.size(), b.truth->objects.size());
    for (std::size_t i = 0; i < a.truth->objects.size(); ++i) {
      EXPECT_EQ(a.truth->objects[i].center, b.truth->objects[i].center);
      EXPECT_EQ(a.truth->objects[i].Height(), b.truth->objects[i].Height());
    }
  }
}

TEST_F(SurveyIo, StereoRoundTripIsIdentical) {
  const SurveyBundle b = ReadSurveyBundle(dir_);
  ExpectSameBundle(TinyBundle(true), b);
  // Written again, the files are byte-identical.
  const std::string dir2 = dir_ + "_again";
  WriteSurveyBundle(b, dir2);
  for (const char* f : {"survey.json", "nav.csv", "odometry.csv", "dvl.csv", "features.csv", "landmarks.csv",
                        "truth/poses.csv", "truth/landmarks.csv", "truth/objects.json"}) {
    EXPECT_EQ(Read(f), ReadFileToString((fs::path(dir2) / f).string())) << f;
  }
  EXPECT_TRUE(ValidateSurveyBundle(dir_).empty());
}

TEST_F(SurveyIo, MonoRoundTripWithoutBottomColumns) {
  fs::remove_all(dir_);
  WriteSurveyBundle(TinyBundle(false), dir_);
  EXPECT_EQ(Read("features.csv").substr(0, 30), "keyframe,landmark,u_top,v_top\n");
  ExpectSameBundle(TinyBundle(false), ReadSurveyBundle(dir_));
}

TEST_F(SurveyIo, ColumnsInAnyOrderUnknownColumnsAndKeysIgnoredCrLf) {
  Write("dvl.csv",
        "extra,r4,r3,r2,r1,keyframe\r\nq,1.8,1.7,1.6,1.5,10\r\nq,1.8,1.7,,1.5,11\r\nq,1.8,1.7,1.6,1.5,12\r\n");
  Replace("survey.json", "\"vehicle\"", "\"future_key\": {\"x\": [1, 2]},\n  \"vehicle\"");
  const SurveyBundle b = ReadSurveyBundle(dir_);
  EXPECT_EQ(b.dvl[1].range[0], 1.5);
  EXPECT_FALSE(DvlRecord::HasReturn(b.dvl[1].range[1]));
  EXPECT_EQ(b.dvl[2].range[3], 1.8);
}

TEST_F(SurveyIo, ManifestFormatAndVersion) {
  Replace("survey.json", "\"hull-survey\"", "\"hull-surveyor\"");
  ExpectError("survey.json", 2, "format", "expected \"hull-survey\"");
}

TEST_F(SurveyIo, ManifestUnknownVersion) {
  Replace("survey.json", "\"version\": 1", "\"version\": 3");
  ExpectError("survey.json", 3, "version", "unsupported version 3");
}

TEST_F(SurveyIo, ManifestCameraType) {
  Replace("survey.json", "\"stereo\"", "\"fisheye\"");
  ExpectError("survey.json", 7, "camera.type", "expected \"stereo\" or \"mono\"");
}

TEST_F(SurveyIo, StereoNeedsBottomCamera) {
  std::string s = Read("survey.json");
  s = std::regex_replace(s, std::regex("\"bottom\": \\{[^}]*\\},"), "");
  Write("survey.json", s);
  ExpectError("survey.json", 6, "camera.bottom", "required key \"bottom\" is missing");
}

TEST_F(SurveyIo, IntrinsicsPositive) {
  Replace("survey.json", "\"fx\": 1150", "\"fx\": -1150");
  ExpectError("survey.json", 11, "camera.top.fx", "expected a positive number");
}

TEST_F(SurveyIo, FourBeams) {
  Replace("survey.json", ",\n      [0, -0.5, 0.866]", "");
  try {
    ReadSurveyBundle(dir_);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "dvl.beams");
  }
}

TEST_F(SurveyIo, JsonSyntaxError) {
  Replace("survey.json", "\"name\": \"tiny\",", "\"name\": \"tiny\"");
  ExpectError("survey.json", 5, "", "expected ',' or '}'");
}

TEST_F(SurveyIo, ModelHintMustExist) {
  Replace("survey.json", "\"vehicle\"", "\"model_hint\": \"missing.ply\",\n  \"vehicle\"");
  ExpectError("survey.json", 5, "model_hint", "does not exist");
}

TEST_F(SurveyIo, NavMissingColumn) {
  Replace("nav.csv", "keyframe,t,", "keyframe,time,");
  ExpectError("nav.csv", 1, "t", "lacks the required column 't'");
}

TEST_F(SurveyIo, NavDuplicateKeyframe) {
  Replace("nav.csv", "\n11,", "\n10,");
  ExpectError("nav.csv", 3, "keyframe", "appears twice");
}

TEST_F(SurveyIo, NavTimeMustIncrease) {
  Replace("nav.csv", "\n12,2.6", "\n12,1.0");
  ExpectError("nav.csv", 4, "t", "t must increase");
}

TEST_F(SurveyIo, NanInfTextAndEmptyAreErrorsInNumericColumns) {
  for (const char* bad : {"nan", "inf", "-Infinity", "ten", ""}) {
    WriteSurveyBundle(TinyBundle(true), dir_);
    Replace("nav.csv", ",10.49,", std::string(",") + bad + ",");
    ExpectError("nav.csv", 2, "depth", bad[0] ? "expected a finite number" : "empty field");
  }
}

TEST_F(SurveyIo, WrongNumberOfFields) {
  Replace("odometry.csv", "\n11,12,", "\n11,12,0,");
  ExpectError("odometry.csv", 3, "", "the line has 9 fields, the header has 8");
}

TEST_F(SurveyIo, OdometryUnknownKeyframe) {
  Replace("odometry.csv", "\n11,12,", "\n11,13,");
  ExpectError("odometry.csv", 3, "to", "keyframe 13 is not in nav.csv");
}

TEST_F(SurveyIo, DvlRangePositive) {
  Replace("dvl.csv", "\n10,1.5,", "\n10,-1.5,");
  ExpectError("dvl.csv", 2, "r1", "expected a positive range");
}

TEST_F(SurveyIo, DvlOneRowPerKeyframe) {
  Replace("dvl.csv", "\n11,", "\n10,");
  ExpectError("dvl.csv", 3, "keyframe", "has a second row");
}

TEST_F(SurveyIo, FeatureKeyframeMustExist) {
  Replace("features.csv", "\n12,100,", "\n99,100,");
  ExpectError("features.csv", 6, "keyframe", "keyframe 99 is not in nav.csv");
}

TEST_F(SurveyIo, FeatureObservedTwice) {
  Replace("features.csv", "\n10,101,", "\n10,100,");
  ExpectError("features.csv", 3, "landmark", "observed twice");
}

TEST_F(SurveyIo, StereoBottomPixelsComeInPairs) {
  Replace("features.csv", "\n10,100,600.25,500.5,601,", "\n10,100,600.25,500.5,,");
  ExpectError("features.csv", 2, "u_bottom", "both be given or both be empty");
}

TEST_F(SurveyIo, StereoFeatureWithoutBottomIsAllowed) {
  const SurveyBundle b = ReadSurveyBundle(dir_);
  EXPECT_FALSE(b.features.back().has_bottom);
}

TEST_F(SurveyIo, MonoMustNotHaveBottomPixels) {
  fs::remove_all(dir_);
  WriteSurveyBundle(TinyBundle(false), dir_);
  Write("features.csv", "keyframe,landmark,u_top,v_top,u_bottom,v_bottom\n10,100,1,2,,\n11,100,1,2,3,4\n");
  ExpectError("features.csv", 3, "u_bottom", "monocular survey has no bottom camera");
}

TEST_F(SurveyIo, PixelOutsideImageIsAWarning) {
  Replace("features.csv", "\n10,100,600.25,", "\n10,100,6000.25,");
  EXPECT_NO_THROW(ReadSurveyBundle(dir_));
  const auto problems = ValidateSurveyBundle(dir_);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].severity, Severity::kWarning);
}

TEST_F(SurveyIo, LandmarksCsvDuplicate) {
  Replace("landmarks.csv", "\n101,", "\n100,");
  ExpectError("landmarks.csv", 3, "landmark", "appears twice");
}

TEST_F(SurveyIo, TruthObjectReferenceAndKind) {
  Replace("truth/landmarks.csv", "cyl-1", "cyl-9");
  ExpectError("truth/landmarks.csv", 3, "object", "not in truth/objects.json");
  WriteSurveyBundle(TinyBundle(true), dir_);
  Replace("truth/objects.json", "\"box\"", "\"sphere\"");
  ExpectError("truth/objects.json", 13, "objects[1].kind", "expected \"cylinder\", \"box\" or \"patch\"");
}

TEST_F(SurveyIo, MissingRequiredFile) {
  fs::remove(File("odometry.csv"));
  ExpectError("odometry.csv", 0, "", "required file is missing");
}

TEST_F(SurveyIo, ValidatorCollectsEveryError) {
  Replace("nav.csv", ",10.49,", ",nan,");
  Replace("dvl.csv", "\n10,1.5,", "\n10,-1.5,");
  Replace("features.csv", "\n12,100,", "\n99,100,");
  const auto problems = ValidateSurveyBundle(dir_);
  std::set<std::string> files;
  for (const auto& p : problems) files.insert(fs::path(p.where.file).filename().string());
  EXPECT_GE(problems.size(), 3u);
  EXPECT_TRUE(files.count("nav.csv") && files.count("dvl.csv") && files.count("features.csv"));
}

TEST_F(SurveyIo, NotABundle) { EXPECT_THROW(ReadSurveyBundle(dir_ + "/nope"), InputError); }

}  // namespace
}  // namespace hull
