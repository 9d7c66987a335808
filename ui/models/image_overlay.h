// What the images view draws over one keyframe's camera image (Ozog et al.'s
// keyframe figure on real pixels): the image's SIFT features, its stereo
// matches (top <-> bottom), its temporal matches with the previous keyframe
// that has an image, each with RANSAC's verdict, and after an adjustment the
// reprojections of the adjusted landmarks with their residual vectors, plus
// the counts for the legend. Derived from the Session's survey, front-end
// result and adjustment; Qt-free.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "adjust/adjust_result.h"
#include "survey/survey.h"
#include "vision/front_end.h"

namespace hull::ui {

struct OverlayFeature {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  float size = 0;        // SIFT diameter (px); 0 when unknown (features.csv)
  bool tracked = false;  // in a track (a landmark of the adjustment's input)
};

// A match as a line in the shown image: from its feature to where the
// matched feature lies in the other image (stereo: the other camera of the
// keyframe; temporal: the previous keyframe's top image).
struct OverlayMatch {
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  MatchVerdict verdict = MatchVerdict::kUnverified;
};

struct OverlayReprojection {
  std::int64_t landmark = 0;
  Eigen::Vector2d observed = Eigen::Vector2d::Zero();   // the feature's pixel
  Eigen::Vector2d projected = Eigen::Vector2d::Zero();  // the adjusted landmark seen from the adjusted pose
  int label = 1;                                        // lambda: 1 on the hull, 0 foreign
};

struct ImageOverlay {
  int index = -1;  // nav row
  std::int64_t keyframe = 0;
  bool bottom = false;       // the bottom camera's image
  bool has_image = false;    // the bundle has that image (else a dropped frame)
  bool from_images = false;  // features and matches from the front end (else from features.csv)
  std::vector<OverlayFeature> features;
  std::vector<OverlayMatch> stereo;
  std::int64_t previous_keyframe = -1;  // of the temporal matches (-1: none)
  bool previous_pair_accepted = false;
  std::vector<OverlayMatch> temporal;  // top image only
  std::vector<OverlayReprojection> reprojections;
  double rms_residual = 0;  // px, over the reprojections

  int tracked = 0;
  int stereo_inliers = 0, stereo_outliers = 0, stereo_unverified = 0;
  int temporal_inliers = 0, temporal_outliers = 0;
};

// The overlay of nav row `index` (top or bottom camera). `front_end` and
// `adjustment` may be null: then only the observations of features.csv (all
// tracked) and no matches or reprojections.
ImageOverlay ComputeImageOverlay(const SurveyBundle& bundle, const FrontEndResult* front_end,
                                 const AdjustmentResult* adjustment, int index, bool bottom);

}  // namespace hull::ui
