// Acoustic sequence v2 (images): round trip, measurements.csv optional, and
// every bad image named by its file (missing step, wrong size, truncated,
// colour, an image of a step that does not exist); version 1 unchanged.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "base/error.h"
#include "base/file_io.h"
#include "image/image_file.h"
#include "simulate/sonar_simulator.h"
#include "support/test_files.h"
#include "support/test_images.h"
#include "survey/acoustic_sequence.h"
#include "survey/sonar_image.h"

namespace hull {
namespace {

using testing::ReadText;
using testing::ScratchDir;
using testing::WriteText;

// A small version 2 sequence: 4 steps, 64 x 16 images with a pattern.
AcousticSequence SmallSequence() {
  SonarSimulationOptions o;
  o.seed = 3;
  o.num_steps = 4;
  AcousticSequence seq = SimulateSonar(o);
  seq.image = SonarImageFormat{64, 16, 3.0};
  return seq;
}

void WriteWithImages(const AcousticSequence& seq, const std::string& dir) {
  WriteAcousticSequence(seq, dir);
  for (int k = 0; k < seq.num_steps(); ++k) {
    WriteSonarImage(SonarImagePath(dir, k), testing::PatternImage(seq.image->beams, seq.image->range_bins, CV_8UC1, k));
  }
}

// Expects ReadAcousticSequence to throw an InputError whose file ends with
// `file` and whose message holds `words`; the validator must report it too.
void ExpectImageError(const std::string& dir, const std::string& file, const std::string& words) {
  try {
    ReadAcousticSequence(dir);
    ADD_FAILURE() << "no error reading " << dir;
  } catch (const InputError& e) {
    EXPECT_TRUE(EndsWith(e.where().file, file)) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
  bool found = false;
  for (const Problem& p : ValidateAcousticSequence(dir)) found = found || EndsWith(p.where.file, file);
  EXPECT_TRUE(found) << "the validator missed the problem with " << file;
}

TEST(AcousticImages, RoundTripWithAndWithoutMeasurements) {
  const ScratchDir dir("sonar_v2_round_trip");
  AcousticSequence seq = SmallSequence();
  WriteWithImages(seq, dir.path());
  EXPECT_NE(ReadText(dir / "sonar.json").find("\"version\": 2"), std::string::npos);
  AcousticSequence back = ReadAcousticSequence(dir.path());
  ASSERT_TRUE(back.image.has_value());
  EXPECT_EQ(back.image->range_bins, 64);
  EXPECT_EQ(back.image->beams, 16);
  EXPECT_EQ(back.image->gain_db, 3.0);
  EXPECT_TRUE(back.has_measurements);
  EXPECT_EQ(back.measurements.size(), seq.measurements.size());
  EXPECT_TRUE(ValidateAcousticSequence(dir.path()).empty());
  const cv::Mat image = ReadSonarImage(SonarImagePath(dir.path(), 2), *back.image);
  EXPECT_EQ(cv::norm(image, testing::PatternImage(16, 64, CV_8UC1, 2), cv::NORM_INF), 0.0);

  // Without measurements.csv: still a sequence (features from the images).
  seq.has_measurements = false;
  WriteAcousticSequence(seq, dir.path());
  EXPECT_FALSE(std::filesystem::exists(dir / "measurements.csv"));
  back = ReadAcousticSequence(dir.path());
  EXPECT_FALSE(back.has_measurements);
  EXPECT_TRUE(back.measurements.empty());
  EXPECT_TRUE(ValidateAcousticSequence(dir.path()).empty());

  // Version 1 still needs its measurements, and knows no image block.
  AcousticSequence v1 = SmallSequence();
  v1.image.reset();
  v1.has_measurements = false;
  EXPECT_THROW(WriteAcousticSequence(v1, (dir / "v1")), std::invalid_argument);
}

TEST(AcousticImages, PixelGeometryFollowsTheContract) {
  SonarSensor s;
  const SonarImageFormat f{512, 128, 0};
  EXPECT_NEAR(f.RowToRange(s, 0), s.range_min + 0.5 * (s.range_max - s.range_min) / 512, 1e-12);
  EXPECT_NEAR(f.ColumnToAzimuth(s, 0), -s.azimuth_fov / 2 + 0.5 * s.azimuth_fov / 128, 1e-12);
  EXPECT_NEAR(f.ColumnToAzimuth(s, 127), s.azimuth_fov / 2 - 0.5 * s.azimuth_fov / 128, 1e-12);
  EXPECT_NEAR(f.RangeToRow(s, f.RowToRange(s, 123.25)), 123.25, 1e-9);
  EXPECT_NEAR(f.AzimuthToColumn(s, f.ColumnToAzimuth(s, 17.75)), 17.75, 1e-9);
}

TEST(AcousticImages, MissingStepImageIsNamed) {
  const ScratchDir dir("sonar_v2_missing");
  const AcousticSequence seq = SmallSequence();
  WriteWithImages(seq, dir.path());
  std::filesystem::remove(SonarImagePath(dir.path(), 2));
  ExpectImageError(dir.path(), "images/2.png", "missing");
  std::filesystem::remove_all(dir / "images");
  ExpectImageError(dir.path(), "images", "missing");
}

TEST(AcousticImages, WrongSizeIsNamed) {
  const ScratchDir dir("sonar_v2_size");
  const AcousticSequence seq = SmallSequence();
  WriteWithImages(seq, dir.path());
  WriteSonarImage(SonarImagePath(dir.path(), 1), testing::PatternImage(64, 16, CV_8UC1));  // transposed
  ExpectImageError(dir.path(), "images/1.png", "range_bins");
}

TEST(AcousticImages, TruncatedAndColourImagesAreNamed) {
  const ScratchDir dir("sonar_v2_truncated");
  const AcousticSequence seq = SmallSequence();
  WriteWithImages(seq, dir.path());
  const std::string path = SonarImagePath(dir.path(), 3);
  const std::string bytes = ReadFileToString(path);
  WriteFileAtomic(path, bytes.substr(0, bytes.size() / 2));
  ExpectImageError(dir.path(), "images/3.png", "images/3.png");
  EXPECT_THROW(ReadSonarImage(path, *seq.image), InputError);

  WriteWithImages(seq, dir.path());
  WriteImageFile(SonarImagePath(dir.path(), 0), testing::PatternImage(16, 64, CV_8UC3));
  ExpectImageError(dir.path(), "images/0.png", "grey");
}

TEST(AcousticImages, ImageOfAStepTheSequenceLacksIsNamed) {
  const ScratchDir dir("sonar_v2_extra");
  const AcousticSequence seq = SmallSequence();
  WriteWithImages(seq, dir.path());
  WriteSonarImage(SonarImagePath(dir.path(), 7), testing::PatternImage(16, 64, CV_8UC1));
  ExpectImageError(dir.path(), "images/7.png", "does not have");
}

TEST(AcousticImages, ImageBlockNeedsVersionTwo) {
  const ScratchDir dir("sonar_v2_block");
  const AcousticSequence seq = SmallSequence();
  WriteWithImages(seq, dir.path());
  std::string json = ReadText(dir / "sonar.json");
  json.replace(json.find("\"version\": 2"), 12, "\"version\": 1");
  WriteText(dir / "sonar.json", json);
  ExpectImageError(dir.path(), "sonar.json", "version");
  // Version 2 without its image block.
  json = ReadText(dir / "sonar.json");
  json.replace(json.find("\"version\": 1"), 12, "\"version\": 2");
  json.replace(json.find("\"image\""), 7, "\"picture\"");
  WriteText(dir / "sonar.json", json);
  ExpectImageError(dir.path(), "sonar.json", "image");
}

}  // namespace
}  // namespace hull
