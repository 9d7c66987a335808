// The visual front end job (Ozog et al., section 3): a version 2 bundle's
// images -> SIFT features -> stereo matches -> nav-guided temporal matches
// with RANSAC -> tracks -> feature observations with global landmark ids in
// the version 1 features.csv contract, so the bundle adjustment reads them
// unchanged. Qt-free; Progress for progress and cancellation.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "base/progress.h"
#include "survey/survey.h"
#include "vision/front_end_evidence.h"
#include "vision/track_check.h"
#include "vision/track_refinement.h"
#include "vision/vision_options.h"

namespace hull {

// What RANSAC said of a match: an inlier, an outlier, or the match never
// took part in a RANSAC (a stereo match no temporal match used).
enum class MatchVerdict : std::uint8_t { kUnverified, kInlier, kOutlier };

// A top <-> bottom match of one keyframe (feature indices). Its verdict is
// that of its top feature in the temporal RANSACs (stereo: the rigid
// alignment checks the triangulated point): an inlier of any pair, else an
// outlier when it was a putative temporal match, else unverified.
struct FrontEndStereoLink {
  int top = 0, bottom = 0;
  MatchVerdict verdict = MatchVerdict::kUnverified;
};

// A putative temporal match (top feature indices in the pair's keyframes)
// and whether the pair's RANSAC kept it.
struct FrontEndMatch {
  int a = 0, b = 0;
  bool inlier = false;
};

struct FrontEndKeyframe {
  std::int64_t keyframe = 0;
  bool has_top = false, has_bottom = false;  // images present (missing: a dropped frame)
  int top_features = 0, bottom_features = 0;
  int stereo_matches = 0;
  int tracked = 0;  // observations written for this keyframe
  // The features and matches themselves (what the GUI's images view draws):
  // pixel positions (origin at the centre of the top-left pixel) and SIFT
  // sizes (diameter, px) of each image's features, the stereo matches, and
  // per top feature the landmark id of its track (-1: not in a track). A
  // track member's top point is where the refinement aligned it
  // (track_refinement.h; the observation written), others SIFT's.
  std::vector<Eigen::Vector2d> top_points, bottom_points;
  std::vector<float> top_sizes, bottom_sizes;
  std::vector<FrontEndStereoLink> stereo;
  std::vector<std::int64_t> landmark;
};

struct FrontEndPair {
  std::int64_t from = 0, to = 0;
  bool stereo = false;  // rigid alignment of clouds; else essential matrix
  bool loop = false;    // a loop closure (far apart in nav order); else neighbours in nav order
  double overlap = 0;   // loop: the predicted footprint overlap (loop_closure.h)
  double window = 0;    // px: the search window used (loops: grown with the nav drift)
  int putative = 0, inliers = 0;
  bool accepted = false;
  std::string note;                    // why a pair was dropped
  std::vector<FrontEndMatch> matches;  // the putative matches (size putative; `inliers` of them inliers)
  double InlierRatio() const { return putative > 0 ? static_cast<double>(inliers) / putative : 0.0; }
};

struct FrontEndResult {
  std::vector<FeatureObservation> features;  // sorted by keyframe (nav order), then landmark
  std::vector<FrontEndKeyframe> keyframes;   // nav order (features.keyframe -> index: KeyframeIndex)
  std::vector<FrontEndPair> pairs;           // the match graph
  int landmarks = 0;                         // tracks written (ids 0 .. landmarks-1)
  int refused_merges = 0;                    // links refused: would put two features of one image in a track
  int dropped_tracks = 0;                    // tracks seen in fewer than min_keyframes keyframes
  int duplicate_keypoints = 0;      // top features repeating another's position (SIFT: one per dominant orientation)
  int duplicate_tracks = 0;         // tracks repeating an earlier track's positions in every keyframe, dropped
  TrackRefinementStats refinement;  // the sub-pixel refinement of the tracks' top pixels
  // The DVL height check of mono tracks (track_check.h): every track
  // checked with its verdict; those not kept are not written.
  std::vector<TrackCheck> track_checks;
  int tracks_failed_check = 0;
  // Loop closures: keyframe pairs whose overlap was predicted, the pairs
  // tried (the candidates, in `pairs` with loop set) and accepted, and the
  // time spent on them (candidate search and matching, wall clock).
  std::size_t loop_pairs_considered = 0;
  int loop_pairs_tried = 0, loop_pairs_accepted = 0;
  double loop_seconds = 0;
  double seconds = 0;
  // What the images gave, per camera and in all (front_end_evidence.h).
  FrontEndEvidence evidence;

  // Index into `keyframes` of a keyframe id (-1: none).
  int KeyframeIndex(std::int64_t keyframe) const;
};

// Runs the front end on every image of a version 2 bundle (bundle.images).
// Throws InputError when the bundle has no images or an image is bad (the
// file named), InsufficientData when the images show too little for an
// inspection (front_end_evidence.h: a camera whose images give no
// features, stereo pairs that match nowhere or look swapped, too few
// tracks), OptionError for bad options, hull::Cancelled on cancel.
FrontEndResult RunFrontEnd(const SurveyBundle& bundle, const FrontEndOptions& options, Progress& progress);

// Runs the front end when a version 2 bundle has images and no feature
// observations, and puts its observations into the bundle. Returns whether
// it ran.
bool ExtractFeaturesIfNeeded(SurveyBundle& bundle, const FrontEndOptions& options, Progress& progress,
                             FrontEndResult* result = nullptr);

}  // namespace hull
