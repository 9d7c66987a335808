#include "ui/scene_options.h"

namespace hull::ui {

const std::vector<SceneLayer>& AllSceneLayers() {
  static const std::vector<SceneLayer> layers = {
      SceneLayer::kHull,      SceneLayer::kTrajectory,   SceneLayer::kTrueTrajectory, SceneLayer::kDvlHits,
      SceneLayer::kLandmarks, SceneLayer::kTruthObjects, SceneLayer::kFrusta};
  return layers;
}

QString LayerKey(SceneLayer layer) {
  switch (layer) {
    case SceneLayer::kHull:
      return QStringLiteral("hull");
    case SceneLayer::kTrajectory:
      return QStringLiteral("trajectory");
    case SceneLayer::kTrueTrajectory:
      return QStringLiteral("true_trajectory");
    case SceneLayer::kDvlHits:
      return QStringLiteral("dvl_hits");
    case SceneLayer::kLandmarks:
      return QStringLiteral("landmarks");
    case SceneLayer::kTruthObjects:
      return QStringLiteral("truth_objects");
    case SceneLayer::kFrusta:
      return QStringLiteral("frusta");
  }
  return {};
}

QString LayerLabel(SceneLayer layer) {
  switch (layer) {
    case SceneLayer::kHull:
      return QStringLiteral("Hull model");
    case SceneLayer::kTrajectory:
      return QStringLiteral("Trajectory (initial navigation)");
    case SceneLayer::kTrueTrajectory:
      return QStringLiteral("True trajectory");
    case SceneLayer::kDvlHits:
      return QStringLiteral("DVL hits");
    case SceneLayer::kLandmarks:
      return QStringLiteral("Landmarks");
    case SceneLayer::kTruthObjects:
      return QStringLiteral("True objects (outlines)");
    case SceneLayer::kFrusta:
      return QStringLiteral("Camera frusta");
  }
  return {};
}

std::optional<SceneLayer> LayerFromKey(const QString& key) {
  for (SceneLayer layer : AllSceneLayers()) {
    if (LayerKey(layer) == key) return layer;
  }
  return std::nullopt;
}

QString ColouringKey(LandmarkColouring c) {
  return c == LandmarkColouring::kLabel ? QStringLiteral("label") : QStringLiteral("deviation");
}

std::optional<LandmarkColouring> ColouringFromKey(const QString& key) {
  if (key == QLatin1String("label")) return LandmarkColouring::kLabel;
  if (key == QLatin1String("deviation")) return LandmarkColouring::kDeviation;
  return std::nullopt;
}

bool SceneOptions::IsVisible(SceneLayer layer) const {
  auto it = visible.find(layer);
  return it != visible.end() && it->second;
}

std::map<SceneLayer, bool> SceneOptions::DefaultVisibility() {
  std::map<SceneLayer, bool> v;
  for (SceneLayer layer : AllSceneLayers()) v[layer] = layer != SceneLayer::kFrusta;
  return v;
}

bool SceneOptions::operator==(const SceneOptions& o) const {
  return visible == o.visible && hull_edges == o.hull_edges && colouring == o.colouring && auto_range == o.auto_range &&
         range_min == o.range_min && range_max == o.range_max && frustum_stride == o.frustum_stride;
}

bool CameraState::operator==(const CameraState& o) const {
  return position == o.position && focal_point == o.focal_point && view_up == o.view_up && view_angle == o.view_angle;
}

}  // namespace hull::ui
