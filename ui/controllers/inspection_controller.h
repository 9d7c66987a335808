// Runs the inspection on what the Session holds, in worker threads: the
// initial alignment (once per mesh and survey) and the bundle adjustment
// (job kind "adjust"), then mapping ("map"), and the other surface models
// for the comparison ("compare"). Results are cached per parameter set, so
// that undoing a parameter change, or going back to values tried before,
// brings their results back at once.
//
// Nothing runs until Run(); from then on a change of the parameters re-runs
// only what depends on it: a change of sigma re-runs the adjustment
// warm-started from the last result of the same model, then mapping; a
// change of the model re-runs the adjustment from the alignment; a change
// of tau, alpha, eps or the object thresholds re-runs mapping only, with the
// adjustment's Mapper kept alive (its refined mesh and shapes are reused, so
// the re-run is instant). A newer run supersedes an older one (JobRunner); a
// cancelled or failed run leaves the last good result in the Session, and
// UpToDate() turns false until the parameters are run again.
//
// Object ids stay with the objects across the runs of one survey
// (ObjectIdentity, matched by position and footprint): the first run numbers
// them from the bow aft as the command line does, later ones keep the ids of
// the objects they find again and give new ones to the rest.
//
// A survey whose features come from its images (FrontEndController) runs
// once they are there: Run() before then waits for them, and new features
// (other front-end parameters) drop the cached results and re-run.
#pragma once

#include <QObject>
#include <QString>
#include <deque>
#include <map>
#include <memory>
#include <string>

#include "mapping/mapper.h"
#include "mapping/object_identity.h"
#include "pipeline/pipeline.h"
#include "ui/jobs/job_runner.h"
#include "ui/session/inspection_results.h"
#include "ui/session/parameters.h"
#include "ui/session/session.h"

namespace hull::ui {

class InspectionController : public QObject {
  Q_OBJECT

 public:
  static const QString kAdjustJob;
  static const QString kCompareJob;
  static const QString kMapJob;

  InspectionController(Session* session, JobRunner* jobs, QObject* parent = nullptr);

  // The parameters in force (valid: the parameter panel's values).
  void SetParameters(const ParameterValues& values);
  const ParameterValues& parameters() const { return values_; }

  bool CanRun() const;  // a mesh and a survey are open
  // Alignment (the first time) and adjustment for the current parameters.
  void Run();
  // The surface models other than the current one, for the parameters in
  // force (those not cached yet), in one job.
  void CompareModels();
  bool CanCompare() const;  // an adjustment of these inputs exists

  bool active() const { return active_; }  // Run() was asked for these inputs
  // The adjustment and the mapping on screen were run with the parameters in force.
  bool UpToDate() const;
  // What is on screen, in a line for the status bar.
  QString StatusText() const;
  std::size_t cachedRuns() const { return cache_.size(); }
  std::size_t cachedMappings() const { return map_cache_.size(); }
  // Mappers kept (one per adjustment mapped).
  std::size_t mappers() const { return mappers_.size(); }

 signals:
  // Results, their freshness or the running jobs changed.
  void stateChanged();

 private:
  // keep_active: the features changed, the survey did not (re-run if active).
  void ResetForInputs(bool keep_active = false);
  void Update();
  void StartAdjustment();
  std::shared_ptr<const AdjustmentRun> Cached(const std::string& key) const;
  void Store(const std::shared_ptr<const AdjustmentRun>& run);
  std::shared_ptr<const AdjustmentResult> WarmStart(SurfaceModel model) const;
  void UpdateModelRuns();
  void UpdateMapping();

  Session* session_;
  JobRunner* jobs_;
  ParameterValues values_;
  bool active_ = false;
  quint64 generation_ = 0;  // bumped when the inputs change: older jobs' results are dropped
  std::shared_ptr<const PipelineInputs> inputs_;
  std::map<std::string, std::shared_ptr<const AdjustmentRun>> cache_;
  std::deque<std::string> order_;  // least recently stored first
  std::map<std::string, std::shared_ptr<const MappingRun>> map_cache_;
  std::deque<std::string> map_order_;
  // A Mapper per adjustment (by its key), kept for instant re-runs.
  std::map<std::string, std::shared_ptr<Mapper>> mappers_;
  std::deque<std::string> mapper_order_;
  // The detected objects' ids across mapping runs of this survey: an object
  // keeps its id when tau, alpha, sigma or the thresholds change.
  ObjectIdentity object_ids_;
};

}  // namespace hull::ui
