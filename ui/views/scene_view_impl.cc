#include "ui/views/scene_view_impl.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointPicker.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mapping/vertex_significance.h"
#include "ui/models/surface_pick.h"
#include "ui/views/legend_histogram_impl.h"
#include "ui/views/scene_guides_impl.h"
#include "ui/views/scene_layers_impl.h"
#include "ui/views/scene_polydata_impl.h"
#include "ui/views/vtk_grab_impl.h"

namespace hull::ui {

namespace {

constexpr double kBackgroundBottom[3] = {0.02, 0.07, 0.13};
constexpr double kBackgroundTop[3] = {0.10, 0.25, 0.38};

}  // namespace

SceneViewImpl::SceneViewImpl() {
  // Points and lines that lie on a surface are drawn in front of it (VTK's
  // polygon offset; a process-wide mapper setting, which every view wants).
  vtkMapper::SetResolveCoincidentTopologyToPolygonOffset();
  window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  // No multisampling: with a software OpenGL (Mesa's llvmpipe under Xvfb)
  // VTK's default 8x MSAA multiplies the cost of every frame, and a frame
  // is drawn on the GUI thread.
  window_->SetMultiSamples(0);
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->GradientBackgroundOn();
  renderer_->SetBackground(kBackgroundBottom[0], kBackgroundBottom[1], kBackgroundBottom[2]);
  renderer_->SetBackground2(kBackgroundTop[0], kBackgroundTop[1], kBackgroundTop[2]);
  window_->AddRenderer(renderer_);
  guides_ = std::make_unique<SceneGuides>(window_, renderer_);

  for (SceneLayer layer : AllSceneLayers()) {
    vtkActor* actor = AddActor();
    actors_[layer] = actor;
    StyleLayerActor(layer, actor);
  }
  selection_ = AddActor();
  selection_->GetProperty()->SetColor(1.0, 1.0, 1.0);
  selection_->GetProperty()->SetPointSize(13.0);
  selection_->GetProperty()->LightingOff();
  selection_->PickableOff();
  selection_->VisibilityOff();
  highlight_ = AddActor();
  // Black: apart from every deviation colour and the outlines' magenta.
  highlight_->GetProperty()->SetColor(0.0, 0.0, 0.0);
  highlight_->GetProperty()->SetLineWidth(5.0);
  highlight_->GetProperty()->LightingOff();
  highlight_->PickableOff();
  highlight_->VisibilityOff();
  measurement_ = AddActor();
  measurement_->GetProperty()->SetColor(1.0, 1.0, 1.0);
  measurement_->GetProperty()->SetLineWidth(3.0);
  measurement_->GetProperty()->LightingOff();
  measurement_->PickableOff();
  measurement_->VisibilityOff();

  // The report's diverging map (RdBu, near-white at zero), shared by the
  // landmark mappers, the heatmaps and the legend; NaN (not significant) is
  // grey.
  deviation_lut_ = MakeDivergingLut();
  deviation_ctf_ = MakeDivergingCtf();
  legend_ = MakeLegend(deviation_lut_, "Deviation (m)", "%+.3f");
  legend_->SetNanAnnotation("not significant");
  legend_->SetAboveRangeAnnotation("above");
  legend_->SetBelowRangeAnnotation("below");
  renderer_->AddViewProp(legend_);
  histogram_ = std::make_unique<LegendHistogram>(renderer_);
  sigma_lut_ = MakeSequentialLut();
  // VTK's embedded fonts have no Greek letters: "sigma" spelled out.
  sigma_legend_ = MakeLegend(sigma_lut_, "sigma (mm)", "%.1f");
  renderer_->AddViewProp(sigma_legend_);
  change_lut_ = MakeDivergingLut();
  change_legend_ = MakeLegend(change_lut_, "Change (m)", "%+.3f");
  renderer_->AddViewProp(change_legend_);

  picker_ = vtkSmartPointer<vtkPointPicker>::New();
  picker_->SetTolerance(0.01);
  picker_->PickFromListOn();
  surface_picker_ = vtkSmartPointer<vtkCellPicker>::New();
  surface_picker_->SetTolerance(0.0005);
  surface_picker_->PickFromListOn();

  UpdateVisibility();
}

SceneViewImpl::~SceneViewImpl() = default;

vtkActor* SceneViewImpl::AddActor() {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer_->AddActor(actor);
  return actor.GetPointer();  // the renderer holds it
}

void SceneViewImpl::SetMesh(std::shared_ptr<const TriangleMesh> mesh) {
  mesh_ = std::move(mesh);
  SetData(actors_[SceneLayer::kHull], mesh_ ? MeshPolyData(*mesh_) : vtkSmartPointer<vtkPolyData>::New());
  UpdateVisibility();
}

void SceneViewImpl::SetModelPose(const Pose& x_gM) {
  x_gM_ = x_gM;
  actors_[SceneLayer::kHull]->SetUserMatrix(PoseMatrix(x_gM));
  actors_[SceneLayer::kHeightChange]->SetUserMatrix(PoseMatrix(x_gM));
  actors_[SceneLayer::kTruthObjects]->SetUserMatrix(PoseMatrix(x_gM));
  UpdateGuides();
}

void SceneViewImpl::UpdateGuides() {
  if (mapping_) {
    const Eigen::Matrix3d R = mapping_->x_gM().rotation();
    guides_->SetHullAxes(std::make_pair(R * mapping_->result->hull.forward(), R * mapping_->result->hull.up()));
  } else if (bundle_ && bundle_->manifest.model_axes) {
    const Eigen::Matrix3d R = x_gM_.rotation();
    guides_->SetHullAxes(
        std::make_pair(R * bundle_->manifest.model_axes->forward, R * bundle_->manifest.model_axes->up));
  } else {
    guides_->SetHullAxes(std::nullopt);
  }
}

const ScaleBar& SceneViewImpl::CurrentScaleBar() const { return guides_->scale_bar(); }

const DeviationHistogram& SceneViewImpl::LegendHistogramData() const { return histogram_->histogram(); }

void SceneViewImpl::UpdateHistogram() {
  constexpr int kBins = 32;
  const std::vector<double>* deviation = mapping_ ? mapping_->result->model.FindScalar("deviation") : nullptr;
  const auto [lo, hi] = EffectiveRange();
  histogram_->Set(ComputeDeviationHistogram(deviation ? *deviation : std::vector<double>{}, lo, std::max(hi, lo + 1e-6),
                                            kBins, options_.tolerance),
                  deviation_lut_);
  histogram_->SetVisible(HistogramShown());
}

void SceneViewImpl::SetAdjusted(std::shared_ptr<const AdjustedOverlays> adjusted) {
  adjusted_ = std::move(adjusted);
  static const AdjustedOverlays kEmpty;
  const AdjustedOverlays& a = adjusted_ ? *adjusted_ : kEmpty;
  SetData(actors_[SceneLayer::kAdjustedTrajectory], PolylinePolyData(a.trajectory));
  std::vector<Eigen::Vector3d> hits;
  hits.reserve(a.dvl_hits.size());
  for (const DvlHit& h : a.dvl_hits) hits.push_back(h.point);
  SetData(actors_[SceneLayer::kAdjustedDvlHits], PointCloudPolyData(hits));
  SetData(actors_[SceneLayer::kAdjustedLandmarks], AdjustedLandmarksPolyData(a.landmarks));
  selection_->VisibilityOff();
  UpdateLandmarkColours();
  UpdateVisibility();
}

void SceneViewImpl::SetMapping(std::shared_ptr<const MappingRun> mapping) {
  mapping_ = std::move(mapping);
  max_sigma_ = 0;
  if (mapping_) {
    const TriangleMesh& model = mapping_->result->model;
    const auto heatmap = HeatmapPolyData(model);
    SetData(actors_[SceneLayer::kHeatmap], heatmap);
    // The sigma and significance heatmaps draw the same surface with other
    // arrays (none without per-vertex sigmas).
    const bool sigmas = HasVertexSigma(model);
    if (sigmas) {
      SetPointArray(heatmap, "sigma_mm", *model.FindScalar("sigma"), 1000.0);
      max_sigma_ = MaxVertexSigma(model);
    }
    for (SceneLayer layer : {SceneLayer::kSigmaHeatmap, SceneLayer::kSignificance}) {
      SetData(actors_[layer], sigmas ? heatmap.GetPointer() : vtkSmartPointer<vtkPolyData>::New().GetPointer());
    }
    SetData(actors_[SceneLayer::kAlphaShapes], AlphaShapesPolyData(mapping_->result->keyframes));
    SetData(actors_[SceneLayer::kDetectedObjects], SegmentsPolyData(mapping_->overlays->object_outlines));
    const auto matrix = PoseMatrix(mapping_->x_gM());
    for (SceneLayer layer :
         {SceneLayer::kHeatmap, SceneLayer::kSigmaHeatmap, SceneLayer::kSignificance, SceneLayer::kDetectedObjects}) {
      actors_[layer]->SetUserMatrix(matrix);
    }
  } else {
    for (SceneLayer layer : {SceneLayer::kHeatmap, SceneLayer::kSigmaHeatmap, SceneLayer::kSignificance,
                             SceneLayer::kAlphaShapes, SceneLayer::kDetectedObjects}) {
      SetData(actors_[layer], vtkSmartPointer<vtkPolyData>::New());
    }
  }
  UpdateSignificance();
  selection_->VisibilityOff();
  HighlightObject(-1);
  UpdateGuides();
  UpdateLandmarkColours();
  UpdateVisibility();
}

void SceneViewImpl::HighlightObject(int index) {
  const bool valid = mapping_ && index >= 0 && index < static_cast<int>(mapping_->result->objects.size());
  highlighted_object_ = valid ? index : -1;
  highlight_->SetVisibility(valid);
  if (!valid) return;
  SetData(highlight_, SegmentsPolyData({mapping_->overlays->object_outlines[static_cast<std::size_t>(index)]}));
  highlight_->SetUserMatrix(PoseMatrix(mapping_->x_gM()));
  ShowSelection(mapping_->x_gM() * mapping_->result->objects[static_cast<std::size_t>(index)].centroid_m);
}

void SceneViewImpl::SetMeasurement(const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segment) {
  measurement_->SetVisibility(segment.has_value());
  if (segment) SetData(measurement_, SegmentsPolyData({{{segment->first, segment->second}}}));
}

bool SceneViewImpl::MeasurementShown() const { return measurement_->GetVisibility(); }

void SceneViewImpl::SetSignificanceK(double k) {
  significance_k_ = k;
  UpdateSignificance();
}

void SceneViewImpl::UpdateSignificance() {
  significant_vertices_ = 0;
  vtkPolyData* data = DataOf(actors_[SceneLayer::kSignificance]);
  if (!mapping_ || !data || data->GetNumberOfPoints() == 0) return;
  const std::vector<double> mask = SignificantDeviation(mapping_->result->model, significance_k_);
  for (const double h : mask) significant_vertices_ += !std::isnan(h);
  SetPointArray(data, "significant_deviation", mask);
  legend_->SetNanAnnotation(
      QStringLiteral("|h| <= %1 sigma").arg(QString::number(significance_k_, 'g', 3)).toUtf8().constData());
}

void SceneViewImpl::SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison) {
  comparison_ = std::move(comparison);
  max_change_ = 0;
  if (comparison_) {
    const TriangleMesh& model = comparison_->comparison.model;
    const auto poly = HeatmapPolyData(model);
    if (const std::vector<double>* change = model.FindScalar("change")) {
      SetPointArray(poly, "change", *change);
      for (const double c : *change) {
        if (std::isfinite(c)) max_change_ = std::max(max_change_, std::abs(c));
      }
    }
    SetData(actors_[SceneLayer::kHeightChange], poly);
  } else {
    SetData(actors_[SceneLayer::kHeightChange], vtkSmartPointer<vtkPolyData>::New());
  }
  UpdateLandmarkColours();
  UpdateVisibility();
}

