// Survey bundle version 2 (../shared/survey-format.md, "Images"): images/
// listed against nav.csv, features.csv optional with images, dropped frames
// warned and counted, every naming and content problem named by file; version
// 1 bundles unchanged.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include <opencv2/core.hpp>

#include "base/file_io.h"
#include "image/image_file.h"
#include "support/test_files.h"
#include "support/test_images.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;
using testing::PatternImage;
using testing::ScratchDir;
using testing::WriteText;

constexpr int kW = 136, kH = 102;  // small images keep the test quick

// Keyframes 10, 11, ... with navigation and DVL, no features.
SurveyBundle ImageBundle(bool stereo, int keyframes = 3) {
  SurveyBundle b;
  b.manifest.version = 2;
  b.manifest.name = "images";
  b.manifest.camera.type = stereo ? CameraType::kStereo : CameraType::kMono;
  b.manifest.camera.width = kW;
  b.manifest.camera.height = kH;
  b.manifest.imaging = ImagingNote{0.004, std::string("strobe")};
  for (int k = 0; k < keyframes; ++k) {
    NavRecord n;
    n.keyframe = 10 + k;
    n.t = 1.0 * k;
    n.x_gv << 0.3 * k, 0, 10, 0, 0, 0;
    n.depth = 10;
    n.servo = 1.5;
    b.nav.push_back(n);
    DvlRecord d;
    d.keyframe = n.keyframe;
    d.range = {1.5, 1.6, 1.7, 1.8};
    b.dvl.push_back(d);
    if (k > 0) b.odometry.push_back({10 + k - 1, 10 + k, (Vector6d() << 0.3, 0, 0, 0, 0, 0).finished()});
  }
  b.images = SurveyImages{};  // written without features.csv
  return b;
}

class SurveyImagesTest : public ::testing::Test {
 protected:
  void Make(bool stereo, int keyframes = 3) {
    for (const auto& e : fs::directory_iterator(dir_.path())) fs::remove_all(e.path());
    WriteSurveyBundle(ImageBundle(stereo, keyframes), dir_.path());
    fs::create_directories(dir_ / "images");
    for (int k = 0; k < keyframes; ++k) {
      WriteImage(SurveyImageName(10 + k, false), CV_8UC1, k);
      if (stereo) WriteImage(SurveyImageName(10 + k, true), CV_8UC1, k + 50);
    }
  }
  void WriteImage(const std::string& name, int type, int seed = 0, int w = kW, int h = kH) const {
    WriteImageFile(dir_ / ("images/" + name), PatternImage(w, h, type, seed));
  }
  // The validator's problems of a severity, as text.
  std::vector<std::string> Problems(Severity severity) const {
    std::vector<std::string> out;
    for (const Problem& p : ValidateSurveyBundle(dir_.path())) {
      if (p.severity == severity) out.push_back(p.ToString());
    }
    return out;
  }
  // Exactly one error, naming `file` (relative to the bundle) and containing `words`.
  void ExpectOneError(const std::string& file, const std::string& words) const {
    const auto errors = Problems(Severity::kError);
    ASSERT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
    EXPECT_NE(errors[0].find(dir_ / file), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find(words), std::string::npos) << errors[0];
  }
  ScratchDir dir_{"survey_images"};
};

