#include "ui/views/sonar_view.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindowInteractor.h>

#include <QTimer>
#include <QVBoxLayout>

#include "ui/views/sonar_view_impl.h"

namespace hull::ui {

SonarView::SonarView(QWidget* parent) : QWidget(parent), impl_(std::make_unique<SonarViewImpl>()) {
  setObjectName(QStringLiteral("sonarView"));
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  vtk_widget_ = new QVTKOpenGLNativeWidget(this);
  vtk_widget_->setRenderWindow(impl_->window());
  vtk_widget_->setEnableHiDPI(false);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtk_widget_->interactor()->SetInteractorStyle(style);
  layout->addWidget(vtk_widget_);
  setMinimumSize(240, 120);
}

SonarView::~SonarView() = default;

void SonarView::ScheduleRender() { render_.Schedule(); }

void SonarView::RenderNow() { impl_->Render(); }

void SonarView::SetRun(std::shared_ptr<const SonarRun> run) {
  impl_->SetRun(std::move(run));
  impl_->ResetCamera(false);
  ScheduleRender();
}

void SonarView::SetStep(int step) {
  impl_->SetStep(step);
  ScheduleRender();
}

void SonarView::SetEllipsoidScale(double scale) {
  impl_->SetEllipsoidScale(scale);
  ScheduleRender();
}

int SonarView::step() const { return impl_->step(); }

void SonarView::SetSmoother(bool smoother) {
  impl_->SetSmoother(smoother);
  ScheduleRender();
}

void SonarView::SetSceneVisible(bool visible) {
  impl_->SetSceneVisible(visible);
  ScheduleRender();
}

void SonarView::ResetCamera(bool whole_run) {
  impl_->ResetCamera(whole_run);
  ScheduleRender();
}

QImage SonarView::Grab() {
  if (!vtk_widget_->isVisible()) return {};
  vtk_widget_->makeCurrent();
  QImage image = impl_->Grab();
  vtk_widget_->doneCurrent();
  return image;
}

SonarView::Counts SonarView::counts() const {
  return {impl_->true_features,   impl_->initial,         impl_->estimated,       impl_->feature_ellipsoids,
          impl_->pose_ellipsoids, impl_->scene_triangles, impl_->showing_smoother};
}

}  // namespace hull::ui
