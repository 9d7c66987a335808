#include "vision/vision_options.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace hull {
namespace {

void Require(bool ok, const char* field, const std::string& why) {
  if (!ok) throw OptionError(field, why);
}

bool Positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

void DetectionOptions::Check() const {
  Require(max_features >= 0 && max_features <= 100000, "max_features", "must be between 0 (all) and 100000");
  Require(Positive(contrast_threshold) && contrast_threshold < 1, "contrast_threshold", "must be in (0, 1)");
  Require(Positive(edge_threshold), "edge_threshold", "must be positive");
  Require(Positive(clahe_clip), "clahe_clip", "must be positive");
  Require(clahe_tiles >= 1 && clahe_tiles <= 64, "clahe_tiles", "must be between 1 and 64");
  Require(max_image_size == 0 || (max_image_size >= 64 && max_image_size <= 100000), "max_image_size",
          "must be 0 (no limit) or between 64 and 100000 px");
}

void StereoOptions::Check() const {
  Require(Positive(epipolar_tolerance), "epipolar_tolerance", "must be positive (px)");
  Require(Positive(ratio) && ratio <= 1, "ratio", "must be in (0, 1]");
  Require(Positive(min_depth), "min_depth", "must be positive (m)");
  Require(Positive(max_depth) && max_depth > min_depth, "max_depth", "must be greater than min_depth (m)");
}

void TemporalOptions::Check() const {
  Require(neighbours >= 1 && neighbours <= 50, "neighbours", "must be between 1 and 50");
  Require(Positive(window), "window", "must be positive (px)");
  Require(Positive(ratio) && ratio <= 1, "ratio", "must be in (0, 1]");
  Require(Positive(mono_min_depth), "mono_min_depth", "must be positive (m)");
  Require(Positive(mono_max_depth) && mono_max_depth > mono_min_depth, "mono_max_depth",
          "must be greater than mono_min_depth (m)");
  Require(Positive(ransac_threshold), "ransac_threshold", "must be positive (px)");
  Require(Positive(ransac_confidence) && ransac_confidence < 1, "ransac_confidence", "must be in (0, 1)");
  Require(ransac_max_iterations >= 1, "ransac_max_iterations", "must be at least 1");
  Require(min_inliers >= 5, "min_inliers", "must be at least 5 (the essential matrix needs 5)");
  Require(Positive(max_rotation_error_deg) && max_rotation_error_deg <= 180, "max_rotation_error_deg",
          "must be in (0, 180] degrees");
  Require(Positive(max_direction_error_deg) && max_direction_error_deg <= 180, "max_direction_error_deg",
          "must be in (0, 180] degrees");
  Require(Positive(max_translation_error), "max_translation_error", "must be positive (m)");
}

void LoopOptions::Check() const {
  Require(candidates >= 1 && candidates <= 100, "loop_candidates", "must be between 1 and 100");
  Require(std::isfinite(min_overlap) && min_overlap > 0 && min_overlap <= 1, "loop_min_overlap", "must be in (0, 1]");
  Require(std::isfinite(min_path_ratio) && min_path_ratio >= 1, "loop_min_path_ratio", "must be at least 1");
  Require(Positive(max_view_angle_deg) && max_view_angle_deg <= 90, "loop_max_view_angle_deg",
          "must be in (0, 90] degrees");
  Require(footprint_points >= 10 && footprint_points <= 100000, "loop_footprint_points",
          "must be between 10 and 100000");
  Require(std::isfinite(drift_sigmas) && drift_sigmas >= 0, "loop_drift_sigmas", "must be >= 0");
  Require(Positive(max_window), "loop_max_window", "must be positive (px)");
  Require(min_inliers >= 5, "loop_min_inliers", "must be at least 5 (the essential matrix needs 5)");
}

void TrackOptions::Check() const {
  Require(min_keyframes >= 2, "min_keyframes", "must be at least 2");
  Require(check_max_keyframes >= 2, "track_check_max_keyframes", "must be at least 2");
  Require(check_max_height > 0, "track_check_max_height", "must be positive (m)");
  Require(check_min_height < 0, "track_check_min_height", "must be negative (m)");
  Require(check_max_reprojection > 0, "track_check_max_reprojection", "must be positive (px)");
  Require(std::isfinite(check_reprojection_height), "track_check_reprojection_height", "must be finite (m)");
  Require(refine_radius >= 2 && refine_radius <= 32, "refine_radius", "must be 2 to 32 (px)");
  Require(refine_max_shift > 0, "refine_max_shift", "must be positive (px)");
  Require(refine_min_ncc >= -1 && refine_min_ncc <= 1, "refine_min_ncc", "must be -1 to 1");
}

void FrontEndOptions::Check() const {
  detection.Check();
  stereo.Check();
  temporal.Check();
  loops.Check();
  tracks.Check();
  Require(threads >= 0, "threads", "must be >= 0 (0: all cores)");
}

}  // namespace hull
