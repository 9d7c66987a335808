// Never report what was not seen, no crash on absurd numbers (issue 23,
// parts 1 and 3), for the sonar: the acoustic sequence's plausibility bounds
// refuse the values that broke the filter (SIGSEGV in WeighPending) with the
// file, line and field; values at the bounds run; the EKF's own guards name
// the step; and RunSonarPipeline stops on images that show nothing or noise.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "base/error.h"
#include "base/file_io.h"
#include "simulate/sonar_image_simulator.h"
#include "simulate/sonar_simulator.h"
#include "sonar/sonar_ekf.h"
#include "sonar/sonar_pipeline.h"
#include "support/test_files.h"
#include "survey/acoustic_sequence.h"

namespace hull {
namespace {

using testing::ScratchDir;

AcousticSequence SmallSequence() {
  SonarSimulationOptions o;
  o.preset = SonarPreset::kPrism;
  o.seed = 7;
  o.num_steps = 6;
  return SimulateSonar(o);
}

// The sequence's error, expected at `field` of `file`.
std::string ReadError(const std::string& dir, const std::string& file, const std::string& field) {
  try {
    ReadAcousticSequence(dir);
  } catch (const InputError& e) {
    EXPECT_TRUE(EndsWith(e.where().file, file)) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
    EXPECT_GT(e.where().line, 0) << e.what();
    return e.detail();
  }
  ADD_FAILURE() << "accepted";
  return "";
}

class SonarPlausibility : public ::testing::Test {
 protected:
  void SetUp() override {
    seq_ = SmallSequence();
    WriteAcousticSequence(seq_, dir_.path());
  }
  // Writes the sequence with `edit` applied and returns its folder.
  std::string With(void (*edit)(AcousticSequence&)) {
    AcousticSequence s = seq_;
    edit(s);
    WriteAcousticSequence(s, dir_.path());
    return dir_.path();
  }
  AcousticSequence seq_;
  ScratchDir dir_{"sonar_plausible"};
};

// The fuzzer's and the cases: each refused at read time, naming the field.
TEST_F(SonarPlausibility, AbsurdSigmasAndControlsAreRefusedWithTheField) {
  std::string why = ReadError(With([](AcousticSequence& s) { s.initial_pose_sigma.setConstant(1e19); }), "sonar.json",
                              "initial_pose_sigma");
  EXPECT_NE(why.find("implausible"), std::string::npos) << why;
  With([](AcousticSequence& s) { s.initial_pose_sigma[3] = 1e19; });  // one entry only (the fuzzer's)
  ReadError(dir_.path(), "sonar.json", "initial_pose_sigma");
  With([](AcousticSequence& s) { s.sensor.range_sigma = 1e308; });
  ReadError(dir_.path(), "sonar.json", "sensor.range_sigma");
  With([](AcousticSequence& s) { s.sensor.range_sigma = 1e150; });
  ReadError(dir_.path(), "sonar.json", "sensor.range_sigma");
  With([](AcousticSequence& s) { s.sensor.azimuth_sigma = 2.0; });
  ReadError(dir_.path(), "sonar.json", "sensor.azimuth_sigma");
  With([](AcousticSequence& s) { s.motion_noise.translation_per_metre = 1e200; });
  ReadError(dir_.path(), "sonar.json", "motion_noise.translation_per_metre");
  With([](AcousticSequence& s) { s.initial_pose[0] = 1e12; });
  ReadError(dir_.path(), "sonar.json", "initial_pose");
  With([](AcousticSequence& s) {
    for (SonarControl& c : s.controls) c.u[5] = 1e308;
  });
  why = ReadError(dir_.path(), "controls.csv", "dyaw");
  EXPECT_NE(why.find("rad per step"), std::string::npos) << why;
  With([](AcousticSequence& s) { s.controls[2].u[0] = 5000; });
  ReadError(dir_.path(), "controls.csv", "dx");
  // The validator lists them too.
  EXPECT_FALSE(ValidateAcousticSequence(dir_.path()).empty());
}

// At the bounds the filter runs to the end (no crash, no numeric failure).
TEST_F(SonarPlausibility, ValuesAtTheBoundsRun) {
  With([](AcousticSequence& s) {
    s.initial_pose_sigma << 1000, 1000, 1000, 6.28, 6.28, 6.28;
    s.sensor.range_sigma = s.sensor.range_max - s.sensor.range_min;
    s.sensor.azimuth_sigma = s.sensor.azimuth_fov;
    s.motion_noise.translation_per_metre = 10;
    s.motion_noise.rotation_per_radian = 10;
    s.motion_noise.translation_floor = 100;
    s.motion_noise.rotation_floor = 6.28;
    for (SonarControl& c : s.controls) c.u << 1000, -1000, 1000, 6.28, -6.28, 6.28;
  });
  const AcousticSequence s = ReadAcousticSequence(dir_.path());
  NullProgress progress;
  SonarPipelineOptions o;
  o.smoother = true;
  try {
    const SonarPipelineResult r = RunSonarPipeline(s, dir_.path(), o, progress);
    EXPECT_EQ(r.run.steps.size(), static_cast<std::size_t>(s.num_steps()));
  } catch (const InputError& e) {
    // A numeric failure is allowed only as a clear error naming sonar.json.
    EXPECT_NE(std::string(e.what()).find("sonar.json"), std::string::npos) << e.what();
  }
}

// The fuzzer's and the inputs (tests/fuzz/regressions/sonar_*), put
// into the fuzz base sequence: refused by the reader, never run into the EKF.
TEST(SonarFuzzRegressions, InputsThatCrashedTheFilterAreRefused) {
  const std::string source = HI_SOURCE_DIR;
  const struct {
    const char* input;
    const char* file;
    const char* field;
  } cases[] = {{"sonar_json/initial-pose-sigma-1e19.json", "sonar.json", "initial_pose_sigma"},
               {"sonar_controls/dyaw-1e308.csv", "controls.csv", "dyaw"}};
  for (const auto& c : cases) {
    const ScratchDir dir("sonar_regression");
    std::filesystem::copy(source + "/tests/fuzz/base/sonar", dir.path(), std::filesystem::copy_options::recursive);
    std::filesystem::copy_file(source + "/tests/fuzz/regressions/" + c.input, dir / c.file,
                               std::filesystem::copy_options::overwrite_existing);
    ReadError(dir.path(), c.file, c.field);
  }
}

TEST(SonarNumerics, TheFiltersGuardsNameTheStep) {
  AcousticSequence s = SmallSequence();
  s.sensor.range_sigma = 1e200;  // past the reader's bounds, as an in-memory caller could
  SonarRunOptions o;
  try {
    RunSonarSequence(s, o);
    ADD_FAILURE() << "a range sigma of 1e200 ran";
  } catch (const SonarNumericalError& e) {
    EXPECT_GE(e.step(), 0);
    EXPECT_NE(std::string(e.what()).find("at step"), std::string::npos) << e.what();
  }
}

// The image chain on in-memory images that show nothing or only noise.
class SonarImageEvidence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { sim_ = new SonarImageSimulation(SimulateSonarImages(SonarImagePreset("prism", 1))); }
  static void TearDownTestSuite() { delete sim_; }
  static std::string Insufficient(const std::function<cv::Mat(int)>& image) {
    SonarPipelineOptions o;
    o.source = SonarFeatureSource::kImages;
    NullProgress progress;
    try {
      RunSonarPipeline(sim_->sequence, "", o, progress, image);
    } catch (const InsufficientData& e) {
      EXPECT_EQ(e.stage(), "sonar images");
      return e.what();
    }
    ADD_FAILURE() << "the images gave a result";
    return "";
  }
  static SonarImageSimulation* sim_;
};
SonarImageSimulation* SonarImageEvidence::sim_ = nullptr;

TEST_F(SonarImageEvidence, RenderedImagesGiveFeatures) {
  SonarPipelineOptions o;
  o.source = SonarFeatureSource::kImages;
  NullProgress progress;
  const SonarPipelineResult r = RunSonarPipeline(sim_->sequence, "", o, progress,
                                                 [](int k) { return sim_->images[static_cast<std::size_t>(k)]; });
  ASSERT_TRUE(r.images);
  EXPECT_GE(r.run.final_features.size(), 6u);
}

TEST_F(SonarImageEvidence, BlackWhiteAndNoiseImagesStop) {
  const cv::Mat& first = sim_->images.front();
  for (const double level : {0.0, 255.0}) {
    const std::string m = Insufficient([&](int) { return cv::Mat(first.size(), first.type(), cv::Scalar(level)); });
    EXPECT_NE(m.find("gave a detection"), std::string::npos) << m;
  }
  cv::RNG rng(5);
  const std::string m = Insufficient([&](int) {
    cv::Mat noise(first.size(), first.type());
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    return noise;
  });
  EXPECT_NE(m.find("noise or clutter"), std::string::npos) << m;
}

TEST(SonarEvidence, AnEmptyMeasurementsFileStops) {
  AcousticSequence s = SmallSequence();
  s.measurements.clear();
  const ScratchDir dir("sonar_empty");
  WriteAcousticSequence(s, dir.path());
  const AcousticSequence read = ReadAcousticSequence(dir.path());
  NullProgress progress;
  EXPECT_THROW(RunSonarPipeline(read, dir.path(), SonarPipelineOptions{}, progress), InsufficientData);
}

}  // namespace
}  // namespace hull
