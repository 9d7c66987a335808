// Acoustic sequence v1: round trip and every malformed case of the contract,
// with the error's file, line, column and field checked.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "simulate/sonar_simulator.h"
#include "support/test_files.h"
#include "survey/acoustic_sequence.h"

namespace hull {
namespace {

using testing::CsvColumn;
using testing::LineOf;
using testing::ReadText;
using testing::ReplaceLine;
using testing::ScratchDir;
using testing::WriteText;

AcousticSequence SmallSequence() {
  SonarSimulationOptions o;
  o.preset = SonarPreset::kPrism;
  o.seed = 7;
  o.num_steps = 6;
  return SimulateSonar(o);
}

// Reads and expects an InputError at file (suffix), line, column and field;
// returns its message.
std::string ExpectError(const std::string& dir, const std::string& file, int line, int column,
                        const std::string& field) {
  try {
    ReadAcousticSequence(dir);
  } catch (const InputError& e) {
    EXPECT_TRUE(EndsWith(e.where().file, file)) << e.what();
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().column, column) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
    // The validator reports the same problem.
    const std::vector<Problem> problems = ValidateAcousticSequence(dir);
    bool found = false;
    for (const Problem& p : problems) found = found || (p.where.line == line && p.where.column == column);
    EXPECT_TRUE(found) << "the validator missed " << e.what();
    return e.detail();
  }
  ADD_FAILURE() << "no error reading " << dir;
  return "";
}

void ExpectSame(const AcousticSequence& a, const AcousticSequence& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.sensor.range_min, b.sensor.range_min);
  EXPECT_EQ(a.sensor.range_max, b.sensor.range_max);
  EXPECT_EQ(a.sensor.azimuth_fov, b.sensor.azimuth_fov);
  EXPECT_EQ(a.sensor.elevation_fov, b.sensor.elevation_fov);
  EXPECT_EQ(a.sensor.range_sigma, b.sensor.range_sigma);
  EXPECT_EQ(a.sensor.azimuth_sigma, b.sensor.azimuth_sigma);
  EXPECT_EQ(a.initial_pose, b.initial_pose);
  EXPECT_EQ(a.initial_pose_sigma, b.initial_pose_sigma);
  EXPECT_EQ(a.motion_noise.translation_per_metre, b.motion_noise.translation_per_metre);
  EXPECT_EQ(a.motion_noise.rotation_per_radian, b.motion_noise.rotation_per_radian);
  EXPECT_EQ(a.motion_noise.translation_floor, b.motion_noise.translation_floor);
  EXPECT_EQ(a.motion_noise.rotation_floor, b.motion_noise.rotation_floor);
  ASSERT_EQ(a.controls.size(), b.controls.size());
  for (std::size_t i = 0; i < a.controls.size(); ++i) {
    EXPECT_EQ(a.controls[i].step, b.controls[i].step);
    EXPECT_EQ(a.controls[i].u, b.controls[i].u);
  }
  ASSERT_EQ(a.measurements.size(), b.measurements.size());
  for (std::size_t i = 0; i < a.measurements.size(); ++i) {
    EXPECT_EQ(a.measurements[i].step, b.measurements[i].step);
    EXPECT_EQ(a.measurements[i].feature, b.measurements[i].feature);
    EXPECT_EQ(a.measurements[i].range, b.measurements[i].range);
    EXPECT_EQ(a.measurements[i].azimuth, b.measurements[i].azimuth);
  }
  ASSERT_EQ(a.truth.has_value(), b.truth.has_value());
  if (a.truth) {
    EXPECT_EQ(a.truth->poses, b.truth->poses);
    EXPECT_EQ(a.truth->feature_ids, b.truth->feature_ids);
    EXPECT_EQ(a.truth->features, b.truth->features);
  }
}

class AcousticIoTest : public ::testing::Test {
 protected:
  void SetUp() override { WriteAcousticSequence(seq_, dir_.path()); }
  std::string File(const std::string& name) const { return dir_ / name; }
  AcousticSequence seq_ = SmallSequence();
  ScratchDir dir_{"io"};
};

