#include "ui/views/scene_layers_impl.h"

#include <vtkColorTransferFunction.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkTextProperty.h>

#include <array>

#include "base/deviation_colours.h"

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

// 256 colours sampled from a transfer function over [0, 1]; NaN grey.
vtkSmartPointer<vtkLookupTable> SampledLut(vtkColorTransferFunction* ctf) {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  lut->SetNumberOfTableValues(256);
  for (int i = 0; i < 256; ++i) {
    double rgb[3];
    ctf->GetColor(i / 255.0, rgb);
    lut->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
  lut->SetNanColor(0.45, 0.46, 0.48, 1.0);
  lut->Build();
  return lut;
}

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
      // Pickable: a click on the CAD reads where it is (PickSurface).
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
    case SceneLayer::kSigmaHeatmap:
    case SceneLayer::kSignificance:
    case SceneLayer::kHeightChange:
      p->SetInterpolationToGouraud();
      p->SetAmbient(0.35);
      p->SetDiffuse(0.7);
      p->SetSpecular(0.0);
      // Pickable: a click reads the vertex's values (PickSurface).
      // All draw the same surface: the deviation heatmap furthest back, so
      // that a sigma, significance or change layer switched on with it wins
      // (and points and lines on the surface stay in front of them all).
      if (layer == SceneLayer::kHeatmap) {
        MapperOf(actor)->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 8.0);
      } else if (layer == SceneLayer::kHeightChange) {
        MapperOf(actor)->SetRelativeCoincidentTopologyPolygonOffsetParameters(1.0, 2.0);
      } else {
        MapperOf(actor)->SetRelativeCoincidentTopologyPolygonOffsetParameters(1.5, 5.0);
      }
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
    case SceneLayer::kPhotomosaic:
      // The atlas holds the hull's albedo: mostly ambient, so that the
      // texture keeps its colours, with some diffuse light for the shape.
      Colour(p, kShapeWhite);
      p->SetInterpolationToGouraud();
      p->SetAmbient(0.6);
      p->SetDiffuse(0.45);
      p->SetSpecular(0.0);
      actor->PickableOff();
      // The same surface as the heatmaps: drawn in front of them all.
      MapperOf(actor)->SetRelativeCoincidentTopologyPolygonOffsetParameters(0.5, 1.0);
      break;
  }
}

vtkSmartPointer<vtkColorTransferFunction> MakeDivergingCtf() {
  auto ctf = vtkSmartPointer<vtkColorTransferFunction>::New();
  ctf->SetColorSpaceToRGB();
  // The report's and the glTF export's map (base/deviation_colours.h) at
  // 65 stops: the 256 entries differ from it by under 1/255.
  for (int i = 0; i <= 64; ++i) {
    const std::array<double, 3> rgb = DivergingRgb(i / 32.0 - 1);
    ctf->AddRGBPoint(i / 64.0, rgb[0], rgb[1], rgb[2]);
  }
  return ctf;
}

vtkSmartPointer<vtkLookupTable> MakeDivergingLut() { return SampledLut(MakeDivergingCtf()); }

