// "Compare with…": the change between two surveys of one hull, computed by
// the core's comparison (mapping/survey_compare.h) in a worker job (kind
// "compare-surveys", with progress and Cancel) and put into the Session.
// Either two results folders (mapping or pipeline results; A the earlier
// survey), or one results folder (A) against the mapping on screen (B, with
// the open mesh as the CAD both were mapped against).
#pragma once

#include <QObject>
#include <QString>

#include "mapping/survey_compare.h"
#include "ui/jobs/job_runner.h"
#include "ui/session/session.h"

namespace hull::ui {

class SurveyCompareController : public QObject {
  Q_OBJECT

 public:
  static const QString kJob;

  SurveyCompareController(Session* session, JobRunner* jobs, QObject* parent = nullptr);

  void SetOptions(const SurveyCompareOptions& options) { options_ = options; }
  const SurveyCompareOptions& options() const { return options_; }

  // Two results folders; the CAD is `mesh` or the one A's mapping.json names.
  void CompareFolders(const QString& a, const QString& b, const QString& mesh = {});
  // A mapping on screen and a mesh are open.
  bool CanCompareWithMapping() const;
  // The earlier survey's results folder (A) against the mapping on screen (B).
  void CompareWithMapping(const QString& a);

 private:
  Session* session_;
  JobRunner* jobs_;
  SurveyCompareOptions options_;
};

}  // namespace hull::ui
