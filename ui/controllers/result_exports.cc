#include "ui/controllers/result_exports.h"

#include <cmath>
#include <optional>

#include <QDir>
#include <QFile>
#include <QFileInfo>

#include "base/csv.h"
#include "base/file_io.h"
#include "pipeline/model_export.h"

namespace hull::ui {

std::string ObjectsCsv(const MappingResult& r) {
  CsvWriter csv({"id", "x", "y", "z", "nx", "ny", "nz", "distance_from_bow", "station", "side", "area", "mean_height",
                 "max_height", "features", "views", "keyframes", "p95_height", "max_height_sigma"});
  for (const DetectedObject& o : r.objects) {
    csv.Add(o.id);
    for (int k = 0; k < 3; ++k) csv.Add(o.centroid_m[k]);
    for (int k = 0; k < 3; ++k) csv.Add(o.normal_m[k]);
    csv.Add(o.distance_from_bow).Add(o.station).Add(HullSideName(o.side)).Add(o.area).Add(o.mean_height);
    std::string keyframes;
    for (std::size_t i = 0; i < o.keyframes.size(); ++i) {
      keyframes += (i ? " " : "") + std::to_string(o.keyframes[i]);
    }
    csv.Add(o.max_height).Add(o.num_features).Add(o.num_views).Add(keyframes).Add(o.p95_height);
    csv.AddOptional(std::isfinite(o.max_height_sigma) ? std::optional<double>(o.max_height_sigma) : std::nullopt);
    csv.EndRow();
  }
  return csv.Take();
}

std::string ZonesCsv(const MappingResult& r) {
  CsvWriter csv({"station", "side", "from_bow", "to_bow", "hull_area", "inspected_area", "covered_area",
                 "cover_percent", "objects", "mean_height", "max_height", "rating", "note"});
  for (const ZoneAssessment& z : r.zones) {
    csv.Add(z.station).Add(HullSideName(z.side)).Add(z.from_bow).Add(z.to_bow).Add(z.hull_area);
    csv.Add(z.inspected_area).Add(z.covered_area).Add(z.cover_percent).Add(z.objects).Add(z.mean_height);
    csv.Add(z.max_height).Add(FoulingRatingName(z.rating)).Add(z.note);
    csv.EndRow();
  }
  return csv.Take();
}

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
         [](const MappingResult& r, const std::string& target) { WriteFileAtomic(target, ObjectsCsv(r)); });
}

void ResultExporter::ExportZones(const QString& path) {
  Export(path, QStringLiteral("the zones"),
         [](const MappingResult& r, const std::string& target) { WriteFileAtomic(target, ZonesCsv(r)); });
}

}  // namespace hull::ui
