// The 3-D scene: the hull model placed in the survey frame g (z down), the
// trajectory, DVL hits, landmarks, the true objects' outlines and camera
// frusta, with a colour legend when landmarks are coloured by deviation and
// picking of landmarks, keyframes and objects.
//
// A QWidget around a QVTKOpenGLNativeWidget. This header is VTK-free: the
// view owns its actors in SceneViewImpl (scene_view_impl.*), and callers
// speak in survey types, SceneOptions and CameraState.
#pragma once

#include <QImage>
#include <QPoint>
#include <QSurfaceFormat>
#include <QWidget>
#include <array>
#include <memory>
#include <optional>
#include <utility>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "results/compare_files.h"
#include "survey/survey.h"
#include "ui/models/cross_section.h"
#include "ui/models/deviation_histogram.h"
#include "ui/models/pick_details.h"
#include "ui/models/scale_bar.h"
#include "ui/session/inspection_results.h"
#include "ui/session/mosaic_layer.h"
#include "ui/session/scene_options.h"
#include "ui/session/survey_overlays.h"
#include "ui/views/render_coalescer.h"

class QTimer;
class QVTKOpenGLNativeWidget;

namespace hull::ui {

class SceneViewImpl;

class SceneView : public QWidget {
  Q_OBJECT

 public:
  explicit SceneView(QWidget* parent = nullptr);
  ~SceneView() override;

  // The OpenGL format VTK needs; set it as the default before QApplication.
  static QSurfaceFormat SurfaceFormat();

  // The hull in its own frame M (nullptr removes it); shown placed by x_gM.
  void SetMesh(std::shared_ptr<const TriangleMesh> mesh);
  void SetModelPose(const Pose& x_gM);
  // The survey and what to draw of it (both nullptr removes it).
  void SetSurvey(std::shared_ptr<const SurveyBundle> bundle, std::shared_ptr<const SurveyOverlays> overlays);
  // The bundle adjustment's trajectory, DVL hits and landmarks (nullptr removes them).
  void SetAdjusted(std::shared_ptr<const AdjustedOverlays> adjusted);
  // Mapping's fused model (heatmap), alpha shapes and detected objects
  // (nullptr removes them).
  void SetMapping(std::shared_ptr<const MappingRun> mapping);
  // The detected object selected in the objects table (its position in the
  // mapping's objects; -1: none): its outline drawn bold in black and the
  // selection marker at its centroid. A new mapping or a pick clears it.
  void HighlightObject(int index);
  int HighlightedObject() const;
  // The distance tool's line between two picks (g; nullopt: none).
  void SetMeasurement(const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segment);
  bool MeasurementShown() const;
  // The significance heatmap's factor k: a vertex is coloured by its
  // deviation h where |h| > k sigma, grey elsewhere. Recomputed from the
  // model's deviation and sigma (no re-run).
  void SetSignificanceK(double k);
  std::size_t SignificantVertices() const;  // at the current k, of the mapping on screen
  // A comparison of two surveys, drawn as the height-change layer (nullptr removes it).
  void SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison);
  // The photomosaic layer: mosaic.obj textured with its atlas, placed by the
  // layer's x_gM (nullptr removes it).
  void SetMosaic(std::shared_ptr<const MosaicLayer> mosaic);
  // The cross-section slab (nullopt removes it).
  void SetSlab(const std::optional<SlabBox>& slab);
  void SetOptions(const SceneOptions& options);
  const SceneOptions& options() const;

  // Looks at the survey (or the whole hull without one) from below, the
  // hull's forward direction up on the screen.
  void ResetCamera();
  CameraState Camera() const;
  void SetCamera(const CameraState& camera);
  // Moves the camera (animated over about 0.3 s) to look at p_g from the
  // current direction, from far enough to see a sphere of `radius` metres.
  void FlyTo(const Eigen::Vector3d& p_g, double radius);

  // The rendered image at the widget's size (vtkWindowToImageFilter); a null
  // image while the widget has never been shown.
  QImage Grab();

  // What a layer holds, for status text and tests.
  struct LayerStats {
    bool present = false;  // has data
    bool visible = false;  // present and switched on
    long long points = 0;
    long long cells = 0;
  };
  LayerStats Stats(SceneLayer layer) const;
  bool LegendVisible() const;
  std::pair<double, double> LegendRange() const;
  // The colour a deviation (m) is drawn in by the deviation layers (the
  // legend's range and tolerance band in force), RGB in [0, 1].
  std::array<double, 3> DeviationColour(double deviation) const;
  // The scale bar as last drawn (ui/models/scale_bar.h; metres 0: none).
  const ScaleBar& CurrentScaleBar() const;
  // The histogram beside the deviation legend: the remeshed model's
  // vertices over the legend's range (ui/models/deviation_histogram.h).
  const DeviationHistogram& LegendHistogram() const;
  bool SigmaLegendVisible() const;
  std::pair<double, double> SigmaLegendRange() const;  // mm
  bool ChangeLegendVisible() const;
  std::pair<double, double> ChangeLegendRange() const;  // m

  // Picks at a widget position (as a click does) and emits picked().
  PickInfo PickAt(const QPoint& position);
  // Where a point of g appears in the widget (nullopt when not rendered yet).
  std::optional<QPoint> WidgetPosition(const Eigen::Vector3d& p_g) const;

 signals:
  // After a click: what is under the cursor (kind kNone: nothing).
  void picked(const hull::ui::PickInfo& info);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void showEvent(QShowEvent* event) override;

 private:
  void ScheduleRender();
  void RenderNow();  // the coalesced frame
  void StepFlight();

  QVTKOpenGLNativeWidget* vtk_widget_ = nullptr;
  RenderCoalescer render_{this, [this] { RenderNow(); }};
  std::unique_ptr<SceneViewImpl> impl_;
  QPoint press_position_;
  bool press_valid_ = false;
  bool warmed_up_ = false;
  // The flight in progress (FlyTo).
  QTimer* flight_timer_ = nullptr;
  CameraState flight_from_, flight_to_;
  int flight_step_ = 0;
};

}  // namespace hull::ui
