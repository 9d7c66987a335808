// Evidence before results (issue 23): what a survey's images gave the
// front end, per camera and in all, and the rules that stop a run whose
// images show too little to stand for an inspection. Images that are all
// black, all white or pure noise, or a stereo rig whose top and bottom
// images were swapped, used to run through to "0 objects detected" and a
// hull rated as inspected; now the front end stops with InsufficientData
// (hullinspect-cli exit 4), naming the camera, the figure and the likely
// cause.
//
// The rules, in the order they are checked (docs/reliability.md):
//  0. a stereo rig: the kSwapProbeKeyframes keyframes spread over the
//     survey are matched as they are and with the cameras exchanged before
//     anything else; when most match more than twice as well exchanged,
//     the images are named as swapped (a swapped rig still gives a few
//     wrong stereo matches, about a tenth of the right ones, and no track);
//  1. every camera: at least one image gives kMinImageFeatures features
//     (none: "blank, saturated or unlit images?");
//  2. a stereo rig: of the keyframes whose two images both give
//     kMinImageFeatures features, at least kMinMatchedShare match with
//     kMinStereoMatches stereo matches;
//  3. the tracks: at least kMinLandmarks landmarks seen in two or more
//     keyframes (none from noise: its features match nothing over time).
#pragma once

#include <string>
#include <vector>

#include "survey/survey.h"

namespace hull {

struct FrontEndResult;

namespace evidence {
constexpr int kMinImageFeatures = 20;     // features for an image to count as showing something
constexpr int kMinStereoMatches = 10;     // stereo matches for a keyframe to count as matched
constexpr double kMinMatchedShare = 0.1;  // share of stereo keyframes that must match
constexpr int kMinLandmarks = 10;         // tracks the whole survey must give
constexpr int kSwapProbeKeyframes = 5;    // keyframes also matched with the cameras exchanged
}  // namespace evidence

struct CameraEvidence {
  int images = 0;                // images of this camera the front end read
  int images_with_features = 0;  // of them, with at least kMinImageFeatures features
  int max_features = 0;          // the most features one image gave
};

struct FrontEndEvidence {
  CameraEvidence top, bottom;         // bottom: a stereo rig only
  int stereo_keyframes = 0;           // keyframes whose two images both give kMinImageFeatures features
  int stereo_matched = 0;             // of them, with at least kMinStereoMatches stereo matches
  int swap_probed = 0;                // keyframes matched again with the cameras exchanged (rule 2 failed)
  int swap_matched = 0;               // of them, matching more than twice as well so
  int pairs = 0, pairs_accepted = 0;  // temporal keyframe pairs tried and accepted by RANSAC
  int landmarks = 0;
};

// A keyframe's stereo matches as its images are named and with the
// cameras exchanged (the _bottom image's features matched as the top's).
struct SwapProbe {
  int as_named = 0, exchanged = 0;
};

// Rule 0 on the probed keyframes: fills the swap figures of `e` and throws
// InsufficientData naming `images_dir` when the images look swapped.
void CheckSwapEvidence(FrontEndEvidence& e, const std::vector<SwapProbe>& probes, const std::string& images_dir);

// The image and stereo figures of a front end's keyframes (rules 1 and 2
// need nothing else; the pairs and landmarks are filled once known).
FrontEndEvidence ImageEvidence(const FrontEndResult& r, bool stereo);

// Rules 1 and 2. Throws InsufficientData naming `images_dir`.
void CheckImageEvidence(const FrontEndEvidence& e, bool stereo, const std::string& images_dir);

// Rule 3 (after the tracks). Throws InsufficientData naming `images_dir`.
void CheckTrackEvidence(const FrontEndEvidence& e, const std::string& images_dir);

}  // namespace hull