TEST_F(AcousticIoTest, RoundTripIsIdentical) {
  const AcousticSequence back = ReadAcousticSequence(dir_.path());
  ExpectSame(seq_, back);
  EXPECT_EQ(back.num_steps(), 6);
  EXPECT_TRUE(ValidateAcousticSequence(dir_.path()).empty());
  // Written again, every file is byte-identical.
  ScratchDir again("io_again");
  WriteAcousticSequence(back, again.path());
  for (const char* f : {"sonar.json", "controls.csv", "measurements.csv", "truth/poses.csv", "truth/features.csv"}) {
    EXPECT_EQ(ReadText(File(f)), ReadText(again / f)) << f;
  }
}

TEST_F(AcousticIoTest, WithoutTruthAndStaleTruthRemoved) {
  AcousticSequence no_truth = seq_;
  no_truth.truth.reset();
  WriteAcousticSequence(no_truth, dir_.path());  // over a folder that had truth
  const AcousticSequence back = ReadAcousticSequence(dir_.path());
  EXPECT_FALSE(back.truth.has_value());
  ExpectSame(no_truth, back);
}

TEST_F(AcousticIoTest, MeasurementsAreSortedByStepAndColumnsFoundByName) {
  // Columns reordered, an unknown column added, rows in reverse step order.
  std::string text = "azimuth,feature,comment,range,step\n";
  for (auto it = seq_.measurements.rbegin(); it != seq_.measurements.rend(); ++it) {
    text += FormatDouble(it->azimuth) + "," + std::to_string(it->feature) + ",\"a, b\"," + FormatDouble(it->range) +
            "," + std::to_string(it->step) + "\n";
  }
  WriteText(File("measurements.csv"), text);
  const AcousticSequence back = ReadAcousticSequence(dir_.path());
  ASSERT_EQ(back.measurements.size(), seq_.measurements.size());
  for (std::size_t i = 1; i < back.measurements.size(); ++i) {
    EXPECT_LE(back.measurements[i - 1].step, back.measurements[i].step);
  }
}

TEST_F(AcousticIoTest, UnknownJsonKeysIgnoredAndFloorsDefault) {
  std::string json = ReadText(File("sonar.json"));
  json.replace(json.find("\"translation_floor\""), 0, "\"future_key\": {\"a\": [1, 2]}, ");
  WriteText(File("sonar.json"), json);
  ExpectSame(seq_, ReadAcousticSequence(dir_.path()));
  const std::string text =
      "{\"format\": \"hull-sonar\", \"version\": 1, \"vendor\": \"x\",\n"
      " \"sensor\": {\"range_min\": 0.7, \"range_max\": 5.0, \"azimuth_fov\": 0.5585, \"elevation_fov\": 0.2443,\n"
      "            \"range_sigma\": 0.01, \"azimuth_sigma\": 0.0044},\n"
      " \"initial_pose\": [0, 0, 0, 0, 0, 0], \"initial_pose_sigma\": [0.001, 0.001, 0.001, 0.001, 0.001, 0.001],\n"
      " \"motion_noise\": {\"translation_per_metre\": 0.05, \"rotation_per_radian\": 0.05}}\n";
  WriteText(File("sonar.json"), text);
  const AcousticSequence back = ReadAcousticSequence(dir_.path());
  EXPECT_EQ(back.motion_noise.translation_floor, 1e-4);
  EXPECT_EQ(back.motion_noise.rotation_floor, 1e-4);
}

TEST_F(AcousticIoTest, FeatureOutsideTheAzimuthFieldOfView) {
  const std::string path = File("measurements.csv");
  std::string line = LineOf(ReadText(path), 3);
  const int col = CsvColumn(line, 3);
  line = line.substr(0, static_cast<std::size_t>(col - 1)) + "-0.3";
  ReplaceLine(path, 3, line);
  const std::string msg = ExpectError(dir_.path(), "measurements.csv", 3, col, "azimuth");
  EXPECT_NE(msg.find("field of view"), std::string::npos) << msg;
}

