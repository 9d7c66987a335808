// The visual front end job (Ozog et al., section 3): a version 2 bundle's
// images -> SIFT features -> stereo matches -> nav-guided temporal matches
// with RANSAC -> tracks -> feature observations with global landmark ids in
// the version 1 features.csv contract, so the bundle adjustment reads them
// unchanged. Qt-free; Progress for progress and cancellation.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/progress.h"
#include "survey/survey.h"
#include "vision/vision_options.h"

namespace hull {

struct FrontEndKeyframe {
  std::int64_t keyframe = 0;
  bool has_top = false, has_bottom = false;  // images present (missing: a dropped frame)
  int top_features = 0, bottom_features = 0;
  int stereo_matches = 0;
  int tracked = 0;  // observations written for this keyframe
};

struct FrontEndPair {
  std::int64_t from = 0, to = 0;
  bool stereo = false;  // rigid alignment of clouds; else essential matrix
  int putative = 0, inliers = 0;
  bool accepted = false;
  std::string note;  // why a pair was dropped
  double InlierRatio() const { return putative > 0 ? static_cast<double>(inliers) / putative : 0.0; }
};

struct FrontEndResult {
  std::vector<FeatureObservation> features;  // sorted by keyframe (nav order), then landmark
  std::vector<FrontEndKeyframe> keyframes;   // nav order
  std::vector<FrontEndPair> pairs;           // the match graph
  int landmarks = 0;                         // tracks written (ids 0 .. landmarks-1)
  int refused_merges = 0;                    // links refused: would put two features of one image in a track
  int dropped_tracks = 0;                    // tracks seen in fewer than min_keyframes keyframes
  double seconds = 0;
};

// Runs the front end on every image of a version 2 bundle (bundle.images).
// Throws InputError when the bundle has no images or an image is bad (the
// file named), OptionError for bad options, hull::Cancelled on cancel.
FrontEndResult RunFrontEnd(const SurveyBundle& bundle, const FrontEndOptions& options, Progress& progress);

// Writes `features_csv` (the version 1 features.csv) and, beside it,
// match-graph.csv (from,to,method,putative,inliers,accepted,note).
void WriteFrontEndResult(const FrontEndResult& result, const SurveyManifest& manifest, const std::string& features_csv);

// Runs the front end when a version 2 bundle has images and no feature
// observations, and puts its observations into the bundle. Returns whether
// it ran.
bool ExtractFeaturesIfNeeded(SurveyBundle& bundle, const FrontEndOptions& options, Progress& progress,
                             FrontEndResult* result = nullptr);

}  // namespace hull
