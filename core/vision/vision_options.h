// Options of the visual front end (Ozog et al., section 3): one struct per
// stage with defaults, a comment per field and Check() (throws OptionError
// naming the field). The same structs feed the CLI flags and the GUI panel.
#pragma once

namespace hull {

// SIFT on each image after contrast normalisation.
struct DetectionOptions {
  int max_features = 2000;           // SIFT keeps the strongest this many per image (0: all)
  double contrast_threshold = 0.03;  // SIFT contrast threshold (OpenCV's, per octave layer set)
  double edge_threshold = 10;        // SIFT edge-response threshold
  bool clahe = true;                 // CLAHE before SIFT (uneven strobe lighting)
  double clahe_clip = 3.0;           // CLAHE clip limit (contrast amplification cap)
  int clahe_tiles = 8;               // CLAHE grid: tiles x tiles regions
  // Larger images are detected at this longest side (px; 0: never), the
  // keypoints scaled back: SIFT needs about 240 bytes a pixel (it doubles
  // the image first), so a 16-megapixel image would take 4 GB. COLMAP's
  // max_image_size, 3200; the tracks are refined at full resolution.
  int max_image_size = 3200;
  void Check() const;
};

// Top <-> bottom matching under the calibrated rig's epipolar constraint.
struct StereoOptions {
  double epipolar_tolerance = 2.0;  // px: max distance of a bottom feature to the top feature's epipolar line
  double ratio = 0.8;               // Lowe's ratio: best / second-best descriptor distance among candidates
  double min_depth = 0.2;           // m: nearer triangulated points are refused
  double max_depth = 10.0;          // m: farther ones too (also bounds the search along the line)
  void Check() const;
};

// Keyframe <-> keyframe matching guided by the navigation prior, then RANSAC.
struct TemporalOptions {
  int neighbours = 2;                   // match each keyframe with this many following keyframes (nav order)
  double window = 40.0;                 // px: search radius around the predicted position (nav error)
  double ratio = 0.8;                   // Lowe's ratio among the candidates in the window
  double mono_min_depth = 0.3;          // m: mono search segment along the epipolar line starts here ...
  double mono_max_depth = 6.0;          // m: ... and ends here
  double ransac_threshold = 2.0;        // px: inlier reprojection error (stereo) / Sampson distance (mono)
  double ransac_confidence = 0.999;     // RANSAC success probability
  int ransac_max_iterations = 2000;     // RANSAC iterations at most (stereo)
  int min_inliers = 12;                 // a pair with fewer inliers is dropped
  double max_rotation_error_deg = 5;    // RANSAC motion vs the nav prior: rotation difference at most this
  double max_direction_error_deg = 25;  // mono: translation direction difference at most this
  double max_translation_error = 0.3;   // m, stereo: translation difference at most this
  void Check() const;
};

// Loop closures: keyframe pairs far apart in nav order (adjacent tracks of a
// lawnmower, revisits) whose footprints on the hull overlap under the
// navigation prior, matched like neighbours but with a search window and
// prior tolerances grown by the navigation drift between the two keyframes
// (survey.json noise: odometry rates times the time between them).
struct LoopOptions {
  bool enabled = true;             // look for loop closures at all
  int candidates = 3;              // each keyframe's this many best partners (by predicted overlap) are tried
  double min_overlap = 0.3;        // predicted footprint overlap (the smaller of both ways) at least this
  double min_path_ratio = 2.0;     // nav path between the two at least this x max(their distance, footprint radius)
  double max_view_angle_deg = 40;  // optical axes (under the prior) within this angle
  int footprint_points = 200;      // points of a keyframe's footprint used to predict the overlap
  double drift_sigmas = 1.0;       // window and tolerances grow by this many times the predicted drift
  double max_window = 200.0;       // px: the grown search window at most this
  int min_inliers = 20;            // a loop pair is accepted with at least this many RANSAC inliers
  void Check() const;
};

// Tracks across keyframes.
struct TrackOptions {
  int min_keyframes = 2;  // tracks seen in fewer keyframes are dropped
  // Height check of tracks without a stereo depth (track_check.h): a wrong
  // mono match along the epipolar line triangulates exactly, so its point
  // (triangulated with the navigation prior) is compared with the plane
  // through the DVL returns of its keyframes. A track of few keyframes whose
  // point stands farther in front of (or behind) the hull than anything on
  // it can is dropped.
  bool check_dvl_height = true;
  int check_max_keyframes = 3;     // mono tracks in at most this many keyframes are checked
  double check_max_height = 0.25;  // m: dropped when this far in front of every member's DVL plane (objects: <= 0.2)
  double check_min_height = -0.1;  // m: ... or this far behind it (inside the hull)
  // A checked track of three or more keyframes is not exact when one
  // observation is wrong (its rays meet pairwise at different points):
  double check_max_reprojection = 8.0;      // px: dropped when the point reprojects this far from a member's feature
  double check_reprojection_height = 0.05;  // m: ... and stands at least this far in front of the members' planes
  // Sub-pixel refinement of the tracks (track_refinement.h): each member's
  // patch aligned with its track's first member's (translation, gain, bias).
  bool refine = true;
  int refine_radius = 7;          // px: patch half-width (Gaussian weights, sigma = radius / 2)
  double refine_max_shift = 3.0;  // px: an alignment moving the feature farther keeps the detector's pixel
  double refine_min_ncc = 0.8;    // ... so does one whose patches correlate less (weighted NCC)
  void Check() const;
};

struct FrontEndOptions {
  DetectionOptions detection;
  StereoOptions stereo;
  TemporalOptions temporal;
  LoopOptions loops;
  TrackOptions tracks;
  int threads = 0;  // worker threads for detection and matching (0: all cores)
  void Check() const;
};

}  // namespace hull