void SceneViewImpl::SetMosaic(std::shared_ptr<const MosaicLayer> mosaic) {
  mosaic_ = std::move(mosaic);
  vtkActor* actor = actors_[SceneLayer::kPhotomosaic];
  if (mosaic_) {
    SetData(actor, TexturedObjPolyData(mosaic_->obj));
    actor->SetTexture(AtlasTexture(mosaic_->atlas));
    actor->SetUserMatrix(PoseMatrix(mosaic_->x_gM));
  } else {
    SetData(actor, vtkSmartPointer<vtkPolyData>::New());
    actor->SetTexture(nullptr);
  }
  UpdateVisibility();
}

void SceneViewImpl::SetSlab(const std::optional<SlabBox>& slab) {
  SetData(actors_[SceneLayer::kSlab], slab ? SlabPolyData(*slab) : vtkSmartPointer<vtkPolyData>::New());
  UpdateVisibility();
}

void SceneViewImpl::SetSurvey(std::shared_ptr<const SurveyBundle> bundle,
                              std::shared_ptr<const SurveyOverlays> overlays) {
  if (!bundle || !overlays) {
    bundle.reset();
    overlays.reset();
  }
  bundle_ = std::move(bundle);
  overlays_ = std::move(overlays);
  static const SurveyOverlays kEmpty;
  const SurveyOverlays& o = overlays_ ? *overlays_ : kEmpty;
  SetData(actors_[SceneLayer::kTrajectory], PolylinePolyData(o.trajectory));
  SetData(actors_[SceneLayer::kTrueTrajectory], PolylinePolyData(o.true_trajectory));
  std::vector<Eigen::Vector3d> hits;
  hits.reserve(o.dvl_hits.size());
  for (const DvlHit& h : o.dvl_hits) hits.push_back(h.point);
  SetData(actors_[SceneLayer::kDvlHits], PointCloudPolyData(hits));
  SetData(actors_[SceneLayer::kLandmarks], LandmarksPolyData(o.landmarks));
  SetData(actors_[SceneLayer::kTruthObjects], OutlinesPolyData(o.objects));
  frusta_stride_built_ = 0;
  selection_->VisibilityOff();
  UpdateGuides();
  UpdateLandmarkColours();
  UpdateFrusta();
  UpdateVisibility();
}

