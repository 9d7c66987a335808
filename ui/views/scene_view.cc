#include "ui/views/scene_view.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindowInteractor.h>
#include <QEvent>
#include <QMouseEvent>
#include <QTimer>
#include <QVBoxLayout>

#include <array>
#include <cmath>

#include "ui/views/scene_view_impl.h"

namespace hull::ui {

SceneView::SceneView(QWidget* parent) : QWidget(parent), impl_(std::make_unique<SceneViewImpl>()) {
  setObjectName(QStringLiteral("sceneView"));
  qRegisterMetaType<PickInfo>("hull::ui::PickInfo");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  vtk_widget_ = new QVTKOpenGLNativeWidget(this);
  vtk_widget_->setRenderWindow(impl_->window());
  // One device pixel per widget pixel keeps screenshots and picking simple
  // and identical across displays.
  vtk_widget_->setEnableHiDPI(false);
  vtk_widget_->setFocusPolicy(Qt::StrongFocus);  // clicking it makes the scene the active view
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtk_widget_->interactor()->SetInteractorStyle(style);
  vtk_widget_->installEventFilter(this);
  layout->addWidget(vtk_widget_);
  setMinimumSize(320, 240);
}

SceneView::~SceneView() = default;

void SceneView::ScheduleRender() { render_.Schedule(); }

void SceneView::RenderNow() { impl_->Render(); }

QSurfaceFormat SceneView::SurfaceFormat() { return QVTKOpenGLNativeWidget::defaultFormat(); }

void SceneView::SetMesh(std::shared_ptr<const TriangleMesh> mesh) {
  impl_->SetMesh(std::move(mesh));
  ScheduleRender();
}

void SceneView::SetModelPose(const Pose& x_gM) {
  impl_->SetModelPose(x_gM);
  ScheduleRender();
}

void SceneView::SetSurvey(std::shared_ptr<const SurveyBundle> bundle, std::shared_ptr<const SurveyOverlays> overlays) {
  impl_->SetSurvey(std::move(bundle), std::move(overlays));
  ScheduleRender();
}

void SceneView::SetAdjusted(std::shared_ptr<const AdjustedOverlays> adjusted) {
  impl_->SetAdjusted(std::move(adjusted));
  ScheduleRender();
}

void SceneView::SetMapping(std::shared_ptr<const MappingRun> mapping) {
  impl_->SetMapping(std::move(mapping));
  ScheduleRender();
}

void SceneView::HighlightObject(int index) {
  impl_->HighlightObject(index);
  ScheduleRender();
}

int SceneView::HighlightedObject() const { return impl_->HighlightedObject(); }

void SceneView::SetMeasurement(const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segment) {
  impl_->SetMeasurement(segment);
  ScheduleRender();
}

bool SceneView::MeasurementShown() const { return impl_->MeasurementShown(); }

void SceneView::SetSignificanceK(double k) {
  impl_->SetSignificanceK(k);
  ScheduleRender();
}

std::size_t SceneView::SignificantVertices() const { return impl_->SignificantVertices(); }

void SceneView::SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison) {
  impl_->SetComparison(std::move(comparison));
  ScheduleRender();
}

void SceneView::SetMosaic(std::shared_ptr<const MosaicLayer> mosaic) {
  impl_->SetMosaic(std::move(mosaic));
  ScheduleRender();
}

void SceneView::SetSlab(const std::optional<SlabBox>& slab) {
  impl_->SetSlab(slab);
  ScheduleRender();
}

void SceneView::SetOptions(const SceneOptions& options) {
  impl_->SetOptions(options);
  ScheduleRender();
}

const SceneOptions& SceneView::options() const { return impl_->options(); }

void SceneView::ResetCamera() {
  impl_->ResetCamera();
  ScheduleRender();
}

CameraState SceneView::Camera() const { return impl_->Camera(); }

void SceneView::SetCamera(const CameraState& camera) {
  if (flight_timer_) flight_timer_->stop();
  impl_->SetCamera(camera);
  ScheduleRender();
}

