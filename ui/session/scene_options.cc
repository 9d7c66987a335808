#include "ui/session/scene_options.h"

namespace hull::ui {

const std::vector<SceneLayer>& AllSceneLayers() {
  static const std::vector<SceneLayer> layers = {SceneLayer::kHull,
                                                 SceneLayer::kTrajectory,
                                                 SceneLayer::kTrueTrajectory,
                                                 SceneLayer::kDvlHits,
                                                 SceneLayer::kLandmarks,
                                                 SceneLayer::kTruthObjects,
                                                 SceneLayer::kFrusta,
                                                 SceneLayer::kAdjustedTrajectory,
                                                 SceneLayer::kAdjustedDvlHits,
                                                 SceneLayer::kAdjustedLandmarks,
                                                 SceneLayer::kSlab,
                                                 SceneLayer::kHeatmap,
                                                 SceneLayer::kAlphaShapes,
                                                 SceneLayer::kDetectedObjects,
                                                 SceneLayer::kSigmaHeatmap,
                                                 SceneLayer::kSignificance,
                                                 SceneLayer::kHeightChange,
                                                 SceneLayer::kPhotomosaic};
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
    case SceneLayer::kAdjustedTrajectory:
      return QStringLiteral("adjusted_trajectory");
    case SceneLayer::kAdjustedDvlHits:
      return QStringLiteral("adjusted_dvl_hits");
    case SceneLayer::kAdjustedLandmarks:
      return QStringLiteral("adjusted_landmarks");
    case SceneLayer::kSlab:
      return QStringLiteral("slab");
    case SceneLayer::kHeatmap:
      return QStringLiteral("heatmap");
    case SceneLayer::kAlphaShapes:
      return QStringLiteral("alpha_shapes");
    case SceneLayer::kDetectedObjects:
      return QStringLiteral("detected_objects");
    case SceneLayer::kSigmaHeatmap:
      return QStringLiteral("sigma_heatmap");
    case SceneLayer::kSignificance:
      return QStringLiteral("significance");
    case SceneLayer::kHeightChange:
      return QStringLiteral("height_change");
    case SceneLayer::kPhotomosaic:
      return QStringLiteral("photomosaic");
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
      return QStringLiteral("DVL hits (initial poses)");
    case SceneLayer::kLandmarks:
      return QStringLiteral("Landmarks (truth or initial)");
    case SceneLayer::kTruthObjects:
      return QStringLiteral("True objects (outlines)");
    case SceneLayer::kFrusta:
      return QStringLiteral("Camera frusta");
    case SceneLayer::kAdjustedTrajectory:
      return QStringLiteral("Trajectory (adjusted)");
    case SceneLayer::kAdjustedDvlHits:
      return QStringLiteral("DVL hits (adjusted poses)");
    case SceneLayer::kAdjustedLandmarks:
      return QStringLiteral("Landmarks (adjusted)");
    case SceneLayer::kSlab:
      return QStringLiteral("Cross-section slab");
    case SceneLayer::kHeatmap:
      return QStringLiteral("Remeshed model (deviation)");
    case SceneLayer::kAlphaShapes:
      return QStringLiteral("Alpha shapes (per keyframe)");
    case SceneLayer::kDetectedObjects:
      return QStringLiteral("Detected objects (outlines)");
    case SceneLayer::kSigmaHeatmap:
      return QStringLiteral("Remeshed model (σ, uncertainty)");
    case SceneLayer::kSignificance:
      return QStringLiteral("Remeshed model (significant deviation)");
    case SceneLayer::kHeightChange:
      return QStringLiteral("Change between surveys (height)");
    case SceneLayer::kPhotomosaic:
      return QStringLiteral("Photomosaic (textured)");
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
  for (SceneLayer layer : AllSceneLayers()) {
    // The sigma and significance heatmaps cover the deviation heatmap: off
    // until asked for.
    v[layer] = layer != SceneLayer::kFrusta && layer != SceneLayer::kAlphaShapes &&
               layer != SceneLayer::kSigmaHeatmap && layer != SceneLayer::kSignificance;
  }
  return v;
}

bool SceneOptions::operator==(const SceneOptions& o) const {
  return visible == o.visible && hull_edges == o.hull_edges && colouring == o.colouring && auto_range == o.auto_range &&
         range_min == o.range_min && range_max == o.range_max && tolerance == o.tolerance &&
         frustum_stride == o.frustum_stride;
}

bool CameraState::operator==(const CameraState& o) const {
  return position == o.position && focal_point == o.focal_point && view_up == o.view_up && view_angle == o.view_angle;
}

}  // namespace hull::ui