void SceneViewImpl::SetOptions(const SceneOptions& options) {
  options_ = options;
  vtkProperty* hull = actors_[SceneLayer::kHull]->GetProperty();
  hull->SetEdgeVisibility(options_.hull_edges);
  UpdateLandmarkColours();
  UpdateFrusta();
  UpdateVisibility();
}

bool SceneViewImpl::HasLayerData(SceneLayer layer) const {
  vtkPolyData* data = DataOf(actors_.at(layer));
  return data && data->GetNumberOfPoints() > 0;
}

long long SceneViewImpl::LayerPoints(SceneLayer layer) const {
  vtkPolyData* data = DataOf(actors_.at(layer));
  return data ? data->GetNumberOfPoints() : 0;
}

long long SceneViewImpl::LayerCells(SceneLayer layer) const {
  vtkPolyData* data = DataOf(actors_.at(layer));
  return data ? data->GetNumberOfCells() : 0;
}

void SceneViewImpl::UpdateVisibility() {
  for (auto& [layer, actor] : actors_) actor->SetVisibility(options_.IsVisible(layer) && HasLayerData(layer));
  legend_->SetVisibility(LegendVisible());
  legend_->SetDrawNanAnnotation(SignificanceShown());
  histogram_->SetVisible(HistogramShown());
  // What lies beyond a manual range: counted under the histogram, or (no
  // histogram) the legend's own swatches.
  const bool swatches = !options_.auto_range && !histogram_->visible();
  legend_->SetDrawAboveRangeSwatch(swatches);
  legend_->SetDrawBelowRangeSwatch(swatches);
  sigma_legend_->SetVisibility(SigmaLegendVisible());
  change_legend_->SetVisibility(ChangeLegendVisible());
  PlaceLegends();
}

