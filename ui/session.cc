#include "ui/session.h"

#include <algorithm>
#include <utility>

namespace hull::ui {

Session::Session(QObject* parent) : QObject(parent) {}

void Session::SetMesh(LoadedMesh mesh) {
  mesh_ = std::move(mesh);
  emit meshChanged();
}

void Session::SetSurvey(LoadedSurvey survey, std::optional<ModelPlacement> preferred) {
  survey_ = std::move(survey);
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
  mesh_.reset();
  emit meshChanged();
}

void Session::ClearSurvey() {
  if (!survey_) return;
  survey_.reset();
  const ModelPlacement old = placement_;
  placement_ = ModelPlacement::kIdentity;
  emit surveyChanged();
  if (placement_ != old) emit placementChanged();
}

std::vector<ModelPlacement> Session::AvailablePlacements() const { return ui::AvailablePlacements(bundle()); }

void Session::SetPlacement(ModelPlacement placement) {
  const std::vector<ModelPlacement> available = AvailablePlacements();
  if (std::find(available.begin(), available.end(), placement) == available.end() || placement == placement_) return;
  placement_ = placement;
  emit placementChanged();
}

Pose Session::ModelPose() const { return PlacementPose(bundle(), placement_); }

void Session::SetProjectPath(const QString& path) {
  if (path == project_path_) return;
  project_path_ = path;
  emit projectPathChanged();
}

}  // namespace hull::ui
