// The sonar job, shaped like the optical pipeline (pipeline/pipeline.h): an
// acoustic sequence -> the EKF of Mai et al. from its given measurements or
// from its images (detection, association, tracking; sonar_image_runner.h)
// -> the batch smoother when asked (sonar_smoother_run.h) -> one
// SonarPipelineResult, which results/sonar_files.h writes and reads. The
// CLI's `sonar` and the GUI's sonar dock both run it, so the chain is wired
// once. `dir` may be empty for a sequence held in memory (a simulation)
// whose images image_of_step gives.
//
// Evidence before results (issue 23): a run whose inputs show nothing stops
// with InsufficientData (hullinspect-cli exit 4) instead of a result from
// nothing: a measurements.csv without a measurement; images that give no
// detection at all; a detector at its cap (max_detections) in most images,
// which real point returns never fill (noise or clutter); or no feature
// seen consistently enough to enter the filter.
#pragma once

#include <functional>
#include <opencv2/core/mat.hpp>
#include <string>

#include "base/progress.h"
#include "sonar/sonar_pipeline_result.h"
#include "survey/acoustic_sequence.h"

namespace hull {

enum class SonarFeatureSource {
  kAuto,          // measurements.csv when the sequence has it, else the images
  kMeasurements,  // given correspondences (measurements.csv)
  kImages,        // the acoustic images (version 2)
};

struct SonarPipelineOptions {
  SonarFeatureSource source = SonarFeatureSource::kAuto;
  // The filter from given measurements.
  SonarRunOptions run;
  // The image chain (images.run is the filter's from the images).
  SonarImageRunOptions images;
  // The batch smoother after the EKF.
  bool smoother = false;
  SonarSmootherOptions smoother_options;

  void Check() const;  // throws OptionError naming the field
};

namespace sonar_evidence {
constexpr double kMaxSaturatedShare = 0.5;  // share of images with the detector at its cap
}  // namespace sonar_evidence

// Runs the job on `seq`, read from the folder `dir` (the images from
// images/<step>.png there unless `image_of_step` gives them). Throws
// OptionError for bad options or a source the sequence cannot give (images
// of a version 1 sequence, measurements of a sequence without
// measurements.csv), InputError naming a bad image, InsufficientData as
// above, hull::Cancelled on cancel.
SonarPipelineResult RunSonarPipeline(const AcousticSequence& seq, const std::string& dir,
                                     const SonarPipelineOptions& options, Progress& progress,
                                     const std::function<cv::Mat(int)>& image_of_step = {});

// Whether the job reads the images (the source resolved against the sequence).
bool SonarFromImages(const AcousticSequence& seq, SonarFeatureSource source);

}  // namespace hull