void SceneViewImpl::PlaceLegends() {
  // Right to left: deviation, sigma, height change.
  // The deviation legend's histogram takes the room of another legend, its
  // counts under it.
  const bool histogram = legend_->GetVisibility() && histogram_->visible();
  double x = 0.85;
  for (vtkScalarBarActor* legend : {legend_.GetPointer(), sigma_legend_.GetPointer(), change_legend_.GetPointer()}) {
    if (!legend->GetVisibility()) continue;
    legend->GetPositionCoordinate()->SetValue(x, histogram ? 0.13 : 0.05);
    x -= legend == legend_.GetPointer() && histogram ? 0.30 : 0.15;
  }
}

bool SceneViewImpl::HistogramShown() const {
  // Not under the significance map: its NaN swatch shifts the colour bar.
  return HeatmapShown() && !SignificanceShown();
}

bool SceneViewImpl::SignificanceShown() const {
  return options_.IsVisible(SceneLayer::kSignificance) && HasLayerData(SceneLayer::kSignificance);
}

bool SceneViewImpl::SigmaLegendVisible() const {
  return options_.IsVisible(SceneLayer::kSigmaHeatmap) && HasLayerData(SceneLayer::kSigmaHeatmap);
}

std::pair<double, double> SceneViewImpl::SigmaLegendRange() const { return {0.0, std::max(1000.0 * max_sigma_, 1e-3)}; }

bool SceneViewImpl::ChangeLegendVisible() const {
  return options_.IsVisible(SceneLayer::kHeightChange) && HasLayerData(SceneLayer::kHeightChange);
}

std::pair<double, double> SceneViewImpl::ChangeLegendRange() const {
  const double m = std::max(max_change_, 1e-3);
  return {-m, m};
}

