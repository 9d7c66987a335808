// File > Export > Report: the inspection report (report.pdf, report.html,
// figures/) of the results on screen, written in a worker (job kind
// "report", with progress and cancel) by the report library's
// WriteReportFolder (ui/report/report_job.h) -- the job `hullinspect-cli
// report` and `hullinspect --report` run -- into a folder the user chooses.
// The folder is a results folder of its own, replaced in one swap when the
// report is complete: a cancelled or failed export leaves an earlier report
// in it byte-identical. A folder holding files HullInspect did not write is
// refused unless `force` (the user confirmed; their files are kept). The
// inputs are a snapshot (models/report_source.h): what the session changes
// meanwhile does not reach a report being written.
#pragma once

#include <QObject>
#include <QString>

#include "ui/jobs/job_runner.h"
#include "ui/report/report_inputs.h"

namespace hull::ui {

class ReportExportController : public QObject {
  Q_OBJECT

 public:
  static const QString kReportJob;

  explicit ReportExportController(JobRunner* jobs, QObject* parent = nullptr);

  void Export(report::ReportInputs inputs, const QString& folder, bool force = false);
  void Cancel();
  bool busy() const;
  // The PDF of the last report written ("" : none yet).
  const QString& lastPdf() const { return last_pdf_; }

 signals:
  void exported(const QString& pdf, const QString& html, int pages);
  void failed(const QString& title, const QString& message);
  void message(const QString& text);  // for the status bar

 private:
  JobRunner* jobs_;
  QString last_pdf_;
};

}  // namespace hull::ui
