#include "vision/front_end_evidence.h"

#include <algorithm>

#include "base/error.h"
#include "vision/front_end.h"

namespace hull {
namespace {

constexpr const char* kStage = "front end";

void Count(CameraEvidence& c, bool present, int features) {
  if (!present) return;
  ++c.images;
  c.images_with_features += features >= evidence::kMinImageFeatures;
  c.max_features = std::max(c.max_features, features);
}

void CheckCamera(const CameraEvidence& c, const char* name, const std::string& images_dir) {
  if (c.images == 0 || c.images_with_features > 0) return;
  throw InsufficientData(kStage,
                         std::string("the ") + name + " camera's images show nothing: none of its " +
                             std::to_string(c.images) + " images gave " + std::to_string(evidence::kMinImageFeatures) +
                             " features or more (the most " + std::to_string(c.max_features) +
                             "); blank, saturated or unlit images?",
                         images_dir);
}

}  // namespace

void CheckSwapEvidence(FrontEndEvidence& e, const std::vector<SwapProbe>& probes, const std::string& images_dir) {
  e.swap_probed = static_cast<int>(probes.size());
  e.swap_matched = 0;
  int as_named = 0;
  for (const SwapProbe& p : probes) {
    e.swap_matched += p.exchanged >= evidence::kMinStereoMatches && p.exchanged > 2 * p.as_named;
    as_named += p.as_named;
  }
  if (e.swap_probed == 0 || e.swap_matched * 2 <= e.swap_probed) return;
  throw InsufficientData(kStage,
                         "the top and bottom images appear swapped: " + std::to_string(e.swap_matched) + " of " +
                             std::to_string(e.swap_probed) +
                             " keyframes tried match more than twice as well with the cameras exchanged (" +
                             std::to_string(as_named) +
                             " stereo matches in all as named); check the cabling or the _top/_bottom file names",
                         images_dir);
}

FrontEndEvidence ImageEvidence(const FrontEndResult& r, bool stereo) {
  FrontEndEvidence e;
  for (const FrontEndKeyframe& k : r.keyframes) {
    Count(e.top, k.has_top, k.top_features);
    if (!stereo) continue;
    Count(e.bottom, k.has_bottom, k.bottom_features);
    if (k.has_top && k.has_bottom && std::min(k.top_features, k.bottom_features) >= evidence::kMinImageFeatures) {
      ++e.stereo_keyframes;
      e.stereo_matched += k.stereo_matches >= evidence::kMinStereoMatches;
    }
  }
  return e;
}

void CheckImageEvidence(const FrontEndEvidence& e, bool stereo, const std::string& images_dir) {
  CheckCamera(e.top, "top", images_dir);
  if (!stereo) return;
  CheckCamera(e.bottom, "bottom", images_dir);
  if (e.stereo_keyframes == 0 || e.stereo_matched >= evidence::kMinMatchedShare * e.stereo_keyframes) return;
  throw InsufficientData(kStage,
                         "the stereo pairs match nowhere: " + std::to_string(e.stereo_matched) + " of the " +
                             std::to_string(e.stereo_keyframes) +
                             " keyframes whose two images give features match with " +
                             std::to_string(evidence::kMinStereoMatches) +
                             " stereo matches or more (nor with the cameras exchanged); images of two different "
                             "scenes, noise, or a rig calibration (top_to_bottom) that does not fit the images?",
                         images_dir);
}

void CheckTrackEvidence(const FrontEndEvidence& e, const std::string& images_dir) {
  if (e.landmarks >= evidence::kMinLandmarks) return;
  throw InsufficientData(kStage,
                         "the images gave " + std::to_string(e.landmarks) + " tracks seen in two keyframes or more (" +
                             std::to_string(evidence::kMinLandmarks) + " needed): " + std::to_string(e.pairs_accepted) +
                             " of " + std::to_string(e.pairs) +
                             " keyframe pairs matched over time; noise, images without overlap, or a navigation "
                             "prior far off?",
                         images_dir);
}

}  // namespace hull