bool SceneViewImpl::TruthDeviationsShown() const {
  return options_.IsVisible(SceneLayer::kLandmarks) && overlays_ &&
         overlays_->landmark_source == LandmarkSource::kTruth && !overlays_->landmarks.empty();
}

bool SceneViewImpl::AdjustedDeviationsShown() const {
  return options_.IsVisible(SceneLayer::kAdjustedLandmarks) && adjusted_ && !adjusted_->landmarks.empty();
}

bool SceneViewImpl::HeatmapShown() const {
  return options_.IsVisible(SceneLayer::kHeatmap) && mapping_ && !mapping_->result->model.empty();
}

bool SceneViewImpl::LegendVisible() const {
  return HeatmapShown() || SignificanceShown() ||
         (options_.colouring == LandmarkColouring::kDeviation && (TruthDeviationsShown() || AdjustedDeviationsShown()));
}

std::pair<double, double> SceneViewImpl::EffectiveRange() const {
  if (!options_.auto_range) return {options_.range_min, options_.range_max};
  // Symmetric about zero so that the neutral colour means "on the surface",
  // reaching the largest |deviation| of the visible layers that carry one.
  double m = 1e-3;
  if (TruthDeviationsShown()) m = std::max({m, std::abs(overlays_->min_deviation), std::abs(overlays_->max_deviation)});
  if (AdjustedDeviationsShown()) {
    m = std::max({m, std::abs(adjusted_->min_deviation), std::abs(adjusted_->max_deviation)});
  }
  if (HeatmapShown() || SignificanceShown()) {
    m = std::max({m, std::abs(mapping_->overlays->min_deviation), std::abs(mapping_->overlays->max_deviation)});
  }
  return {-m, m};
}

std::pair<double, double> SceneViewImpl::LegendRange() const { return EffectiveRange(); }

std::array<double, 3> SceneViewImpl::DeviationColour(double deviation) const {
  const unsigned char* rgba = deviation_lut_->MapValue(deviation);
  return {rgba[0] / 255.0, rgba[1] / 255.0, rgba[2] / 255.0};
}

void SceneViewImpl::UpdateLandmarkColours() {
  const auto [lo, hi] = EffectiveRange();
  // A manual range marks what lies beyond it (an automatic one holds every value).
  const bool manual = !options_.auto_range;
  ShapeDeviationLut(deviation_lut_, deviation_ctf_, lo, hi, options_.tolerance, manual);
  for (SceneLayer layer : {SceneLayer::kLandmarks, SceneLayer::kAdjustedLandmarks}) {
    ColourLandmarks(MapperOf(actors_[layer]));
  }
  ColourByArray(MapperOf(actors_[SceneLayer::kHeatmap]), "deviation", deviation_lut_);
  ColourByArray(MapperOf(actors_[SceneLayer::kSignificance]), "significant_deviation", deviation_lut_);
  UpdateHistogram();
  const auto [slo, shi] = SigmaLegendRange();
  sigma_lut_->SetTableRange(slo, shi);
  ColourByArray(MapperOf(actors_[SceneLayer::kSigmaHeatmap]), "sigma_mm", sigma_lut_);
  const auto [clo, chi] = ChangeLegendRange();
  change_lut_->SetTableRange(clo, chi);
  ColourByArray(MapperOf(actors_[SceneLayer::kHeightChange]), "change", change_lut_);
}

void SceneViewImpl::ColourLandmarks(vtkPolyDataMapper* mapper) {
  mapper->ScalarVisibilityOn();
  mapper->SetScalarModeToUsePointFieldData();
  if (options_.colouring == LandmarkColouring::kLabel) {
    mapper->SelectColorArray("label_rgb");
    mapper->SetColorModeToDirectScalars();
  } else {
    mapper->SelectColorArray("deviation");
    mapper->SetColorModeToMapScalars();
    mapper->SetLookupTable(deviation_lut_);
    mapper->UseLookupTableScalarRangeOn();
  }
  mapper->Modified();
}

void SceneViewImpl::UpdateFrusta() {
  vtkActor* actor = actors_[SceneLayer::kFrusta];
  const bool wanted = bundle_ && options_.IsVisible(SceneLayer::kFrusta);
  if (!wanted) {
    if (frusta_stride_built_ != 0) SetData(actor, vtkSmartPointer<vtkPolyData>::New());
    frusta_stride_built_ = 0;
    return;
  }
  const int stride = std::max(1, options_.frustum_stride);
  if (stride == frusta_stride_built_) return;
  SetData(actor, FrustaPolyData(ComputeFrusta(*bundle_, stride)));
  frusta_stride_built_ = stride;
}

