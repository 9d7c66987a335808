// The look of each layer of the 3-D scene (colours, point sizes, line
// widths) and small helpers for actors fed by a vtkPolyDataMapper. VTK side
// only: scene_view_impl.cc includes it.
#pragma once

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkColorTransferFunction.h>
#include <vtkLookupTable.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextProperty.h>

#include "ui/session/scene_options.h"

namespace hull::ui {

// Sets the actor's property (and pickability) for the layer.
void StyleLayerActor(SceneLayer layer, vtkActor* actor);

// The deviation map of the report and the glTF export (ColorBrewer RdBu,
// base/deviation_colours.h; 256 entries; NaN: mid grey).
vtkSmartPointer<vtkLookupTable> MakeDivergingLut();
vtkSmartPointer<vtkColorTransferFunction> MakeDivergingCtf();  // the same map over [0, 1]

// Fills the deviation table for [lo, hi] from ctf (MakeDivergingCtf): zero
// white and the colours symmetric about it whatever the range (a manual
// range of -0.05..0.15 shows pale blue to dark red, not a shifted map);
// tolerance > 0: the entries within +-tolerance in kWithinTolerance
// (scene_options.h);
// mark_out_of_range: values below lo and above hi in kBelowRange and
// kAboveRange instead of the end colours.
void ShapeDeviationLut(vtkLookupTable* lut, vtkColorTransferFunction* ctf, double lo, double hi, double tolerance,
                       bool mark_out_of_range);
// A perceptually uniform sequential map (viridis, 256 entries).
vtkSmartPointer<vtkLookupTable> MakeSequentialLut();
// The dark, translucent backing of everything written over the scene (the
// legends, the histogram's note, the scale bar's and the axes' labels):
// white text on it reads over a light model as over the dark water.
constexpr double kOverlayPanel[3] = {0.06, 0.09, 0.13};
constexpr double kOverlayPanelOpacity = 0.72;
// White text of `font_size` on that backing, plain (no bold, italic, shadow).
void StyleOverlayText(vtkTextProperty* text, int font_size);
// An unpickable 2-D actor drawing `data` in viewport pixels.
vtkSmartPointer<vtkActor2D> OverlayActor2D(vtkPolyData* data);

// A colour legend (hidden) in the scene's style for a lookup table.
vtkSmartPointer<vtkScalarBarActor> MakeLegend(vtkLookupTable* lut, const char* title, const char* label_format);

// The mapper colours its input by the named point array through the table.
void ColourByArray(vtkPolyDataMapper* mapper, const char* array, vtkLookupTable* lut);

inline vtkPolyDataMapper* MapperOf(vtkActor* actor) { return vtkPolyDataMapper::SafeDownCast(actor->GetMapper()); }

inline vtkPolyData* DataOf(vtkActor* actor) {
  vtkPolyDataMapper* mapper = MapperOf(actor);
  return mapper ? vtkPolyData::SafeDownCast(mapper->GetInput()) : nullptr;
}

inline void SetData(vtkActor* actor, vtkPolyData* data) { MapperOf(actor)->SetInputData(data); }

}  // namespace hull::ui