TEST_F(SurveyImagesTest, VersionTwoWithImagesNeedsNoFeatures) {
  Make(true);
  ASSERT_FALSE(fs::exists(dir_ / "features.csv"));
  EXPECT_TRUE(ValidateSurveyBundle(dir_.path()).empty()) << ::testing::PrintToString(Problems(Severity::kWarning));
  const SurveyBundle b = ReadSurveyBundle(dir_.path());
  EXPECT_EQ(b.manifest.version, 2);
  ASSERT_TRUE(b.manifest.imaging);
  EXPECT_EQ(*b.manifest.imaging->exposure_s, 0.004);
  EXPECT_EQ(*b.manifest.imaging->illumination, "strobe");
  ASSERT_TRUE(b.images);
  EXPECT_EQ(b.images->expected, 6);
  EXPECT_EQ(b.images->dropped, 0);
  ASSERT_EQ(b.images->frames.size(), 3u);
  EXPECT_EQ(b.images->frames[1].keyframe, 11);
  EXPECT_EQ(b.images->frames[1].top, "images/11_top.png");
  EXPECT_EQ(b.images->frames[1].bottom, "images/11_bottom.png");
  EXPECT_EQ(b.ImagePath(12, true), dir_ / "images/12_bottom.png");
  EXPECT_TRUE(b.features.empty());
  ImageInfo info;
  const cv::Mat top = ReadSurveyImage(b, 11, false, std::nullopt, &info);
  EXPECT_EQ(cv::norm(top, PatternImage(kW, kH, CV_8UC1, 1), cv::NORM_INF), 0);
  EXPECT_EQ(info.Describe(), "136x102 8-bit grey PNG");
  // Written again: still version 2, still no features.csv, the images block kept.
  const ScratchDir again("survey_images_again");
  WriteSurveyBundle(b, again.path());
  EXPECT_EQ(ReadFileToString(dir_ / "survey.json"), ReadFileToString(again / "survey.json"));
  EXPECT_FALSE(fs::exists(again / "features.csv"));
}

TEST_F(SurveyImagesTest, FeaturesStillRequiredWithoutImagesOrInVersionOne) {
  Make(false);
  fs::remove_all(dir_ / "images");
  ExpectOneError("features.csv", "required file is missing");
  Make(false);
  const std::string json = ReadFileToString(dir_ / "survey.json");
  WriteText(dir_ / "survey.json", std::regex_replace(json, std::regex("\"version\": 2"), "\"version\": 1"));
  ExpectOneError("features.csv", "required file is missing");
  const auto warnings = Problems(Severity::kWarning);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("images need \"version\": 2"), std::string::npos) << warnings[0];
  // An empty images/ and no features.csv: nothing to work from.
  Make(false);
  fs::remove_all(dir_ / "images");
  fs::create_directories(dir_ / "images");
  const auto errors = Problems(Severity::kError);
  ASSERT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
  EXPECT_NE(errors[0].find("holds no image and there is no features.csv"), std::string::npos);
}

TEST_F(SurveyImagesTest, DroppedFramesAreWarnedAndCounted) {
  Make(true);
  fs::remove(dir_ / "images/11_bottom.png");
  EXPECT_TRUE(Problems(Severity::kError).empty());
  const auto warnings = Problems(Severity::kWarning);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("(11_bottom.png): warning: dropped frame: keyframe 11 has no bottom image"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("1 of 6 images missing (dropped frames)"), std::string::npos) << warnings[1];
  const SurveyBundle b = ReadSurveyBundle(dir_.path());
  EXPECT_EQ(b.images->dropped, 1);
  EXPECT_EQ(b.images->present(), 5);
  EXPECT_TRUE(b.images->frames[1].bottom.empty());
  EXPECT_EQ(b.ImagePath(11, true), "");
  try {
    ReadSurveyImage(b, 11, true);
    ADD_FAILURE() << "no error for a dropped frame";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "11_bottom.png");
    EXPECT_NE(e.detail().find("dropped frame"), std::string::npos);
  }
  // Many drops: the first 20 named, all counted, and still no error.
  Make(false, 40);
  for (int k = 1; k < 40; ++k) fs::remove(dir_ / ("images/" + SurveyImageName(10 + k, false)));
  EXPECT_TRUE(Problems(Severity::kError).empty());
  const auto many = Problems(Severity::kWarning);
  ASSERT_EQ(many.size(), 21u);
  EXPECT_NE(many.back().find("39 of 40 images missing (dropped frames); the first 20 are listed above"),
            std::string::npos)
      << many.back();
  EXPECT_EQ(ReadSurveyBundle(dir_.path()).images->dropped, 39);
}

