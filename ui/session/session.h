// What is open: the hull mesh, the survey bundle (with what the scene draws
// of it), where the model is placed in g, and the pipeline's results for
// them (the alignment, the adjustment on screen, the runs of each surface
// model for the comparison and the mapping on screen). The document of the application; views and
// panels follow its signals. Opening another mesh or survey drops the
// results.
#pragma once

#include <QObject>
#include <QString>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "registration/model_alignment.h"
#include "results/compare_files.h"
#include "survey/survey.h"
#include "ui/session/inspection_results.h"
#include "ui/session/mosaic_layer.h"
#include "ui/session/survey_overlays.h"
#include "vision/front_end.h"

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

  // The pipeline's results (nullptr: none yet).
  using ModelRuns = std::map<SurfaceModel, std::shared_ptr<const AdjustmentRun>>;
  const std::shared_ptr<const ModelAlignment>& alignment() const { return alignment_; }
  const std::shared_ptr<const AdjustmentRun>& adjustment() const { return adjustment_; }
  // The run of each surface model for the current parameters, as far as
  // they were computed (the adjustment on screen is one of them).
  const ModelRuns& modelRuns() const { return model_runs_; }
  void SetAlignment(std::shared_ptr<const ModelAlignment> alignment);
  // The first adjustment, and any while the model is placed by the
  // adjustment, places the model by its x_gM.
  void SetAdjustment(std::shared_ptr<const AdjustmentRun> run);
  void SetModelRuns(ModelRuns runs);
  // The mapping on screen (of the adjustment on screen, normally).
  const std::shared_ptr<const MappingRun>& mapping() const { return mapping_; }
  void SetMapping(std::shared_ptr<const MappingRun> run);
  // Drops every result of the inputs open: the adjustments, the mapping, and
  // the comparison and photomosaic shown with them (another mesh, survey or
  // set of features makes them another survey's: issue 25.5).
  void ClearResults();
  // The comparison of two surveys on screen (nullptr: none); it may be
  // shown without a survey open, and goes when one is opened.
  const std::shared_ptr<const SurveyComparisonRun>& comparison() const { return comparison_; }
  void SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison);
  // The photomosaic on screen (nullptr: none), opened from a results or
  // mosaic folder; like the comparison, it goes with the inputs.
  const std::shared_ptr<const MosaicLayer>& mosaic() const { return mosaic_; }
  void SetMosaic(std::shared_ptr<const MosaicLayer> mosaic);

  // What the visual front end found in the survey's images (nullptr: the
  // features came with the bundle, or none extracted yet), and whether the
  // open survey still needs it: images and no feature observations.
  const std::shared_ptr<const FrontEndResult>& frontEnd() const { return front_end_; }
  bool NeedsFeatureExtraction() const;
  bool HasImages() const;
  // Puts extracted features into the survey: `bundle` is the open survey's
  // bundle with the front end's observations, `overlays` computed from it.
  // Drops the results (they were computed from other features) and emits
  // featuresChanged, not surveyChanged: the survey is the same.
  void SetExtractedFeatures(std::shared_ptr<const SurveyBundle> bundle, std::shared_ptr<const SurveyOverlays> overlays,
                            std::shared_ptr<const FrontEndResult> front_end);

  // The project file this session was last saved to or opened from ("" if none).
  const QString& projectPath() const { return project_path_; }
  void SetProjectPath(const QString& path);

 signals:
  void meshChanged();
  void surveyChanged();
  void placementChanged();
  void projectPathChanged();
  void alignmentChanged();
  void adjustmentChanged();
  void modelRunsChanged();
  void mappingChanged();
  void featuresChanged();
  void comparisonChanged();
  void mosaicChanged();

 private:
  std::optional<LoadedMesh> mesh_;
  std::optional<LoadedSurvey> survey_;
  ModelPlacement placement_ = ModelPlacement::kIdentity;
  QString project_path_;
  std::shared_ptr<const ModelAlignment> alignment_;
  std::shared_ptr<const AdjustmentRun> adjustment_;
  ModelRuns model_runs_;
  std::shared_ptr<const MappingRun> mapping_;
  std::shared_ptr<const FrontEndResult> front_end_;
  std::shared_ptr<const SurveyComparisonRun> comparison_;
  std::shared_ptr<const MosaicLayer> mosaic_;
};

}  // namespace hull::ui
