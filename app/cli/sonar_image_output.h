// hullinspect-cli sonar --from-images: the detections and the image chain's
// part of summary.json.
#pragma once

#include <string>

#include "base/json.h"
#include "sonar/sonar_image_runner.h"

namespace hull::cli {

// detections.csv: per step and detection its position (bins, beams; range,
// azimuth), strength, contrast and standard deviations, the feature it was
// paired with and how (in_state, waiting, new), and with truth its label.
void WriteSonarDetections(const SonarImageRunResult& r, const std::string& path);

// Counts, timings and, with truth, the evaluation (detection rate, wrong
// associations, final error of the features with truth).
Json SonarImageSummary(const SonarImageRunResult& r);

}  // namespace hull::cli