void SceneViewImpl::ResetCamera() {
  Eigen::AlignedBox3d box;
  Pose placed = x_gM_;  // the hull's axes come from it
  if (overlays_ && !overlays_->bounds.isEmpty()) {
    box = overlays_->bounds;
  } else if (mesh_ && !mesh_->empty()) {
    for (const auto& v : mesh_->vertices) box.extend(x_gM_ * v);
  } else if (comparison_ && !comparison_->comparison.model.empty()) {
    for (const auto& v : comparison_->comparison.model.vertices) box.extend(x_gM_ * v);
  } else if (mosaic_ && HasLayerData(SceneLayer::kPhotomosaic)) {
    double b[6];
    actors_[SceneLayer::kPhotomosaic]->GetBounds(b);  // placed by the mosaic's x_gM
    box.extend(Eigen::Vector3d(b[0], b[2], b[4]));
    box.extend(Eigen::Vector3d(b[1], b[3], b[5]));
    placed = mosaic_->x_gM;
  } else {
    box.extend(Eigen::Vector3d(-1, -1, -1));
    box.extend(Eigen::Vector3d(1, 1, 1));
  }
  // The hull's axes in g. Seen from below (g is z down, so "below" is +z),
  // bow to the right and starboard up on the screen, tilted a little so
  // the view has depth.
  Eigen::Vector3d forward = placed.Rotate(Eigen::Vector3d::UnitX());
  Eigen::Vector3d up = placed.Rotate(Eigen::Vector3d::UnitZ());
  if (bundle_ && bundle_->manifest.model_axes) {
    forward = placed.Rotate(bundle_->manifest.model_axes->forward.normalized());
    up = placed.Rotate(bundle_->manifest.model_axes->up.normalized());
  }
  const Eigen::Vector3d starboard = forward.cross(up).normalized();
  const double tilt = 0.35;  // rad
  const Eigen::Vector3d view_from = (-up * std::cos(tilt) - starboard * std::sin(tilt)).normalized();
  const Eigen::Vector3d centre = box.center();
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(centre.data());
  const Eigen::Vector3d position = centre + view_from;
  camera->SetPosition(position.data());
  camera->SetViewUp(starboard.data());
  camera->SetViewAngle(30.0);
  double bounds[6] = {box.min().x(), box.max().x(), box.min().y(), box.max().y(), box.min().z(), box.max().z()};
  renderer_->ResetCamera(bounds);
  camera->Dolly(1.3);
  renderer_->ResetCameraClippingRange();
}

CameraState SceneViewImpl::Camera() const {
  CameraState state;
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->GetPosition(state.position.data());
  camera->GetFocalPoint(state.focal_point.data());
  camera->GetViewUp(state.view_up.data());
  state.view_angle = camera->GetViewAngle();
  return state;
}

void SceneViewImpl::SetCamera(const CameraState& state) {
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetPosition(state.position.data());
  camera->SetFocalPoint(state.focal_point.data());
  camera->SetViewUp(state.view_up.data());
  camera->SetViewAngle(state.view_angle);
  camera->OrthogonalizeViewUp();
  renderer_->ResetCameraClippingRange();
}

