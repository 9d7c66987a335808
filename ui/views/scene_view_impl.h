// The VTK side of SceneView: the render window, one actor per layer, the
// colour legend, picking and image capture. Only scene_view.cc includes this.
#pragma once

#include <vtkSmartPointer.h>

#include <QImage>
#include <map>
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

class vtkActor;
class vtkGenericOpenGLRenderWindow;
class vtkColorTransferFunction;
class vtkLookupTable;
class vtkCellPicker;
class vtkPointPicker;
class vtkPolyDataMapper;
class vtkPolyData;
class vtkRenderer;
class vtkScalarBarActor;

namespace hull::ui {

class LegendHistogram;
class SceneGuides;

class SceneViewImpl {
 public:
  SceneViewImpl();
  ~SceneViewImpl();

  vtkGenericOpenGLRenderWindow* window() const { return window_; }

  void SetMesh(std::shared_ptr<const TriangleMesh> mesh);
  void SetModelPose(const Pose& x_gM);
  void SetSurvey(std::shared_ptr<const SurveyBundle> bundle, std::shared_ptr<const SurveyOverlays> overlays);
  void SetAdjusted(std::shared_ptr<const AdjustedOverlays> adjusted);
  void SetSlab(const std::optional<SlabBox>& slab);
  // The fused model, alpha shapes and detected objects (nullptr removes them).
  void SetMapping(std::shared_ptr<const MappingRun> mapping);
  void HighlightObject(int index);
  int HighlightedObject() const { return highlighted_object_; }
  void SetMeasurement(const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segment);
  bool MeasurementShown() const;
  // The significance factor k of the significance heatmap (|h| > k sigma).
  void SetSignificanceK(double k);
  double significanceK() const { return significance_k_; }
  std::size_t SignificantVertices() const { return significant_vertices_; }
  // A comparison of two surveys: survey B's model (in M, placed by x_gM)
  // coloured by the change in height (nullptr removes it).
  void SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison);
  // The photomosaic: mosaic.obj (with its texture coordinates) textured with
  // the atlas, placed by the layer's x_gM (nullptr removes it).
  void SetMosaic(std::shared_ptr<const MosaicLayer> mosaic);
  void SetOptions(const SceneOptions& options);
  const SceneOptions& options() const { return options_; }

  void ResetCamera();
  CameraState Camera() const;
  void SetCamera(const CameraState& camera);

  // Draws every layer once with a tiny stand-in (invisible at the focal
  // point) so that the shader programs they need are compiled now, not at
  // the first render of real data (a software OpenGL compiles each program
  // in tens of milliseconds); then restores the scene.
  void WarmUp();
  // (Re)renders now and reads the back buffer.
  QImage Grab();
  void Render();

  bool HasLayerData(SceneLayer layer) const;
  long long LayerPoints(SceneLayer layer) const;
  long long LayerCells(SceneLayer layer) const;
  bool LegendVisible() const;
  std::pair<double, double> LegendRange() const;
  std::array<double, 3> DeviationColour(double deviation) const;
  const ScaleBar& CurrentScaleBar() const;  // as last drawn
  const DeviationHistogram& LegendHistogramData() const;
  bool SigmaLegendVisible() const;
  std::pair<double, double> SigmaLegendRange() const;  // mm
  bool ChangeLegendVisible() const;
  std::pair<double, double> ChangeLegendRange() const;  // m

  // Display coordinates: pixels from the bottom-left corner.
  PickInfo Pick(double x, double y);
  std::optional<std::pair<double, double>> ToDisplay(const Eigen::Vector3d& p_g) const;

 private:
  vtkActor* AddActor();
  void UpdateVisibility();
  void UpdateLandmarkColours();
  void ColourLandmarks(vtkPolyDataMapper* mapper);
  bool TruthDeviationsShown() const;
  bool AdjustedDeviationsShown() const;
  bool HeatmapShown() const;
  bool SignificanceShown() const;
  bool HistogramShown() const;  // the histogram beside the deviation legend is wanted
  void UpdateSignificance();
  void PlaceLegends();
  void UpdateFrusta();
  Eigen::Vector3d ShowSelection(const Eigen::Vector3d& p_g);  // returns p_g
  // The orientation axes in hull terms: the mapping's hull frame, else the
  // survey's model axes, placed by the model pose; g's axes without either.
  void UpdateGuides();
  // The remeshed model's deviations over the legend's range (and tolerance).
  void UpdateHistogram();
  // A point of the first visible surface layer under (x, y): the remeshed
  // model, the change map, the CAD (kind kNone: none).
  PickInfo PickSurface(double x, double y);
  std::pair<double, double> EffectiveRange() const;

  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  std::map<SceneLayer, vtkSmartPointer<vtkActor>> actors_;
  vtkSmartPointer<vtkActor> selection_;
  vtkSmartPointer<vtkActor> highlight_;         // the highlighted object's outline
  vtkSmartPointer<vtkActor> measurement_;       // the distance tool's line
  std::unique_ptr<SceneGuides> guides_;         // orientation axes and scale bar
  std::unique_ptr<LegendHistogram> histogram_;  // beside the deviation legend
  int highlighted_object_ = -1;
  vtkSmartPointer<vtkLookupTable> deviation_lut_;
  vtkSmartPointer<vtkColorTransferFunction> deviation_ctf_;  // what deviation_lut_ is filled from
  vtkSmartPointer<vtkScalarBarActor> legend_;
  vtkSmartPointer<vtkLookupTable> sigma_lut_, change_lut_;
  vtkSmartPointer<vtkScalarBarActor> sigma_legend_, change_legend_;
  vtkSmartPointer<vtkPointPicker> picker_;
  vtkSmartPointer<vtkCellPicker> surface_picker_;

  std::shared_ptr<const TriangleMesh> mesh_;
  std::shared_ptr<const SurveyBundle> bundle_;
  std::shared_ptr<const SurveyOverlays> overlays_;
  std::shared_ptr<const AdjustedOverlays> adjusted_;
  std::shared_ptr<const MappingRun> mapping_;
  std::shared_ptr<const SurveyComparisonRun> comparison_;
  std::shared_ptr<const MosaicLayer> mosaic_;
  double significance_k_ = 1.96;
  std::size_t significant_vertices_ = 0;
  double max_sigma_ = 0, max_change_ = 0;
  Pose x_gM_;
  SceneOptions options_;
  int frusta_stride_built_ = 0;  // 0: not built for the current survey
};

}  // namespace hull::ui
