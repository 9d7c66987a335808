// Sub-pixel refinement of feature tracks, and SIFT's duplicate keypoints.
//
// A track's members were each placed by SIFT on their own image's
// scale-space extremum. On the rendered mono survey two views of one point
// disagree by 0.2 px (median) but by more than 1.7 px for 1 % of the pairs;
// a two-view track seen along a 10 degree baseline turns 1 px at 1.6 m into
// about 2.5 cm of depth, and the highest such point over an object is its
// max (docs/vision.md, "Mono: the box's max and two-view depth noise").
// RefineTrackPixels aligns each member's patch with the track's reference
// patch (its first member in nav order; patch_alignment.h, translation,
// gain and bias, started from the prior's rotation warp), so the members'
// rays meet at the reference pixel's surface point.
//
// OpenCV's SIFT gives one keypoint per dominant orientation: about one in
// six of its keypoints repeats another's position in the same image. Each
// copy matches on its own, so one physical point made two tracks with the
// same pixels (counted twice by the adjustment and by the mapping's feature
// support). DuplicateKeypoints maps each copy to the first feature at its
// position; the front end drops a track that repeats an earlier one's
// positions in every keyframe.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "geometry/pose.h"
#include "survey/survey.h"
#include "vision/feature_tracks.h"
#include "vision/vision_options.h"

namespace hull {

// Per feature, the index of the first feature at exactly the same position
// (itself when it is the first).
std::vector<int> DuplicateKeypoints(const std::vector<Eigen::Vector2d>& points);

struct TrackRefinementStats {
  int members = 0;  // non-reference members tried
  int refined = 0;  // moved to the aligned pixel
  int kept = 0;     // kept the detector's pixel (no convergence, moved too far, low correlation, patch outside)
};

// Refines points[k][f] (top pixels per keyframe index) of every track's
// members other than its first (the reference) in place. image(k): the top
// image of keyframe index k (8- or 16-bit grey or colour), read twice at
// most per keyframe; cameras[k]: its prior pose (for the starting warp).
// Deterministic; threads as in the front end (0: all cores).
TrackRefinementStats RefineTrackPixels(const std::vector<TrackBuilder::Track>& tracks,
                                       const std::function<cv::Mat(std::size_t)>& image,
                                       const std::vector<Pose>& cameras, const PinholeIntrinsics& intrinsics,
                                       std::vector<std::vector<Eigen::Vector2d>>& points, const TrackOptions& options,
                                       int threads);

}  // namespace hull