void ShapeDeviationLut(vtkLookupTable* lut, vtkColorTransferFunction* ctf, double lo, double hi, double tolerance,
                       bool mark_out_of_range) {
  hi = std::max(hi, lo + 1e-6);
  lut->SetTableRange(lo, hi);
  // Entry i stands for x_i = lo + i (hi - lo) / 255 (its colour; over a
  // symmetric range exactly SampledLut's) and covers the values around
  // its centre; zero is white however asymmetric the range.
  const double m = std::max(std::abs(lo), std::abs(hi));
  const int n = lut->GetNumberOfTableValues();
  for (int i = 0; i < n; ++i) {
    const double u = i / static_cast<double>(n - 1);
    const double centre = lo + (i + 0.5) * (hi - lo) / n;
    double rgb[3];
    if (tolerance > 0 && std::abs(centre) <= tolerance) {
      rgb[0] = kWithinTolerance[0], rgb[1] = kWithinTolerance[1], rgb[2] = kWithinTolerance[2];
    } else {
      ctf->GetColor(0.5 * (1.0 + (lo + u * (hi - lo)) / m), rgb);
    }
    lut->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
  lut->SetUseAboveRangeColor(mark_out_of_range);
  lut->SetUseBelowRangeColor(mark_out_of_range);
  lut->SetAboveRangeColor(kAboveRange[0], kAboveRange[1], kAboveRange[2], 1.0);
  lut->SetBelowRangeColor(kBelowRange[0], kBelowRange[1], kBelowRange[2], 1.0);
  lut->Build();
}

vtkSmartPointer<vtkLookupTable> MakeSequentialLut() {
  // Viridis at nine stops, interpolated in RGB.
  static const double stops[9][3] = {{0.267, 0.005, 0.329}, {0.278, 0.175, 0.483}, {0.230, 0.322, 0.546},
                                     {0.173, 0.449, 0.558}, {0.128, 0.567, 0.551}, {0.153, 0.680, 0.504},
                                     {0.361, 0.785, 0.388}, {0.668, 0.862, 0.196}, {0.993, 0.906, 0.144}};
  vtkNew<vtkColorTransferFunction> ctf;
  ctf->SetColorSpaceToRGB();
  for (int i = 0; i < 9; ++i) ctf->AddRGBPoint(i / 8.0, stops[i][0], stops[i][1], stops[i][2]);
  return SampledLut(ctf);
}

vtkSmartPointer<vtkScalarBarActor> MakeLegend(vtkLookupTable* lut, const char* title, const char* label_format) {
  auto legend = vtkSmartPointer<vtkScalarBarActor>::New();
  legend->SetLookupTable(lut);
  legend->SetTitle(title);
  legend->SetNumberOfLabels(5);
  legend->SetLabelFormat(label_format);
  legend->SetMaximumWidthInPixels(110);
  legend->GetPositionCoordinate()->SetValue(0.85, 0.05);
  legend->SetWidth(0.13);
  legend->SetHeight(0.6);
  legend->UnconstrainedFontSizeOn();
  legend->SetVerticalTitleSeparation(6);
  legend->GetTitleTextProperty()->SetFontSize(14);
  legend->GetLabelTextProperty()->SetFontSize(12);
  legend->GetTitleTextProperty()->ItalicOff();
  legend->GetTitleTextProperty()->ShadowOff();
  legend->GetLabelTextProperty()->ItalicOff();
  legend->GetLabelTextProperty()->ShadowOff();
  legend->GetAnnotationTextProperty()->SetFontSize(12);
  legend->GetAnnotationTextProperty()->ItalicOff();
  legend->GetAnnotationTextProperty()->ShadowOff();
  // White text on a dark panel: readable over a light model (zero deviation
  // is near-white) as over the dark water.
  legend->DrawBackgroundOn();
  legend->GetBackgroundProperty()->SetColor(kOverlayPanel[0], kOverlayPanel[1], kOverlayPanel[2]);
  legend->GetBackgroundProperty()->SetOpacity(kOverlayPanelOpacity);
  // The title and the NaN annotation may reach beyond the panel: their own backing.
  for (vtkTextProperty* t : {legend->GetTitleTextProperty(), legend->GetAnnotationTextProperty()}) {
    t->SetBackgroundColor(kOverlayPanel[0], kOverlayPanel[1], kOverlayPanel[2]);
    t->SetBackgroundOpacity(kOverlayPanelOpacity);
  }
  legend->VisibilityOff();
  return legend;
}

void StyleOverlayText(vtkTextProperty* text, int font_size) {
  text->SetFontSize(font_size);
  text->SetColor(1.0, 1.0, 1.0);
  text->BoldOff();
  text->ItalicOff();
  text->ShadowOff();
  text->SetBackgroundColor(kOverlayPanel[0], kOverlayPanel[1], kOverlayPanel[2]);
  text->SetBackgroundOpacity(kOverlayPanelOpacity);
}

vtkSmartPointer<vtkActor2D> OverlayActor2D(vtkPolyData* data) {
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor2D>::New();
  actor->SetMapper(mapper);
  actor->PickableOff();
  return actor;
}

void ColourByArray(vtkPolyDataMapper* mapper, const char* array, vtkLookupTable* lut) {
  mapper->ScalarVisibilityOn();
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray(array);
  mapper->SetColorModeToMapScalars();
  mapper->SetLookupTable(lut);
  mapper->UseLookupTableScalarRangeOn();
  mapper->Modified();
}

}  // namespace hull::ui
