#include "ui/controllers/result_exports.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>

#include "pipeline/model_export.h"
#include "results/mapping_files.h"

namespace hull::ui {

ResultExporter::ResultExporter(Session* session, JobRunner* jobs, QObject* parent)
    : QObject(parent), session_(session), jobs_(jobs) {}

void ResultExporter::Export(const QString& path, const QString& what,
                            std::function<void(const MappingResult&, const std::string&)> write) {
  if (!session_->mapping()) {
    emit failed(QStringLiteral("Cannot export"), QStringLiteral("There is no map yet: run the inspection first."));
    return;
  }
  const std::shared_ptr<const MappingResult> result = session_->mapping()->result;
  const std::string target = QFile::encodeName(path).toStdString();
  // One job kind per file: exports of different files all complete; a new
  // export of the same file replaces one still running.
  jobs_->Start(
      QStringLiteral("export:") + QFileInfo(path).absoluteFilePath(),
      QStringLiteral("Export %1").arg(QFileInfo(path).fileName()),
      [result, target, write = std::move(write)](Progress& progress) {
        progress.Update(0.0, "writing " + target);
        write(*result, target);
      },
      [this, path, what] {
        emit message(QStringLiteral("Exported %1 to %2").arg(what, QDir::toNativeSeparators(path)));
      });
}

void ResultExporter::ExportModel(const QString& path) {
  Export(path, QStringLiteral("the remeshed model"),
         [](const MappingResult& r, const std::string& target) { hull::ExportModel(r.model, "", target); });
}

void ResultExporter::ExportObjects(const QString& path) {
  Export(path, QStringLiteral("the detected objects"),
         [](const MappingResult& r, const std::string& target) { WriteObjectsCsv(r, target); });
}

void ResultExporter::ExportZones(const QString& path) {
  Export(path, QStringLiteral("the zones"),
         [](const MappingResult& r, const std::string& target) { WriteZonesCsv(r, target); });
}

}  // namespace hull::ui
