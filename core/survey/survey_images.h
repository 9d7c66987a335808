// The images/ folder of a version 2 survey bundle (../shared/survey-format.md,
// "Images"): listing it against nav.csv, checking every image, and reading
// one image with the bundle's requirements.
//
// The bundle model only lists paths (SurveyBundle::images); pixels are read
// when a consumer needs them (ReadSurveyImage), so opening a bundle stays
// cheap. The validator checks every image's contents.
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "base/error.h"
#include "image/image_file.h"
#include "survey/survey.h"

namespace hull {

// Lists <bundle>/images against the keyframes of nav.csv (`index`: keyframe
// id -> nav row; ids in `unreadable` had a bad nav.csv row already reported,
// so their images are skipped quietly). Appends to `problems`: an error per
// badly named image (padded or unknown keyframe id, a bottom image in a
// monocular survey, two images for one camera, another extension), a
// warning per other file and per dropped frame (the first 20 named, then a
// count). Returns the listing; `frames` follows `nav`.
SurveyImages ListSurveyImages(const std::string& bundle_dir, const SurveyManifest& manifest,
                              const std::vector<NavRecord>& nav, const std::unordered_set<std::int64_t>& unreadable,
                              std::vector<Problem>& problems);

// Reads every listed image (in parallel) and appends an error per image that
// is unreadable, truncated or corrupt, not camera.width x camera.height, or
// of another bit depth or channel count than the first good image. Returns
// the layout of the first good image (codec, size, depth, channels), or
// nothing when no image could be read.
std::optional<ImageInfo> CheckSurveyImages(const std::string& bundle_dir, const SurveyManifest& manifest,
                                           const SurveyImages& images, std::vector<Problem>& problems);

// The size every image of the bundle must have (camera.width x camera.height).
ImageRequirements SurveyImageRequirements(const SurveyManifest& manifest);

// Reads one keyframe's image with the bundle's size requirement (and
// `same_layout_as` when given, e.g. the first image read). Throws InputError
// naming the file, or naming the images folder when the keyframe has no
// such image.
cv::Mat ReadSurveyImage(const SurveyBundle& bundle, std::int64_t keyframe, bool bottom_camera,
                        const std::optional<ImageInfo>& same_layout_as = std::nullopt, ImageInfo* info = nullptr);

// File name of a keyframe's image in images/: "<keyframe>_top.png" etc.
std::string SurveyImageName(std::int64_t keyframe, bool bottom_camera, const std::string& extension = ".png");

}  // namespace hull
