// Matching between two keyframes guided by the navigation prior, then
// RANSAC (Ozog et al., 3.1):
// - stereo: each triangulated point of keyframe a is moved into keyframe b
//   with the prior relative pose and projected; candidates are b's stereo
//   features within `window` px; Lowe's ratio; then RANSAC over the rigid
//   alignment of the two triangulated clouds (3-point samples, AlignRigid,
//   inliers by reprojection error in both images);
// - mono (or a keyframe without a bottom image): the top feature's ray
//   between mono_min_depth and mono_max_depth projects to a segment of the
//   epipolar line in b; candidates within `window` px of that segment;
//   Lowe's ratio; then the 5-point essential matrix in RANSAC
//   (cv::findEssentialMat) and its motion (cv::recoverPose).
// Either motion is checked against the prior (rotation, and translation for
// stereo or its direction for mono); a pair that disagrees is dropped.
#pragma once

#include <string>
#include <vector>

#include "geometry/pose.h"
#include "survey/survey.h"
#include "vision/feature_detection.h"
#include "vision/stereo_matching.h"
#include "vision/vision_options.h"

namespace hull {

// What the temporal matcher needs of one keyframe.
struct KeyframeView {
  std::int64_t keyframe = 0;
  Pose x_g_cT;                      // top camera pose from the navigation prior
  ImageFeatures top;                // features of the top image
  std::vector<StereoMatch> stereo;  // empty for mono or without a bottom image
};

struct TemporalMatch {
  int a = 0, b = 0;  // top feature indices in keyframes a and b
  float distance = 0;
};

struct PairMatches {
  bool stereo = false;                 // which RANSAC ran (rigid clouds or essential matrix)
  int putative = 0;                    // matches after the ratio test
  int inliers = 0;                     // after RANSAC
  bool accepted = false;               // enough inliers and agrees with the prior
  std::string note;                    // why a pair was dropped
  Pose x_ca_cb;                        // estimated motion (mono: unit translation)
  std::vector<TemporalMatch> matches;  // RANSAC inliers (empty when not accepted)
  // Every putative match (after the ratio test and one-to-one) with its
  // RANSAC verdict (1: inlier); all 0 when RANSAC did not run (too few).
  std::vector<TemporalMatch> putative_matches;
  std::vector<char> putative_inlier;
};

// RANSAC's adaptive stop (Fischler and Bolles): the draws needed to have
// drawn one all-inlier sample of sample_size with the given confidence at
// this inlier ratio, at most max_draws; max_draws when the ratio is 0 (no
// information), 0 when it is 1.
int RansacDrawsNeeded(double inlier_ratio, int sample_size, double confidence, int max_draws);

PairMatches MatchKeyframes(const KeyframeView& a, const KeyframeView& b, const CameraRig& rig,
                           const TemporalOptions& options);

}  // namespace hull
