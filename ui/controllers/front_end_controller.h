// Runs the visual front end (core/vision) on the open survey's images in a
// worker (job kind "features", with progress and cancel) and puts what it
// found into the Session: the observations into the survey (so the bundle
// adjustment consumes them) and the per-keyframe features, matches and
// RANSAC verdicts for the images view.
//
// A version 2 bundle without features.csv is extracted as soon as it is
// opened (before any adjustment: the InspectionController waits for the
// features); any survey with images can be extracted again on request
// (Inspection > Extract features), replacing the features it came with. A
// change of a front-end parameter re-extracts when the features on screen
// came from the images; results are cached per parameter set, so an undo
// brings the previous features back at once.
#pragma once

#include <QObject>
#include <QString>
#include <deque>
#include <map>
#include <memory>
#include <string>

#include "ui/jobs/job_runner.h"
#include "ui/session/parameters.h"
#include "ui/session/session.h"

namespace hull::ui {

class FrontEndController : public QObject {
  Q_OBJECT

 public:
  static const QString kFeaturesJob;

  FrontEndController(Session* session, JobRunner* jobs, QObject* parent = nullptr);

  // The parameters in force (valid: the parameter panel's values).
  void SetParameters(const ParameterValues& values);
  // Off: a bundle without features.csv is not extracted when opened (tests).
  void SetAutomatic(bool automatic) { automatic_ = automatic; }

  bool CanExtract() const;  // the open survey has images
  // Extracts (again) with the parameters in force.
  void Extract();
  void Cancel();
  bool busy() const;
  std::size_t cachedResults() const { return cache_.size(); }

 signals:
  void stateChanged();

 private:
  struct Entry {
    std::shared_ptr<const SurveyBundle> bundle;
    std::shared_ptr<const SurveyOverlays> overlays;
    std::shared_ptr<const FrontEndResult> result;
  };
  void OnSurveyChanged();
  void Apply(const Entry& entry);

  Session* session_;
  JobRunner* jobs_;
  ParameterValues values_;
  bool automatic_ = true;
  quint64 generation_ = 0;
  // The survey as opened (its own features, if any, are not used).
  std::shared_ptr<const SurveyBundle> source_;
  std::map<std::string, Entry> cache_;
  std::deque<std::string> order_;
};

}  // namespace hull::ui
