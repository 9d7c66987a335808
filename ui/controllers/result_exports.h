// Exports of the mapping on screen, in jobs (kind "export:<file>"): the fused,
// remeshed model (PLY with the per-vertex "deviation" and "fusions", OBJ,
// STL, or an exporter plugin's format such as glTF, by the extension) and the detected objects and zones as CSV, in the
// columns of the results format (docs/results-format.md: objects.csv and
// zones.csv: ObjectsCsv and ZonesCsv of mapping/mapping_result.h). Errors go
// through failed(); nothing here shows a dialog.
#pragma once

#include <QObject>
#include <QString>
#include <string>

#include "mapping/mapping_result.h"
#include "ui/jobs/job_runner.h"
#include "ui/session/session.h"

namespace hull::ui {

class ResultExporter : public QObject {
  Q_OBJECT

 public:
  ResultExporter(Session* session, JobRunner* jobs, QObject* parent = nullptr);

  bool CanExport() const { return session_->mapping() != nullptr; }
  void ExportModel(const QString& path);
  void ExportObjects(const QString& path);
  void ExportZones(const QString& path);

 signals:
  void failed(const QString& title, const QString& message);
  void message(const QString& text);

 private:
  void Export(const QString& path, const QString& what,
              std::function<void(const MappingResult&, const std::string&)> write);

  Session* session_;
  JobRunner* jobs_;
};

}  // namespace hull::ui
