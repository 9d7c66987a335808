#include "ui/controllers/report_export_controller.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <memory>

#include "results/results_folder.h"
#include "ui/report/report_job.h"

namespace hull::ui {

const QString ReportExportController::kReportJob = QStringLiteral("report");

ReportExportController::ReportExportController(JobRunner* jobs, QObject* parent) : QObject(parent), jobs_(jobs) {}

bool ReportExportController::busy() const { return jobs_->IsBusy(kReportJob); }

void ReportExportController::Cancel() { jobs_->Cancel(kReportJob); }

void ReportExportController::Export(report::ReportInputs inputs, const QString& folder, bool force) {
  const QString title = QStringLiteral("Cannot export the report");
  if (folder.isEmpty()) {
    emit failed(title, QStringLiteral("No folder given."));
    return;
  }
  const OutputFolder out{QFile::encodeName(QDir::cleanPath(QFileInfo(folder).absoluteFilePath())).toStdString(), force};
  ResultsRun run = NewResultsRun("gui report");
  try {
    report::CheckInputs(inputs);
    CheckResultsFolder(out);  // before any work, as the CLI does
    if (!inputs.bundle_path.empty()) run.AddSurvey("bundle", inputs.bundle_path);
    if (!inputs.mesh_path.empty()) run.AddFile("mesh", inputs.mesh_path);
  } catch (const std::exception& e) {
    emit failed(title, QString::fromStdString(e.what()));
    return;
  }
  auto shared = std::make_shared<const report::ReportInputs>(std::move(inputs));
  jobs_->Run<report::ReportFiles>(
      kReportJob, QStringLiteral("Writing the report"),
      [shared, out, run](Progress& progress) { return report::WriteReportFolder(*shared, out, run, progress); },
      [this](report::ReportFiles& files) {
        last_pdf_ = files.pdf;
        // Short: the status bar's permanent fields leave little room.
        const QFileInfo pdf(files.pdf);
        emit message(
            QStringLiteral("Report written: %1/report.pdf, %2 pages").arg(pdf.dir().dirName()).arg(files.pdf_pages));
        emit exported(files.pdf, files.html, files.pdf_pages);
      });
}

}  // namespace hull::ui
