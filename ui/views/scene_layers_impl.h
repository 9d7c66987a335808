// The look of each layer of the 3-D scene (colours, point sizes, line
// widths) and small helpers for actors fed by a vtkPolyDataMapper. VTK side
// only: scene_view_impl.cc includes it.
#pragma once

#include <vtkActor.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>

#include "ui/session/scene_options.h"

namespace hull::ui {

// Sets the actor's property (and pickability) for the layer.
void StyleLayerActor(SceneLayer layer, vtkActor* actor);

inline vtkPolyDataMapper* MapperOf(vtkActor* actor) { return vtkPolyDataMapper::SafeDownCast(actor->GetMapper()); }

inline vtkPolyData* DataOf(vtkActor* actor) {
  vtkPolyDataMapper* mapper = MapperOf(actor);
  return mapper ? vtkPolyData::SafeDownCast(mapper->GetInput()) : nullptr;
}

inline void SetData(vtkActor* actor, vtkPolyData* data) { MapperOf(actor)->SetInputData(data); }

}  // namespace hull::ui
