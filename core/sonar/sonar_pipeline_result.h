// What a sonar run over an acoustic sequence produced, as a whole: the
// EKF's per-step estimates (from the given measurements or from the images),
// the image chain's detections and tracks when the features came from the
// images, and the batch smoother's estimate when it ran. Written and read
// as a results folder by results/sonar_files.h (the CLI's `sonar`, the GUI).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sonar/sonar_image_runner.h"
#include "sonar/sonar_runner.h"
#include "sonar/sonar_smoother_run.h"

namespace hull {

struct SonarPipelineResult {
  std::string sequence;  // the sequence folder (absolute)
  // Features from the images (images) or from measurements.csv.
  bool from_images = false;
  // The options the filter ran with (from images: the image chain's), and
  // the image chain's and the smoother's when they ran.
  SonarRunOptions options;
  SonarImageRunOptions image_options;
  SonarSmootherOptions smoother_options;
  std::int64_t measurements = 0;  // rows of the sequence's measurements.csv (0 without one)
  // The filter's run (from images: images->run).
  SonarRunResult run;
  std::optional<SonarImageRunResult> images;
  std::optional<SonarSmootherRun> smoother;
};

}  // namespace hull
