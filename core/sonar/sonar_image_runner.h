// The whole acoustic-image chain over a sequence (version 2): per step the
// image is read, its point features detected (sonar_detector.h), associated
// with the EKF's prediction and the EKF corrected (sonar_tracker.h), through
// RunSonarSequence, so the per-step estimates, errors and NEES are those of
// the run with given correspondences.
//
// With truth (truth/poses.csv and truth/features.csv) every detection is
// labelled with the true feature whose true projection lies within
// truth_tolerance bins and beams of it (the nearest), and each estimated
// feature stands for the label most of its detections carry. A visible true
// feature (listed in measurements.csv at the step or, without it, in the
// field of view) is detected when a detection lies within the tolerance of
// its projection (true features closer than that, e.g. a vertical edge's two
// ends seen without roll, share one detection: the image cannot separate
// them); an association is wrong when the detection does not lie within the
// tolerance of the projection of the true feature its feature stands for
// (visible or not: a hidden vertex whose projection coincides with a visible
// one's is measured where it truly projects).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "base/progress.h"
#include "sonar/sonar_detector.h"
#include "sonar/sonar_runner.h"
#include "sonar/sonar_tracker.h"

namespace hull {

struct SonarImageRunOptions {
  // The filter and the run (ekf.confirm_views: 3, tentative features wait three views).
  SonarRunOptions run = [] {
    SonarRunOptions r;
    r.ekf.confirm_views = 3;
    return r;
  }();
  SonarDetectorOptions detector;
  SonarTrackerOptions tracker;
  // Truth labelling: the largest distance, in bins (range) and beams
  // (azimuth), between a detection and a true feature's projection.
  double truth_tolerance = 2.0;

  bool Check(std::string* why = nullptr) const;
};

struct SonarImageStep {
  std::vector<SonarDetection> detections;
  SonarTrackStep track;
  // With truth: per detection the nearest visible true feature within the
  // tolerance (-1: none) and every true feature, visible or not, within it;
  // the true features visible at the step and how many of them have a
  // detection within the tolerance.
  std::vector<std::int64_t> label;
  std::vector<std::vector<std::int64_t>> near;
  int visible = 0;
  int visible_detected = 0;
};

// Scores of the chain against the truth.
struct SonarImageEvaluation {
  int frames = 0;                  // steps with at least one visible feature
  double mean_detection_rate = 0;  // mean over those of detected / visible
  double min_detection_rate = 0;   // the worst frame
  int frames_below_90 = 0;         // frames with less than 90 % detected
  double clutter_per_frame = 0;    // detections on no true feature
  int associations = 0;            // detections paired with an existing feature (in the state or waiting)
  int wrong_associations = 0;      // of which on another true feature (or on none) than the feature stands for
  int in_state_associations = 0;   // the same for features in the state only
  int wrong_in_state_associations = 0;
  int final_features = 0;             // in the state at the end
  int final_features_with_truth = 0;  // of which stand for a true feature
  int duplicate_features = 0;         // of those, standing for a true feature another one already stands for
  double final_mean_error = 0;        // over the features with truth (m)
};

struct SonarImageRunResult {
  SonarRunResult run;
  std::vector<SonarImageStep> steps;
  std::map<std::int64_t, std::int64_t> truth_of;  // feature -> true feature (-1: none), with truth
  bool has_truth = false;
  SonarImageEvaluation evaluation;  // with truth
  double image_seconds = 0;         // reading the images
  double detect_seconds = 0;        // detection
  double track_seconds = 0;         // association and the EKF
};

// The comparison: the final mean error of a run with the given
// correspondences (measurements.csv of the same sequence) over the true
// features that the image run's final in-state features stand for.
struct SonarGivenComparison {
  int features = 0;        // image-run features with truth that the given run also has in its state
  double given_error = 0;  // the given run's mean final error over their true features (m)
};
SonarGivenComparison CompareWithGiven(const SonarImageRunResult& images, const SonarRunResult& given);

// Runs the chain with the images of step k from image_of_step(k). Throws
// OptionError when options.Check() fails, hull::Cancelled when the progress
// asks to stop, and whatever image_of_step throws.
SonarImageRunResult RunSonarImages(const AcousticSequence& seq, const std::function<cv::Mat(int)>& image_of_step,
                                   const SonarImageRunOptions& options = {}, Progress* progress = nullptr);
// The images of a sequence folder (images/<step>.png, InputError naming a bad one).
SonarImageRunResult RunSonarImages(const AcousticSequence& seq, const std::string& dir,
                                   const SonarImageRunOptions& options = {}, Progress* progress = nullptr);

}  // namespace hull