void SceneViewImpl::WarmUp() {
  if (!window_->GetReadyForRendering()) return;
  double focal[3];
  renderer_->GetActiveCamera()->GetFocalPoint(focal);
  const Eigen::Vector3d c(focal[0], focal[1], focal[2]);
  const double e = 1e-6;
  TriangleMesh tri;
  tri.vertices = {c, c + Eigen::Vector3d(e, 0, 0), c + Eigen::Vector3d(0, e, 0)};
  tri.faces = {Face{0, 1, 2}};
  tri.ComputeNormals();
  tri.SetScalar("deviation", {0.0, 0.01, -0.01});
  tri.SetScalar("sigma", {0.001, 0.002, 0.003});
  tri.SetScalar("change", {0.0, 0.01, -0.01});
  const std::vector<Eigen::Vector3d> points = {c, c + Eigen::Vector3d(e, 0, 0)};
  LandmarkMarker marker;
  marker.position = c;
  marker.has_truth = true;
  AdjustedLandmark adjusted;
  adjusted.position = c;
  KeyframeShapes shapes;
  DetectedShape shape;
  shape.vertices_g = tri.vertices;
  shape.triangles = tri.faces;
  shapes.shapes.push_back(shape);
  SlabBox slab;
  slab.centre = c;
  slab.half_extents = Eigen::Vector3d::Constant(e);

  std::map<SceneLayer, vtkSmartPointer<vtkPolyData>> saved;
  for (SceneLayer layer : AllSceneLayers()) {
    saved[layer] = DataOf(actors_[layer]);
    vtkSmartPointer<vtkPolyData> stand_in;
    switch (layer) {
      case SceneLayer::kHull:
      case SceneLayer::kPhotomosaic:
        stand_in = MeshPolyData(tri);
        break;
      case SceneLayer::kHeatmap:
      case SceneLayer::kSigmaHeatmap:
      case SceneLayer::kSignificance:
      case SceneLayer::kHeightChange:
        stand_in = HeatmapPolyData(tri);
        SetPointArray(stand_in, "sigma_mm", {1.0, 2.0, 3.0});
        SetPointArray(stand_in, "significant_deviation", {std::nan(""), 0.01, -0.01});
        SetPointArray(stand_in, "change", {0.0, 0.01, -0.01});
        break;
      case SceneLayer::kAlphaShapes:
        stand_in = AlphaShapesPolyData({shapes});
        break;
      case SceneLayer::kSlab:
        stand_in = SlabPolyData(slab);
        break;
      case SceneLayer::kLandmarks:
        stand_in = LandmarksPolyData({marker});
        break;
      case SceneLayer::kAdjustedLandmarks:
        stand_in = AdjustedLandmarksPolyData({adjusted});
        break;
      case SceneLayer::kDvlHits:
      case SceneLayer::kAdjustedDvlHits:
        stand_in = PointCloudPolyData(points);
        break;
      case SceneLayer::kTrajectory:
      case SceneLayer::kTrueTrajectory:
      case SceneLayer::kAdjustedTrajectory:
      case SceneLayer::kTruthObjects:
      case SceneLayer::kFrusta:
      case SceneLayer::kDetectedObjects:
        stand_in = PolylinePolyData(points);
        break;
    }
    SetData(actors_[layer], stand_in);
    actors_[layer]->SetVisibility(true);
  }
  const SceneOptions options = options_;
  for (LandmarkColouring colouring : {LandmarkColouring::kLabel, LandmarkColouring::kDeviation}) {
    options_.colouring = colouring;
    UpdateLandmarkColours();
    window_->Render();
  }
  options_ = options;
  for (auto& [layer, data] : saved) SetData(actors_[layer], data);
  UpdateLandmarkColours();
  UpdateVisibility();
}

void SceneViewImpl::Render() {
  renderer_->ResetCameraClippingRange();
  window_->Render();
  // The histogram follows the legend's colour bar, placed by the frame just drawn.
  int bar[4];
  legend_->GetScalarBarRect(bar, renderer_);
  if (legend_->GetVisibility() && histogram_->Place({{bar[0], bar[1], bar[2], bar[3]}})) window_->Render();
}

QImage SceneViewImpl::Grab() {
  if (!window_->GetReadyForRendering()) return {};
  Render();
  return GrabRenderWindow(window_);
}

