#include "ui/views/scene_layers_impl.h"

#include <vtkProperty.h>

namespace hull::ui {

namespace {

// Colours (RGB in [0, 1]).
constexpr double kHullGrey[3] = {0.56, 0.58, 0.61};
constexpr double kHullEdge[3] = {0.36, 0.37, 0.40};
constexpr double kTrajectoryOrange[3] = {1.0, 0.62, 0.12};
constexpr double kTruthMagenta[3] = {0.93, 0.35, 0.93};
constexpr double kDvlCyan[3] = {0.2, 0.85, 0.95};
constexpr double kObjectYellow[3] = {1.0, 0.92, 0.2};
constexpr double kFrustumWhite[3] = {0.85, 0.88, 0.9};
constexpr double kAdjustedWhite[3] = {0.97, 0.97, 0.97};
constexpr double kAdjustedDvlBlue[3] = {0.25, 0.45, 1.0};
constexpr double kSlabAmber[3] = {1.0, 0.78, 0.3};
constexpr double kShapeWhite[3] = {0.95, 0.95, 0.95};
constexpr double kDetectedMagenta[3] = {1.0, 0.25, 0.85};

void Colour(vtkProperty* p, const double (&rgb)[3]) { p->SetColor(rgb[0], rgb[1], rgb[2]); }

}  // namespace

void StyleLayerActor(SceneLayer layer, vtkActor* actor) {
  vtkProperty* p = actor->GetProperty();
  switch (layer) {
    case SceneLayer::kHull:
      Colour(p, kHullGrey);
      p->SetEdgeColor(kHullEdge[0], kHullEdge[1], kHullEdge[2]);
      p->SetInterpolationToFlat();
      p->SetAmbient(0.25);
      p->SetDiffuse(0.75);
      p->SetSpecular(0.0);
      actor->PickableOff();
      // Landmarks, DVL hits and outlines lie on the surface: push the
      // hull's polygons back in depth so that they stay visible.
      MapperOf(actor)->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 8.0);
      break;
    case SceneLayer::kTrajectory:
      Colour(p, kTrajectoryOrange);
      p->SetLineWidth(2.0);
      p->LightingOff();
      break;
    case SceneLayer::kTrueTrajectory:
      Colour(p, kTruthMagenta);
      p->SetLineWidth(2.0);
      p->LightingOff();
      break;
    case SceneLayer::kDvlHits:
      Colour(p, kDvlCyan);
      p->SetPointSize(3.0);
      p->LightingOff();
      actor->PickableOff();
      break;
    case SceneLayer::kLandmarks:
    case SceneLayer::kAdjustedLandmarks:
      p->SetPointSize(layer == SceneLayer::kLandmarks ? 4.0 : 5.0);
      p->LightingOff();
      break;
    case SceneLayer::kTruthObjects:
      Colour(p, kObjectYellow);
      p->SetLineWidth(2.0);
      p->LightingOff();
      break;
    case SceneLayer::kFrusta:
      Colour(p, kFrustumWhite);
      p->SetOpacity(0.7);
      p->LightingOff();
      actor->PickableOff();
      break;
    case SceneLayer::kAdjustedTrajectory:
      Colour(p, kAdjustedWhite);
      p->SetLineWidth(2.0);
      p->LightingOff();
      break;
    case SceneLayer::kAdjustedDvlHits:
      Colour(p, kAdjustedDvlBlue);
      p->SetPointSize(3.0);
      p->LightingOff();
      actor->PickableOff();
      break;
    case SceneLayer::kSlab:
      Colour(p, kSlabAmber);
      p->SetEdgeColor(kSlabAmber[0], kSlabAmber[1], kSlabAmber[2]);
      p->EdgeVisibilityOn();
      p->SetLineWidth(1.5);
      p->SetOpacity(0.22);
      p->LightingOff();
      actor->PickableOff();
      break;
    case SceneLayer::kHeatmap:
      p->SetInterpolationToGouraud();
      p->SetAmbient(0.35);
      p->SetDiffuse(0.7);
      p->SetSpecular(0.0);
      actor->PickableOff();
      MapperOf(actor)->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 8.0);
      break;
    case SceneLayer::kAlphaShapes:
      Colour(p, kShapeWhite);
      p->SetEdgeColor(0.3, 0.3, 0.3);
      p->EdgeVisibilityOn();
      p->SetOpacity(0.55);
      p->LightingOff();
      actor->PickableOff();
      break;
    case SceneLayer::kDetectedObjects:
      Colour(p, kDetectedMagenta);
      p->SetLineWidth(3.0);
      p->LightingOff();
      break;
  }
}

}  // namespace hull::ui
