#include "survey/survey.h"

#include <filesystem>
#include <unordered_set>

namespace hull {

const char* ObjectKindName(ObjectKind k) {
  switch (k) {
    case ObjectKind::kCylinder:
      return "cylinder";
    case ObjectKind::kBox:
      return "box";
    case ObjectKind::kPatch:
      return "patch";
  }
  return "?";
}

std::unordered_map<std::int64_t, int> SurveyBundle::KeyframeIndex() const {
  std::unordered_map<std::int64_t, int> index;
  index.reserve(nav.size());
  for (int i = 0; i < static_cast<int>(nav.size()); ++i) index.emplace(nav[i].keyframe, i);
  return index;
}

void SurveyBundle::AdoptImageFeatureTracks(std::vector<FeatureObservation> tracks) {
  features = std::move(tracks);
  features_from_images = true;
  landmarks.reset();
  if (truth) truth->landmarks.clear();
}

std::string SurveyBundle::ModelHintPath() const {
  if (!manifest.model_hint) return "";
  std::filesystem::path p(*manifest.model_hint);
  if (p.is_absolute() || directory.empty()) return p.string();
  return (std::filesystem::path(directory) / p).string();
}

std::string SurveyBundle::ImagePath(std::int64_t keyframe, bool bottom_camera) const {
  if (!images) return "";
  for (const KeyframeImages& f : images->frames) {
    if (f.keyframe != keyframe) continue;
    const std::string& rel = bottom_camera ? f.bottom : f.top;
    if (rel.empty()) return "";
    return directory.empty() ? rel : (std::filesystem::path(directory) / rel).string();
  }
  return "";
}

std::size_t SurveyBundle::CountLandmarks() const {
  std::unordered_set<std::int64_t> ids;
  for (const auto& f : features) ids.insert(f.landmark);
  return ids.size();
}

}  // namespace hull
