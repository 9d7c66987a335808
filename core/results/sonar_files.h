// The sonar results folder (docs/sonar.md, docs/results-format.md "Sonar
// results, version 1"), written by `hullinspect-cli sonar` and the GUI:
//   poses.csv       per step: pose estimate, standard deviations, the 21
//                   terms of its covariance, dead reckoning, the update's
//                   statistics and, with truth, errors and NEES
//   features.csv    per step (or the last step only) and feature: estimate,
//                   6 covariance terms, in the state or waiting, and its
//                   error against the truth
//   summary.json    format "hull-sonar-result": options, counts, timing, the
//                   final pose and, with truth, the errors; the image
//                   chain's and the smoother's parts when they ran
//   detections.csv  (features from the images) per step and detection
//   smoother_poses.csv, smoother_features.csv   (the smoother) its estimate
#pragma once

#include <string>
#include <vector>

#include "results/results_folder.h"
#include "sonar/sonar_pipeline_result.h"

namespace hull {

struct SonarWriteOptions {
  // features.csv holds the last step's features only.
  bool final_only = false;
};

// The files into `dir` (created when needed). Throws std::invalid_argument
// for a run without steps.
void WriteSonarResults(const SonarPipelineResult& result, const std::string& dir,
                       const SonarWriteOptions& options = {});
// The file names written for `result`.
std::vector<std::string> SonarFileNames(const SonarPipelineResult& result);
// `hullinspect-cli sonar`: the folder out.path replaced as a whole by the
// files and a manifest naming `run` (input: the sequence).
void SaveSonarResults(const SonarPipelineResult& result, const OutputFolder& out, ResultsRun run,
                      const SonarWriteOptions& options = {});

// Reads a sonar results folder back: the options, the filter's steps (pose,
// covariance, dead reckoning, statistics, errors with truth) and the
// features of every step written (the last one only after --final-only),
// the final features, the image chain's detections with their pairing and
// truth labels and its summary, the smoother's poses, features and
// summary. What the files do not hold stays empty (the EKF's predictions,
// the detections' full covariances: their standard deviations are kept).
// Throws InputError naming file, line and field, and when the files are
// not those of one run.
SonarPipelineResult ReadSonarResults(const std::string& dir);

// True when `dir` holds a sonar run's summary.json.
bool IsSonarResults(const std::string& dir);

}  // namespace hull
