#include "sonar/sonar_pipeline.h"

#include <algorithm>
#include <filesystem>

#include "base/csv.h"
#include "base/error.h"
#include "survey/sonar_image.h"

namespace hull {
namespace fs = std::filesystem;

namespace {

void ThrowUnlessValid(bool ok, const std::string& why) {
  if (ok) return;
  const auto colon = why.find(':');
  if (colon == std::string::npos) throw OptionError("sonar", why);
  throw OptionError(why.substr(0, colon), why.substr(std::min(why.size(), colon + 2)));
}

// The image chain's evidence: detections at all, a detector that is not at
// its cap in most images, and a feature in the filter at the end.
void CheckImageEvidence(const SonarImageRunResult& r, const SonarImageRunOptions& o, const std::string& dir) {
  const std::string images = (fs::path(dir) / "images").string();
  std::size_t detections = 0;
  int saturated = 0;
  for (const SonarImageStep& s : r.steps) {
    detections += s.detections.size();
    saturated += static_cast<int>(s.detections.size()) >= o.detector.max_detections;
  }
  const int frames = static_cast<int>(r.steps.size());
  if (detections == 0) {
    throw InsufficientData("sonar images",
                           "none of the " + std::to_string(frames) + " images gave a detection (" +
                               FormatDouble(o.detector.min_contrast) +
                               " grey levels above the background needed): blank or saturated images, or a gain "
                               "too low?",
                           images);
  }
  if (saturated > sonar_evidence::kMaxSaturatedShare * frames) {
    throw InsufficientData("sonar images",
                           "the detector reached its cap of " + std::to_string(o.detector.max_detections) +
                               " detections in " + std::to_string(saturated) + " of " + std::to_string(frames) +
                               " images: they look like noise or clutter, not point returns (a higher "
                               "--min-contrast?)",
                           images);
  }
  int in_state = 0;
  for (const SonarFeatureEstimate& f : r.run.final_features) in_state += f.in_state;
  if (in_state == 0) {
    throw InsufficientData("sonar images",
                           "no feature was seen consistently enough to enter the filter (" +
                               std::to_string(detections) + " detections over " + std::to_string(frames) + " images, " +
                               std::to_string(o.run.ekf.confirm_views) + " views needed)",
                           images);
  }
}

}  // namespace

void SonarPipelineOptions::Check() const {
  std::string why;
  ThrowUnlessValid(run.Check(&why), why);
  ThrowUnlessValid(images.Check(&why), why);
  if (smoother) ThrowUnlessValid(smoother_options.Check(&why), why);
}

bool SonarFromImages(const AcousticSequence& seq, SonarFeatureSource source) {
  if (source == SonarFeatureSource::kAuto) return !seq.has_measurements;
  return source == SonarFeatureSource::kImages;
}

namespace {

// The filter from the measurements or the images into result.
void RunFilter(const AcousticSequence& seq, const std::string& dir, const SonarPipelineOptions& o,
               const std::function<cv::Mat(int)>& image_of_step, Progress& progress, SonarPipelineResult& result) {
  if (result.from_images) {
    const SonarImageFormat format = *seq.image;
    const std::function<cv::Mat(int)> read =
        image_of_step ? image_of_step : [&](int k) { return ReadSonarImage(SonarImagePath(dir, k), format); };
    result.images = RunSonarImages(seq, read, o.images, &progress);
    CheckImageEvidence(*result.images, o.images, dir);
    result.options = o.images.run;
    result.run = result.images->run;
  } else {
    result.options = o.run;
    result.run = RunSonarSequence(seq, o.run, &progress);
  }
}

}  // namespace

SonarPipelineResult RunSonarPipeline(const AcousticSequence& seq, const std::string& dir, const SonarPipelineOptions& o,
                                     Progress& progress, const std::function<cv::Mat(int)>& image_of_step) {
  o.Check();
  SonarPipelineResult result;
  if (!dir.empty()) result.sequence = fs::absolute(dir).lexically_normal().string();
  result.from_images = SonarFromImages(seq, o.source);
  if (result.from_images && !seq.image) {
    throw OptionError("source", "'" + dir + "' has no images (a version 1 sequence)");
  }
  if (!result.from_images && !seq.has_measurements) {
    throw OptionError("source", "'" + dir + "' has no measurements.csv; its features can only come from its images");
  }
  if (!result.from_images && seq.measurements.empty()) {
    throw InsufficientData("sonar", "measurements.csv holds no measurement: nothing was seen",
                           (fs::path(dir) / "measurements.csv").string());
  }
  result.image_options = o.images;
  result.smoother_options = o.smoother_options;
  result.measurements = static_cast<std::int64_t>(seq.measurements.size());
  const double filter_share = o.smoother ? 0.7 : 1.0;
  try {
    SubProgress p(progress, 0.0, filter_share);
    RunFilter(seq, dir, o, image_of_step, p, result);
  } catch (const SonarNumericalError& e) {
    throw InputError({(fs::path(dir) / "sonar.json").string(), 0, 0, "sensor, initial_pose_sigma, motion_noise"},
                     std::string(e.what()) +
                         ": the sequence's noise figures or controls (controls.csv) are beyond what the filter's "
                         "arithmetic can carry");
  }
  if (o.smoother) {
    progress.Update(filter_share, "running the batch smoother");
    SubProgress p(progress, filter_share, 1.0);
    const std::optional<SonarImageRunResult>& images = result.images;
    result.smoother = RunSonarSmoother(seq, result.run, images ? AssociatedMeasurements(*images) : seq.measurements,
                                       o.smoother_options, images ? &images->truth_of : nullptr, &p);
  }
  progress.Update(1.0, "sonar done");
  return result;
}

}  // namespace hull