namespace {

constexpr int kFlightSteps = 12;  // at 25 ms: 0.3 s

std::array<double, 3> Lerp(const std::array<double, 3>& a, const std::array<double, 3>& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

}  // namespace

void SceneView::FlyTo(const Eigen::Vector3d& p_g, double radius) {
  flight_from_ = impl_->Camera();
  CameraState to = flight_from_;
  Eigen::Vector3d direction(to.position[0] - to.focal_point[0], to.position[1] - to.focal_point[1],
                            to.position[2] - to.focal_point[2]);
  if (direction.norm() < 1e-9) direction = Eigen::Vector3d(0, 0, 1);
  const double distance = std::max(radius, 0.05) / std::sin(0.5 * to.view_angle * M_PI / 180.0);
  const Eigen::Vector3d position = p_g + distance * direction.normalized();
  to.focal_point = {p_g.x(), p_g.y(), p_g.z()};
  to.position = {position.x(), position.y(), position.z()};
  flight_to_ = to;
  flight_step_ = 0;
  if (!flight_timer_) {
    flight_timer_ = new QTimer(this);
    flight_timer_->setInterval(25);
    connect(flight_timer_, &QTimer::timeout, this, &SceneView::StepFlight);
  }
  flight_timer_->start();
}

void SceneView::StepFlight() {
  ++flight_step_;
  const double s = static_cast<double>(flight_step_) / kFlightSteps;
  const double t = s * s * (3 - 2 * s);  // ease in and out
  CameraState c = flight_to_;
  c.position = Lerp(flight_from_.position, flight_to_.position, t);
  c.focal_point = Lerp(flight_from_.focal_point, flight_to_.focal_point, t);
  impl_->SetCamera(c);
  if (flight_step_ >= kFlightSteps) flight_timer_->stop();
  ScheduleRender();
}

QImage SceneView::Grab() {
  if (!vtk_widget_->isVisible()) return {};
  vtk_widget_->makeCurrent();
  QImage image = impl_->Grab();
  vtk_widget_->doneCurrent();
  return image;
}

SceneView::LayerStats SceneView::Stats(SceneLayer layer) const {
  LayerStats s;
  s.present = impl_->HasLayerData(layer);
  s.visible = s.present && impl_->options().IsVisible(layer);
  s.points = impl_->LayerPoints(layer);
  s.cells = impl_->LayerCells(layer);
  return s;
}

bool SceneView::LegendVisible() const { return impl_->LegendVisible(); }

std::pair<double, double> SceneView::LegendRange() const { return impl_->LegendRange(); }

std::array<double, 3> SceneView::DeviationColour(double deviation) const { return impl_->DeviationColour(deviation); }

const ScaleBar& SceneView::CurrentScaleBar() const { return impl_->CurrentScaleBar(); }

const DeviationHistogram& SceneView::LegendHistogram() const { return impl_->LegendHistogramData(); }

bool SceneView::SigmaLegendVisible() const { return impl_->SigmaLegendVisible(); }

std::pair<double, double> SceneView::SigmaLegendRange() const { return impl_->SigmaLegendRange(); }

bool SceneView::ChangeLegendVisible() const { return impl_->ChangeLegendVisible(); }

std::pair<double, double> SceneView::ChangeLegendRange() const { return impl_->ChangeLegendRange(); }

PickInfo SceneView::PickAt(const QPoint& position) {
  const QPoint local = vtk_widget_->mapFrom(this, position);
  const double x = local.x();
  const double y = vtk_widget_->height() - 1 - local.y();
  PickInfo info = impl_->Pick(x, y);
  ScheduleRender();
  emit picked(info);
  return info;
}

std::optional<QPoint> SceneView::WidgetPosition(const Eigen::Vector3d& p_g) const {
  const auto display = impl_->ToDisplay(p_g);
  if (!display) return std::nullopt;
  const QPoint local(static_cast<int>(std::lround(display->first)),
                     static_cast<int>(std::lround(vtk_widget_->height() - 1 - display->second)));
  return vtk_widget_->mapTo(this, local);
}

void SceneView::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  if (warmed_up_) return;
  warmed_up_ = true;
  // Once the widget has its OpenGL context: compile the layers' shaders now,
  // while nothing is on screen yet, so that showing results later is quick.
  QTimer::singleShot(0, this, [this] {
    if (!vtk_widget_->isVisible()) return;
    impl_->WarmUp();
    ScheduleRender();
  });
}

bool SceneView::eventFilter(QObject* watched, QEvent* event) {
  if (watched == vtk_widget_) {
    // A click (press and release within a few pixels) picks; a drag turns
    // the camera as usual (the interactor sees every event).
    if (event->type() == QEvent::MouseButtonPress) {
      auto* e = static_cast<QMouseEvent*>(event);
      press_valid_ = e->button() == Qt::LeftButton;
      press_position_ = e->pos();
    } else if (event->type() == QEvent::MouseButtonRelease) {
      auto* e = static_cast<QMouseEvent*>(event);
      if (press_valid_ && e->button() == Qt::LeftButton && (e->pos() - press_position_).manhattanLength() <= 3) {
        PickAt(vtk_widget_->mapTo(this, e->pos()));
      }
      press_valid_ = false;
    }
  }
  return QWidget::eventFilter(watched, event);
}

}  // namespace hull::ui
