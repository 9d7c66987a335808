#include "ui/controllers/survey_compare_controller.h"

#include <QFileInfo>
#include <memory>

#include "base/error.h"

namespace hull::ui {

const QString SurveyCompareController::kJob = QStringLiteral("compare-surveys");

SurveyCompareController::SurveyCompareController(Session* session, JobRunner* jobs, QObject* parent)
    : QObject(parent), session_(session), jobs_(jobs) {}

void SurveyCompareController::CompareFolders(const QString& a, const QString& b, const QString& mesh) {
  const std::string sa = a.toStdString(), sb = b.toStdString(), sm = mesh.toStdString();
  const SurveyCompareOptions o = options_;
  Session* session = session_;
  jobs_->Run<std::shared_ptr<const SurveyComparisonRun>>(
      kJob, QStringLiteral("Comparing %1 with %2").arg(QFileInfo(a).fileName(), QFileInfo(b).fileName()),
      [sa, sb, sm, o](Progress& progress) {
        return std::shared_ptr<const SurveyComparisonRun>(
            std::make_shared<SurveyComparisonRun>(RunSurveyComparison(sa, sb, sm, 1.0, o, progress)));
      },
      [session](std::shared_ptr<const SurveyComparisonRun>& run) { session->SetComparison(run); });
}

bool SurveyCompareController::CanCompareWithMapping() const {
  return session_->mapping() && session_->mesh() && session_->mesh()->mesh;
}

void SurveyCompareController::CompareWithMapping(const QString& a) {
  if (!CanCompareWithMapping()) return;
  const std::shared_ptr<const MappingRun> mapping = session_->mapping();
  const std::shared_ptr<const TriangleMesh> cad = session_->mesh()->mesh;
  const std::string sa = a.toStdString();
  const std::string mesh_path = session_->mesh()->path.toStdString();
  const std::string survey = session_->survey() ? session_->survey()->path.toStdString() : std::string();
  const SurveyCompareOptions o = options_;
  Session* session = session_;
  jobs_->Run<std::shared_ptr<const SurveyComparisonRun>>(
      kJob, QStringLiteral("Comparing %1 with the mapping on screen").arg(QFileInfo(a).fileName()),
      [sa, mapping, cad, mesh_path, survey, o](Progress& progress) {
        auto run = std::make_shared<SurveyComparisonRun>();
        const auto folder = FindMappingResults(sa);
        if (!folder)
          throw InputError({sa, 0, 0, ""}, "holds neither mapping results (model.ply) nor a pipeline's mapping/");
        run->folder_a = *folder;
        run->folder_b = survey.empty() ? std::string("the mapping on screen") : survey;
        run->mesh = mesh_path;
        progress.Update(0.0, "reading survey A's results");
        MappingResultsOnDisk ra = ReadMappingResultsForCompare(*folder);
        progress.ThrowIfCancelled();
        SubProgress sub(progress, 0.2, 1.0);
        run->comparison =
            CompareSurveys(*cad, ra.model, ra.objects, mapping->result->model, mapping->result->objects, o, sub);
        run->objects_a = std::move(ra.objects);
        run->objects_b = mapping->result->objects;
        return std::shared_ptr<const SurveyComparisonRun>(std::move(run));
      },
      [session](std::shared_ptr<const SurveyComparisonRun>& run) { session->SetComparison(run); });
}

}  // namespace hull::ui
