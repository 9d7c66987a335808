// The deviation histogram drawn beside the colour legend (issue 25.2): one
// bar per band of the legend's range, in the band's colour, its length the
// log of the vertex count (the hull's many vertices near zero would
// otherwise hide every tail), with the count and, against a tolerance, the
// share of vertices within it written above. It follows the legend's colour
// bar, whose place VTK knows only once it drew it: Place() after a frame
// says whether the histogram moved (then draw again). VTK side only:
// scene_view_impl uses it.
#pragma once

#include <vtkSmartPointer.h>

#include <array>

#include "ui/models/deviation_histogram.h"

class vtkActor2D;
class vtkLookupTable;
class vtkPolyData;
class vtkRenderer;
class vtkTextActor;

namespace hull::ui {

class LegendHistogram {
 public:
  explicit LegendHistogram(vtkRenderer* renderer);

  // The counts and the table their bands are coloured by (the legend's).
  void Set(const DeviationHistogram& histogram, vtkLookupTable* lut);
  void SetVisible(bool visible);
  bool visible() const;  // asked for and has something to show
  // bar: the legend's colour bar {x, y, width, height} in pixels of the
  // viewport (vtkScalarBarActor::GetScalarBarRect); true when that moved it.
  bool Place(const std::array<int, 4>& bar);

  const DeviationHistogram& histogram() const { return histogram_; }

 private:
  void Rebuild();

  vtkSmartPointer<vtkPolyData> bars_, panel_;
  vtkSmartPointer<vtkActor2D> bars_actor_, panel_actor_;
  vtkSmartPointer<vtkTextActor> text_;
  vtkLookupTable* lut_ = nullptr;
  DeviationHistogram histogram_;
  std::array<int, 4> bar_{{0, 0, 0, 0}};
  bool visible_ = false;
};

}  // namespace hull::ui