TEST_F(AcousticIoTest, FeatureBeyondTheRange) {
  const std::string path = File("measurements.csv");
  std::string line = LineOf(ReadText(path), 4);
  const int col = CsvColumn(line, 2);
  const int next = CsvColumn(line, 3);
  line = line.substr(0, static_cast<std::size_t>(col - 1)) + "5.5" + line.substr(static_cast<std::size_t>(next - 2));
  ReplaceLine(path, 4, line);
  ExpectError(dir_.path(), "measurements.csv", 4, col, "range");
}

TEST_F(AcousticIoTest, MissingControlStepNamesTheLine) {
  // controls.csv: header, steps 1..5 on lines 2..6. Without step 3 the row
  // of step 4 (now line 4) is reported.
  testing::RemoveLine(File("controls.csv"), 4);
  const std::string msg = ExpectError(dir_.path(), "controls.csv", 4, 1, "step");
  EXPECT_NE(msg.find("step 3 is missing"), std::string::npos) << msg;
}

TEST_F(AcousticIoTest, ControlStepZeroIsRefused) {
  const std::string path = File("controls.csv");
  ReplaceLine(path, 2, "0,0,0,0,0,0,0");
  ExpectError(dir_.path(), "controls.csv", 2, 1, "step");
}

TEST_F(AcousticIoTest, NanInAControl) {
  const std::string path = File("controls.csv");
  std::string line = LineOf(ReadText(path), 3);
  const int col = CsvColumn(line, 1);
  const int next = CsvColumn(line, 2);
  line = line.substr(0, static_cast<std::size_t>(col - 1)) + "nan" + line.substr(static_cast<std::size_t>(next - 2));
  ReplaceLine(path, 3, line);
  ExpectError(dir_.path(), "controls.csv", 3, col, "dx");
}

TEST_F(AcousticIoTest, InfAndTextInAMeasurement) {
  const std::string path = File("measurements.csv");
  std::string line = LineOf(ReadText(path), 2);
  const int col = CsvColumn(line, 2);
  const int next = CsvColumn(line, 3);
  ReplaceLine(
      path, 2,
      line.substr(0, static_cast<std::size_t>(col - 1)) + "inf" + line.substr(static_cast<std::size_t>(next - 2)));
  ExpectError(dir_.path(), "measurements.csv", 2, col, "range");
  ReplaceLine(
      path, 2,
      line.substr(0, static_cast<std::size_t>(col - 1)) + "2.5m" + line.substr(static_cast<std::size_t>(next - 2)));
  ExpectError(dir_.path(), "measurements.csv", 2, col, "range");
}

TEST_F(AcousticIoTest, DuplicateMeasurement) {
  const std::string path = File("measurements.csv");
  const std::string text = ReadText(path);
  const std::string second = LineOf(text, 2);
  WriteText(path, text + second + "\n");
  const int last = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  const std::string msg = ExpectError(dir_.path(), "measurements.csv", last, CsvColumn(second, 1), "feature");
  EXPECT_NE(msg.find("twice"), std::string::npos) << msg;
}

TEST_F(AcousticIoTest, MeasurementStepThatDoesNotExist) {
  const std::string path = File("measurements.csv");
  std::string line = LineOf(ReadText(path), 2);
  line = "6" + line.substr(line.find(','));
  ReplaceLine(path, 2, line);
  ExpectError(dir_.path(), "measurements.csv", 2, 1, "step");
}

TEST_F(AcousticIoTest, MeasuredFeatureMissingFromTheTruth) {
  const std::string path = File("measurements.csv");
  std::string line = LineOf(ReadText(path), 2);
  const int col = CsvColumn(line, 1);
  const int next = CsvColumn(line, 2);
  line = line.substr(0, static_cast<std::size_t>(col - 1)) + "99" + line.substr(static_cast<std::size_t>(next - 2));
  ReplaceLine(path, 2, line);
  ExpectError(dir_.path(), "measurements.csv", 2, col, "feature");
}

TEST_F(AcousticIoTest, UnknownVersionIsRefused) {
  std::string json = ReadText(File("sonar.json"));
  const std::size_t at = json.find("\"version\": 1");
  ASSERT_NE(at, std::string::npos);
  json.replace(at, 12, "\"version\": 3");
  WriteText(File("sonar.json"), json);
  // The value's position: line 3 of the pretty-printed manifest, after the key.
  const std::string line = LineOf(json, 3);
  const std::string msg = ExpectError(dir_.path(), "sonar.json", 3, static_cast<int>(line.find('3')) + 1, "version");
  EXPECT_NE(msg.find("unknown version 3"), std::string::npos) << msg;
}