PickInfo SceneViewImpl::Pick(double x, double y) {
  PickInfo info;
  selection_->VisibilityOff();
  HighlightObject(-1);
  if (!bundle_ || !overlays_) return info;
  // Landmarks first (adjusted, then truth), then keyframes, then objects:
  // the nearest point to the ray of the first layer that has one within the
  // tolerance.
  vtkActor* actor = nullptr;
  vtkIdType id = -1;
  for (SceneLayer layer : {SceneLayer::kAdjustedLandmarks, SceneLayer::kLandmarks, SceneLayer::kDetectedObjects,
                           SceneLayer::kAdjustedTrajectory, SceneLayer::kTrajectory, SceneLayer::kTrueTrajectory,
                           SceneLayer::kTruthObjects}) {
    vtkActor* candidate = actors_[layer];
    if (!candidate->GetVisibility()) continue;
    picker_->InitializePickList();
    picker_->AddPickList(candidate);
    if (picker_->Pick(x, y, 0.0, renderer_) && picker_->GetActor() == candidate && picker_->GetPointId() >= 0) {
      actor = candidate;
      id = picker_->GetPointId();
      break;
    }
  }
  if (!actor) return PickSurface(x, y);
  const int index = static_cast<int>(id);
  if (actor == actors_[SceneLayer::kAdjustedLandmarks]) {
    info = DescribeAdjustedLandmark(*adjusted_, index);
    if (info.kind != PickKind::kNone) info.position = ShowSelection(adjusted_->landmarks[index].position);
  } else if (actor == actors_[SceneLayer::kLandmarks]) {
    info = DescribeLandmark(*overlays_, index);
    if (info.kind != PickKind::kNone) info.position = ShowSelection(overlays_->landmarks[index].position);
  } else if (actor == actors_[SceneLayer::kDetectedObjects]) {
    vtkDataArray* owner = DataOf(actor)->GetPointData()->GetArray("object_index");
    const int object = owner ? static_cast<int>(owner->GetTuple1(id)) : -1;
    info = DescribeDetectedObject(*mapping_, object);
    if (info.kind != PickKind::kNone) {
      info.position = ShowSelection(mapping_->x_gM() * mapping_->result->objects[object].centroid_m);
    }
  } else if (actor == actors_[SceneLayer::kAdjustedTrajectory]) {
    info = DescribeAdjustedKeyframe(*bundle_, *overlays_, *adjusted_, index);
    if (info.kind != PickKind::kNone) info.position = ShowSelection(adjusted_->trajectory[index]);
  } else if (actor == actors_[SceneLayer::kTrajectory]) {
    info = DescribeKeyframe(*bundle_, *overlays_, index);
    if (info.kind != PickKind::kNone) info.position = ShowSelection(overlays_->trajectory[index]);
  } else if (actor == actors_[SceneLayer::kTrueTrajectory]) {
    if (index < static_cast<int>(overlays_->true_nav_index.size())) {
      info = DescribeKeyframe(*bundle_, *overlays_, overlays_->true_nav_index[index]);
      if (info.kind != PickKind::kNone) info.position = ShowSelection(overlays_->true_trajectory[index]);
    }
  } else if (actor == actors_[SceneLayer::kTruthObjects]) {
    vtkDataArray* owner = DataOf(actor)->GetPointData()->GetArray("object_index");
    const int object = owner ? static_cast<int>(owner->GetTuple1(id)) : -1;
    info = DescribeObject(*bundle_, *overlays_, object, x_gM_);
    if (info.kind != PickKind::kNone) info.position = ShowSelection(x_gM_ * overlays_->objects[object].center);
  }
  return info;
}

PickInfo SceneViewImpl::PickSurface(double x, double y) {
  for (SceneLayer layer : {SceneLayer::kHeatmap, SceneLayer::kSigmaHeatmap, SceneLayer::kSignificance,
                           SceneLayer::kHeightChange, SceneLayer::kHull}) {
    vtkActor* candidate = actors_[layer];
    if (!candidate->GetVisibility()) continue;
    surface_picker_->InitializePickList();
    surface_picker_->AddPickList(candidate);
    if (!surface_picker_->Pick(x, y, 0.0, renderer_) || surface_picker_->GetActor() != candidate) continue;
    const int face = static_cast<int>(surface_picker_->GetCellId());
    double* hit = surface_picker_->GetPickPosition();
    const Eigen::Vector3d p_g(hit[0], hit[1], hit[2]);
    PickInfo info;
    if (layer == SceneLayer::kHull && mesh_) {
      const int v = NearestCorner(*mesh_, face, x_gM_.Inverse() * p_g);
      info = DescribeCadPoint(*mesh_, face, v, x_gM_, mapping_.get());
    } else if (layer == SceneLayer::kHeightChange && comparison_) {
      const TriangleMesh& model = comparison_->comparison.model;
      info = DescribeChangePoint(*comparison_, NearestCorner(model, face, x_gM_.Inverse() * p_g), x_gM_);
    } else if (mapping_) {
      const TriangleMesh& model = mapping_->result->model;
      const int v = NearestCorner(model, face, mapping_->x_gM().Inverse() * p_g);
      info = DescribeModelPoint(*mapping_, v, significance_k_);
    }
    if (info.kind != PickKind::kNone) ShowSelection(*info.position);
    return info;
  }
  return {};
}

Eigen::Vector3d SceneViewImpl::ShowSelection(const Eigen::Vector3d& p_g) {
  SetData(selection_, PointCloudPolyData({p_g}));
  selection_->VisibilityOn();
  return p_g;
}

std::optional<std::pair<double, double>> SceneViewImpl::ToDisplay(const Eigen::Vector3d& p_g) const {
  int* size = window_->GetSize();
  if (!size || size[0] <= 0 || size[1] <= 0) return std::nullopt;
  renderer_->SetWorldPoint(p_g.x(), p_g.y(), p_g.z(), 1.0);
  renderer_->WorldToDisplay();
  double d[3];
  renderer_->GetDisplayPoint(d);
  return std::make_pair(d[0], d[1]);
}

}  // namespace hull::ui
