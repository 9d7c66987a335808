// Height check of feature tracks without a stereo depth. A monocular track
// matched at the wrong point along the epipolar line triangulates exactly:
// no reprojection error reveals it (docs/vision.md, "Mono: wrong matches
// the rays cannot reveal"), and a third view along the same straight leg
// sees the same epipolar line. The DVL does: each keyframe's returns give
// the plane of the hull in front of its camera (loop_closure.h, DvlPlane).
// A track of few keyframes whose point, triangulated with the navigation
// prior, stands farther in front of every member's plane than any object on
// the hull does (or farther behind it, inside the hull) is dropped. Tracks
// seen in more keyframes, or with a stereo depth, are left to RANSAC and
// the adjustment.
#pragma once

#include <optional>
#include <vector>

#include "vision/feature_tracks.h"
#include "vision/loop_closure.h"
#include "vision/temporal_matching.h"
#include "vision/vision_options.h"

namespace hull {

// The verdict on one checked track.
struct TrackCheck {
  int track = 0;                                    // index into the tracks given
  TrackBuilder::Track members;                      // its (keyframe index, top feature) pairs
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // triangulated with the prior (g)
  // Its height in front of the members' DVL planes (m): the smallest and the
  // largest over the members with a plane (NaN: none has one).
  double min_height = 0, max_height = 0;
  // The largest reprojection error of the point in its members' images
  // with the prior poses (px; 0 for two keyframes, whose rays meet exactly).
  double max_reprojection = 0;
  bool kept = true;
};

// The verdict from a check's figures: dropped when the point stands more
// than check_max_height in front of every member's plane, or more than
// -check_min_height behind them, or (three or more keyframes) reprojects
// more than check_max_reprojection px from a member's feature while standing
// at least check_reprojection_height in front of every plane. Kept without a
// plane.
bool TrackCheckKeeps(const TrackCheck& check, const TrackOptions& options);

// Checks the tracks with at most options.check_max_keyframes keyframes none
// of whose features has a stereo match (has_stereo[k][f]). views: per
// keyframe index, the prior pose and top features; planes: per keyframe
// index, its DVL plane in the top camera frame (nullopt: none). Returns one
// TrackCheck per checked track whose point lies in front of its cameras.
// Deterministic (threads: as in the front end, 0: all cores).
std::vector<TrackCheck> CheckTrackHeights(const std::vector<TrackBuilder::Track>& tracks,
                                          const std::vector<KeyframeView>& views,
                                          const std::vector<std::vector<char>>& has_stereo,
                                          const std::vector<std::optional<CameraPlane>>& planes, const CameraRig& rig,
                                          const TrackOptions& options, int threads);

}  // namespace hull
