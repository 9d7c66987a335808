#include "ui/session/session.h"

#include <algorithm>
#include <utility>

namespace hull::ui {

Session::Session(QObject* parent) : QObject(parent) {}

void Session::SetMesh(LoadedMesh mesh) {
  ClearResults();
  mesh_ = std::move(mesh);
  emit meshChanged();
}

void Session::SetSurvey(LoadedSurvey survey, std::optional<ModelPlacement> preferred) {
  ClearResults();
  survey_ = std::move(survey);
  front_end_.reset();
  const std::vector<ModelPlacement> available = AvailablePlacements();
  const ModelPlacement old = placement_;
  if (preferred && std::find(available.begin(), available.end(), *preferred) != available.end()) {
    placement_ = *preferred;
  } else {
    placement_ = available.front();
  }
  emit surveyChanged();
  if (placement_ != old) emit placementChanged();
}

void Session::ClearMesh() {
  if (!mesh_) return;
  ClearResults();
  mesh_.reset();
  emit meshChanged();
}

void Session::ClearSurvey() {
  if (!survey_) return;
  ClearResults();
  survey_.reset();
  front_end_.reset();
  const ModelPlacement old = placement_;
  placement_ = ModelPlacement::kIdentity;
  emit surveyChanged();
  if (placement_ != old) emit placementChanged();
}

std::vector<ModelPlacement> Session::AvailablePlacements() const {
  std::vector<ModelPlacement> out = ui::AvailablePlacements(bundle());
  if (adjustment_) out.insert(out.begin(), ModelPlacement::kAdjusted);
  return out;
}

void Session::SetPlacement(ModelPlacement placement) {
  const std::vector<ModelPlacement> available = AvailablePlacements();
  if (std::find(available.begin(), available.end(), placement) == available.end() || placement == placement_) return;
  placement_ = placement;
  emit placementChanged();
}

Pose Session::ModelPose() const {
  if (placement_ == ModelPlacement::kAdjusted && adjustment_) return adjustment_->x_gM();
  return PlacementPose(bundle(), placement_);
}

void Session::SetAlignment(std::shared_ptr<const ModelAlignment> alignment) {
  if (alignment == alignment_) return;
  alignment_ = std::move(alignment);
  emit alignmentChanged();
}

void Session::SetAdjustment(std::shared_ptr<const AdjustmentRun> run) {
  if (run == adjustment_) return;
  const bool first = !adjustment_;
  adjustment_ = std::move(run);
  emit adjustmentChanged();
  if (!adjustment_) {
    if (placement_ == ModelPlacement::kAdjusted) {
      placement_ = AvailablePlacements().front();
      emit placementChanged();
    }
    return;
  }
  if (first || placement_ == ModelPlacement::kAdjusted) {
    placement_ = ModelPlacement::kAdjusted;
    emit placementChanged();  // the pose changed even when the placement did not
  }
}

void Session::SetModelRuns(ModelRuns runs) {
  if (runs == model_runs_) return;
  model_runs_ = std::move(runs);
  emit modelRunsChanged();
}

void Session::SetMapping(std::shared_ptr<const MappingRun> run) {
  if (run == mapping_) return;
  mapping_ = std::move(run);
  emit mappingChanged();
}

void Session::SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison) {
  if (comparison == comparison_) return;
  comparison_ = std::move(comparison);
  emit comparisonChanged();
}

void Session::SetMosaic(std::shared_ptr<const MosaicLayer> mosaic) {
  if (mosaic == mosaic_) return;
  mosaic_ = std::move(mosaic);
  emit mosaicChanged();
}

void Session::ClearResults() {
  SetComparison(nullptr);
  SetMosaic(nullptr);
  SetMapping(nullptr);
  const bool had_runs = !model_runs_.empty();
  model_runs_.clear();
  SetAdjustment(nullptr);
  SetAlignment(nullptr);
  if (had_runs) emit modelRunsChanged();
}

bool Session::HasImages() const {
  const SurveyBundle* b = bundle();
  return b && b->images && b->images->present() > 0;
}

bool Session::NeedsFeatureExtraction() const { return HasImages() && bundle()->features.empty(); }

void Session::SetExtractedFeatures(std::shared_ptr<const SurveyBundle> bundle,
                                   std::shared_ptr<const SurveyOverlays> overlays,
                                   std::shared_ptr<const FrontEndResult> front_end) {
  if (!survey_) return;
  ClearResults();
  survey_->bundle = std::move(bundle);
  survey_->overlays = std::move(overlays);
  front_end_ = std::move(front_end);
  emit featuresChanged();
}

void Session::SetProjectPath(const QString& path) {
  if (path == project_path_) return;
  project_path_ = path;
  emit projectPathChanged();
}

}  // namespace hull::ui
