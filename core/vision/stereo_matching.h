// Top <-> bottom matching of one keyframe under the calibrated rig's
// epipolar constraint (Ozog et al., 3.1): a bottom feature is a candidate
// for a top feature when it lies within epipolar_tolerance of the top
// feature's epipolar line (F from the rig: for a rectified rig with a
// baseline along y that is "the same column", along x "the same row") and
// triangulates between min_depth and max_depth; Lowe's ratio test among the
// candidates, then one-to-one (a bottom feature keeps its best top feature).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "survey/survey.h"
#include "vision/feature_detection.h"
#include "vision/vision_options.h"

namespace hull {

struct StereoMatch {
  int top = 0, bottom = 0;    // feature indices
  Eigen::Vector2d bottom_uv;  // the bottom feature's pixel
  Eigen::Vector3d p_top;      // triangulated point in the top camera frame (m)
  float distance = 0;         // descriptor distance
};

std::vector<StereoMatch> MatchStereo(const ImageFeatures& top, const ImageFeatures& bottom, const CameraRig& rig,
                                     const StereoOptions& options);

// The triangulated point (top camera frame) of a top/bottom pixel pair of
// the rig (linear DLT).
Eigen::Vector3d TriangulateStereo(const CameraRig& rig, const Eigen::Vector2d& top, const Eigen::Vector2d& bottom);

}  // namespace hull
