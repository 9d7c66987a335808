// What is open: the hull mesh, the survey bundle (with what the scene draws
// of it) and where the model is placed in g. The document of the
// application; views and panels follow its signals. Later rounds add the
// pipeline's results here (alignment, adjusted poses and landmarks, maps).
#pragma once

#include <QObject>
#include <QString>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "survey/survey.h"
#include "ui/survey_overlays.h"

namespace hull::ui {

struct LoadedMesh {
  QString path;
  std::shared_ptr<const TriangleMesh> mesh;  // in M
};

struct LoadedSurvey {
  QString path;  // the bundle folder
  std::shared_ptr<const SurveyBundle> bundle;
  std::shared_ptr<const SurveyOverlays> overlays;
};

class Session : public QObject {
  Q_OBJECT

 public:
  explicit Session(QObject* parent = nullptr);

  const std::optional<LoadedMesh>& mesh() const { return mesh_; }
  const std::optional<LoadedSurvey>& survey() const { return survey_; }
  const SurveyBundle* bundle() const { return survey_ ? survey_->bundle.get() : nullptr; }

  void SetMesh(LoadedMesh mesh);
  // Also picks the placement: `preferred` when the survey offers it, else the
  // best available (truth, then the guess, then identity).
  void SetSurvey(LoadedSurvey survey, std::optional<ModelPlacement> preferred = std::nullopt);
  void ClearMesh();
  void ClearSurvey();

  ModelPlacement placement() const { return placement_; }
  std::vector<ModelPlacement> AvailablePlacements() const;
  void SetPlacement(ModelPlacement placement);
  // x_gM: places the mesh (frame M) in the survey frame g.
  Pose ModelPose() const;

  // The project file this session was last saved to or opened from ("" if none).
  const QString& projectPath() const { return project_path_; }
  void SetProjectPath(const QString& path);

 signals:
  void meshChanged();
  void surveyChanged();
  void placementChanged();
  void projectPathChanged();

 private:
  std::optional<LoadedMesh> mesh_;
  std::optional<LoadedSurvey> survey_;
  ModelPlacement placement_ = ModelPlacement::kIdentity;
  QString project_path_;
};

}  // namespace hull::ui
