// The 3-D scene's guides (issue 25.2): orientation axes in the bottom-left
// corner, turning with the camera, in hull terms when the hull's axes are
// known (bow, port, up) and as g's x, y, z otherwise; and a scale bar whose
// length is a round number of metres at the depth of the view's focal point
// (a perspective view shows nearer things larger: the bar holds at the
// centre of the view, where the camera turns about). Both are redrawn
// before every frame of the window, whoever asked for it (the interactor as
// well as the view). VTK side only: scene_view_impl uses it.
#pragma once

#include <vtkSmartPointer.h>

#include <optional>
#include <utility>

#include "geometry/pose.h"
#include "ui/models/scale_bar.h"

class vtkActor2D;
class vtkAxesActor;
class vtkObject;
class vtkPoints;
class vtkRenderWindow;
class vtkRenderer;
class vtkTextActor;

namespace hull::ui {

class SceneGuides {
 public:
  // Adds the guides to `window`, drawn over `scene` (its camera followed).
  SceneGuides(vtkRenderWindow* window, vtkRenderer* scene);
  ~SceneGuides();
  SceneGuides(const SceneGuides&) = delete;
  SceneGuides& operator=(const SceneGuides&) = delete;

  // The hull's forward and up directions in g (nullopt: not known, the
  // axes are g's).
  void SetHullAxes(const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& forward_up_g);

  const ScaleBar& scale_bar() const { return bar_; }

 private:
  void Update(vtkObject*, unsigned long, void*);  // before every frame

  vtkRenderWindow* window_;
  vtkRenderer* scene_;
  vtkSmartPointer<vtkRenderer> axes_renderer_;
  vtkSmartPointer<vtkAxesActor> axes_;
  vtkSmartPointer<vtkPoints> bar_points_;
  vtkSmartPointer<vtkActor2D> bar_back_, bar_front_;
  vtkSmartPointer<vtkTextActor> bar_text_;
  ScaleBar bar_;
  unsigned long observer_ = 0;
};

}  // namespace hull::ui