TEST_F(AcousticIoTest, WrongFormatIsRefused) {
  std::string json = ReadText(File("sonar.json"));
  json.replace(json.find("hull-sonar"), 10, "hull-survey");
  WriteText(File("sonar.json"), json);
  const std::string line = LineOf(json, 2);
  ExpectError(dir_.path(), "sonar.json", 2, static_cast<int>(line.find("\"hull-survey\"")) + 1, "format");
}

TEST_F(AcousticIoTest, MissingColumn) {
  const std::string path = File("measurements.csv");
  std::string text = ReadText(path);
  // Drop the azimuth column everywhere.
  std::string out;
  for (int l = 1;; ++l) {
    std::string line;
    try {
      line = LineOf(text, l);
    } catch (const std::out_of_range&) {
      break;
    }
    out += line.substr(0, line.rfind(',')) + "\n";
  }
  WriteText(path, out);
  const std::string msg = ExpectError(dir_.path(), "measurements.csv", 1, 1, "azimuth");
  EXPECT_NE(msg.find("azimuth"), std::string::npos);
}

TEST_F(AcousticIoTest, ShortRow) {
  ReplaceLine(File("controls.csv"), 2, "1,0.1,0.2");
  try {
    ReadAcousticSequence(dir_.path());
    ADD_FAILURE() << "a short row was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(EndsWith(e.where().file, "controls.csv"));
    EXPECT_EQ(e.where().line, 2);
  }
}

TEST_F(AcousticIoTest, BadSensorAndMissingKeys) {
  std::string json = ReadText(File("sonar.json"));
  json.replace(json.find("\"range_min\": 0.7"), 16, "\"range_min\": -1");
  WriteText(File("sonar.json"), json);
  try {
    ReadAcousticSequence(dir_.path());
    ADD_FAILURE() << "a negative range_min was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "sensor.range_min");
    EXPECT_GT(e.where().line, 0);
  }
  WriteText(File("sonar.json"), "{\"format\": \"hull-sonar\", \"version\": 1}\n");
  const std::vector<Problem> problems = ValidateAcousticSequence(dir_.path());
  // sensor, initial_pose, initial_pose_sigma and motion_noise are all missing.
  EXPECT_GE(problems.size(), 4u);
}

TEST_F(AcousticIoTest, MissingFileAndValidatorCollectsEverything) {
  std::filesystem::remove(File("controls.csv"));
  try {
    ReadAcousticSequence(dir_.path());
    ADD_FAILURE() << "a missing controls.csv was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(EndsWith(e.where().file, "controls.csv"));
    EXPECT_NE(e.detail().find("missing"), std::string::npos);
  }
  WriteAcousticSequence(seq_, dir_.path());
  // Two independent problems in two files: both reported.
  ReplaceLine(File("controls.csv"), 3, "2,nan,0,0,0,0,0");
  std::string line = LineOf(ReadText(File("measurements.csv")), 2);
  ReplaceLine(File("measurements.csv"), 2, line.substr(0, line.rfind(',')) + ",1.0");
  const std::vector<Problem> problems = ValidateAcousticSequence(dir_.path());
  ASSERT_GE(problems.size(), 2u);
  bool controls = false, meas = false;
  for (const Problem& p : problems) {
    controls = controls || (EndsWith(p.where.file, "controls.csv") && p.where.line == 3);
    meas = meas || (EndsWith(p.where.file, "measurements.csv") && p.where.line == 2);
  }
  EXPECT_TRUE(controls);
  EXPECT_TRUE(meas);
}

TEST_F(AcousticIoTest, TruthPosesMustCoverEveryStep) {
  testing::RemoveLine(File("truth/poses.csv"), 7);  // the last step
  try {
    ReadAcousticSequence(dir_.path());
    ADD_FAILURE() << "truth without the last step was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(EndsWith(e.where().file, "truth/poses.csv"));
  }
}

}  // namespace
}  // namespace hull