TEST_F(SurveyImagesTest, BadNamesAreErrorsNamingTheFile) {
  struct Case {
    std::string name, words, reported;  // reported: the file named, when not `name`
  } cases[] = {
      {"010_top.png", "the keyframe id is written '010'; expected it as nav.csv writes it ('10', no padding or sign)",
       ""},
      {"99_top.png", "keyframe 99 is not in nav.csv", ""},
      {"10_top.jpeg", "not a valid image name", ""},
      {"10_TOP.png", "not a valid image name", ""},
      {"10_left.png", "not a valid image name", ""},
      {"10_top.jpg", "a second image for keyframe 10's top camera (also 10_top.jpg)", "10_top.png"},
  };
  for (const Case& c : cases) {
    Make(true);
    WriteImage(c.name, CV_8UC1);
    SCOPED_TRACE(c.name);
    const std::string reported = "images/" + (c.reported.empty() ? c.name : c.reported);
    ExpectOneError(reported, c.words);
    // The reader stops at the same problem.
    try {
      ReadSurveyBundle(dir_.path());
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, dir_ / reported);
    }
  }
  Make(false);
  WriteImage("10_bottom.png", CV_8UC1);
  ExpectOneError("images/10_bottom.png", "a monocular survey has no bottom camera");
  // Other files are ignored with a warning.
  Make(false);
  WriteText(dir_ / "images/notes.txt", "taken on a sunny day\n");
  EXPECT_TRUE(Problems(Severity::kError).empty());
  const auto warnings = Problems(Severity::kWarning);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("notes.txt: warning: ignored: not an image of the bundle"), std::string::npos);
}

TEST_F(SurveyImagesTest, EveryImageIsCheckedByTheValidator) {
  // A truncated image: the reader lists it (images are read lazily), the
  // validator and ReadSurveyImage refuse it.
  Make(true);
  const std::string bytes = ReadFileToString(dir_ / "images/11_top.png");
  WriteText(dir_ / "images/11_top.png", bytes.substr(0, bytes.size() / 2));
  ExpectOneError("images/11_top.png", "truncated PNG");
  const SurveyBundle b = ReadSurveyBundle(dir_.path());
  EXPECT_THROW(ReadSurveyImage(b, 11, false), InputError);
  EXPECT_NO_THROW(ReadSurveyImage(b, 12, false));

  Make(true);
  WriteImage("12_bottom.png", CV_8UC1, 0, kW * 2, kH);
  ExpectOneError("images/12_bottom.png",
                 "the image is 272x102; expected 136x102 (camera.width x camera.height in survey.json)");

  Make(true);
  WriteImage("11_top.png", CV_16UC1);
  ExpectOneError("images/11_top.png", "the image is 16-bit grey; expected 8-bit grey like images/10_top.png");

  Make(true);
  WriteImage("10_top.png", CV_8UC3);  // the first image sets the layout; the other five differ
  EXPECT_EQ(Problems(Severity::kError).size(), 5u);

  // JPEG among PNG is fine when the layout is the same.
  Make(true);
  fs::remove(dir_ / "images/11_top.png");
  WriteImage("11_top.jpg", CV_8UC1);
  EXPECT_TRUE(ValidateSurveyBundle(dir_.path()).empty());
  EXPECT_EQ(ReadSurveyBundle(dir_.path()).images->frames[1].top, "images/11_top.jpg");
}

TEST_F(SurveyImagesTest, ImagesOfAnUnreadableNavRowAreSkippedQuietly) {
  Make(false);
  // Keyframe 11's nav row gets a bad number: one error, none for its image.
  std::string nav = ReadFileToString(dir_ / "nav.csv");
  nav.replace(nav.find("\n11,") + 4, 1, "x");
  WriteText(dir_ / "nav.csv", nav);
  const auto errors = Problems(Severity::kError);
  ASSERT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
  EXPECT_NE(errors[0].find("nav.csv:3"), std::string::npos) << errors[0];
}

}  // namespace
}  // namespace hull
