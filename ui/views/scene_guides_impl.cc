#include "ui/views/scene_guides_impl.h"

#include <vtkActor2D.h>
#include <vtkAxesActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCaptionActor2D.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <cmath>

#include "ui/views/scene_layers_impl.h"

namespace hull::ui {

namespace {

constexpr int kAxesPixels = 120;            // the orientation marker's square
constexpr int kBarLeft = 24 + kAxesPixels;  // the scale bar starts right of it
constexpr int kBarBottom = 22;

void StyleCaption(vtkCaptionActor2D* caption) {
  StyleOverlayText(caption->GetCaptionTextProperty(), 13);
  caption->GetTextActor()->SetTextScaleModeToNone();
}

vtkSmartPointer<vtkActor2D> BarActor(vtkPolyData* bar, double width, double grey) {
  auto actor = OverlayActor2D(bar);
  actor->GetProperty()->SetLineWidth(width);
  actor->GetProperty()->SetColor(grey, grey, grey);
  return actor;
}

}  // namespace

SceneGuides::SceneGuides(vtkRenderWindow* window, vtkRenderer* scene) : window_(window), scene_(scene) {
  // The axes in a renderer of their own over the scene's (layer 1 keeps the
  // scene's colours and clears only depth), camera turned with the scene's.
  window_->SetNumberOfLayers(2);
  axes_renderer_ = vtkSmartPointer<vtkRenderer>::New();
  axes_renderer_->SetLayer(1);
  axes_renderer_->InteractiveOff();
  axes_ = vtkSmartPointer<vtkAxesActor>::New();
  axes_->SetShaftTypeToCylinder();
  axes_->SetCylinderRadius(0.04);
  axes_->SetConeRadius(0.35);
  axes_->SetTotalLength(1.0, 1.0, 1.0);
  axes_->PickableOff();
  for (vtkCaptionActor2D* c :
       {axes_->GetXAxisCaptionActor2D(), axes_->GetYAxisCaptionActor2D(), axes_->GetZAxisCaptionActor2D()}) {
    StyleCaption(c);
  }
  axes_renderer_->AddActor(axes_);
  window_->AddRenderer(axes_renderer_);
  SetHullAxes(std::nullopt);

  // The scale bar: a white line over a black one (readable on the hull as
  // on the water), end ticks, its length above it.
  bar_points_ = vtkSmartPointer<vtkPoints>::New();
  bar_points_->SetNumberOfPoints(6);
  vtkNew<vtkCellArray> lines;
  for (const vtkIdType segment : {0, 2, 4}) {
    const vtkIdType ids[2] = {segment, segment + 1};
    lines->InsertNextCell(2, ids);
  }
  vtkNew<vtkPolyData> bar;
  bar->SetPoints(bar_points_);
  bar->SetLines(lines);
  bar_back_ = BarActor(bar, 5.0, 0.0);
  bar_front_ = BarActor(bar, 2.0, 1.0);
  bar_text_ = vtkSmartPointer<vtkTextActor>::New();
  StyleOverlayText(bar_text_->GetTextProperty(), 13);
  bar_text_->PickableOff();
  for (vtkProp* p :
       {static_cast<vtkProp*>(bar_back_), static_cast<vtkProp*>(bar_front_), static_cast<vtkProp*>(bar_text_)}) {
    scene_->AddViewProp(p);
  }
  observer_ = window_->AddObserver(vtkCommand::StartEvent, this, &SceneGuides::Update);
}

SceneGuides::~SceneGuides() { window_->RemoveObserver(observer_); }

void SceneGuides::SetHullAxes(const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& forward_up_g) {
  vtkNew<vtkMatrix4x4> m;  // columns: the marker's x, y, z in g
  if (forward_up_g) {
    const Eigen::Vector3d forward = forward_up_g->first.normalized();
    const Eigen::Vector3d up = (forward_up_g->second - forward_up_g->second.dot(forward) * forward).normalized();
    const Eigen::Vector3d port = up.cross(forward);
    for (int r = 0; r < 3; ++r) {
      m->SetElement(r, 0, forward[r]);
      m->SetElement(r, 1, port[r]);
      m->SetElement(r, 2, up[r]);
    }
    axes_->SetXAxisLabelText("bow");
    axes_->SetYAxisLabelText("port");
    axes_->SetZAxisLabelText("up");
  } else {
    axes_->SetXAxisLabelText("x");
    axes_->SetYAxisLabelText("y");
    axes_->SetZAxisLabelText("z");
  }
  axes_->SetUserMatrix(m);
}

void SceneGuides::Update(vtkObject*, unsigned long, void*) {
  const int* size = window_->GetSize();
  if (!size || size[0] <= 0 || size[1] <= 0) return;
  axes_renderer_->SetViewport(0.0, 0.0, std::min(1.0, kAxesPixels / static_cast<double>(size[0])),
                              std::min(1.0, kAxesPixels / static_cast<double>(size[1])));
  vtkCamera* camera = scene_->GetActiveCamera();
  double position[3], focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  Eigen::Vector3d direction(focal[0] - position[0], focal[1] - position[1], focal[2] - position[2]);
  if (direction.norm() > 0) direction.normalize();
  vtkCamera* marker = axes_renderer_->GetActiveCamera();
  marker->SetFocalPoint(0.0, 0.0, 0.0);
  marker->SetPosition(-5.6 * direction.x(), -5.6 * direction.y(), -5.6 * direction.z());
  marker->SetViewUp(camera->GetViewUp());
  marker->SetViewAngle(30.0);
  axes_renderer_->ResetCameraClippingRange();

  const double world_height = camera->GetParallelProjection()
                                  ? 2.0 * camera->GetParallelScale()
                                  : 2.0 * camera->GetDistance() * std::tan(0.5 * camera->GetViewAngle() * M_PI / 180.0);
  bar_ = ChooseScaleBar(world_height, size[1]);
  const bool shown = bar_.metres > 0 && kBarLeft + bar_.pixels < size[0];
  for (vtkProp* p :
       {static_cast<vtkProp*>(bar_back_), static_cast<vtkProp*>(bar_front_), static_cast<vtkProp*>(bar_text_)}) {
    p->SetVisibility(shown);
  }
  if (!shown) return;
  const double x0 = kBarLeft, x1 = kBarLeft + bar_.pixels, y = kBarBottom;
  bar_points_->SetPoint(0, x0, y, 0.0);
  bar_points_->SetPoint(1, x1, y, 0.0);
  bar_points_->SetPoint(2, x0, y - 5, 0.0);
  bar_points_->SetPoint(3, x0, y + 5, 0.0);
  bar_points_->SetPoint(4, x1, y - 5, 0.0);
  bar_points_->SetPoint(5, x1, y + 5, 0.0);
  bar_points_->Modified();
  bar_text_->SetInput(bar_.label.c_str());
  bar_text_->SetPosition(x0, y + 9);
}

}  // namespace hull::ui
