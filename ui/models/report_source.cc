#include "ui/models/report_source.h"

#include <QFile>
#include <filesystem>
#include <memory>

namespace hull::ui {

std::optional<ReportSource> CollectReportSource(const Session& session, const ParameterValues& parameters,
                                                bool up_to_date) {
  if (!session.alignment() || !session.adjustment() || !session.survey() || !session.mesh()) return std::nullopt;
  ReportSource r;
  r.bundle_path = session.survey()->path;
  r.mesh_path = session.mesh()->path;
  r.bundle = session.survey()->bundle;
  r.mesh = session.mesh()->mesh;
  r.parameters = parameters;
  r.up_to_date = up_to_date;
  r.pipeline.alignment = *session.alignment();
  const AdjustmentRun& run = *session.adjustment();
  r.pipeline.adjustment = *run.result;
  r.pipeline.evaluation = run.evaluation;
  for (const auto& [model, other] : session.modelRuns()) {
    if (model == run.model()) continue;
    r.pipeline.baselines.push_back(*other->result);
    if (other->evaluation) r.pipeline.baseline_evaluations.push_back(*other->evaluation);
  }
  if (session.mapping()) r.mapping = session.mapping()->result;
  r.comparison = session.comparison();
  if (const auto& mosaic = session.mosaic();
      mosaic && mosaic->coloured && !mosaic->adjustment_key.empty() && mosaic->adjustment_key == run.key) {
    r.mosaic = mosaic->coloured;
    r.mosaic_path = mosaic->ply;
    r.results_path = std::filesystem::path(mosaic->dir).parent_path().string();
  }
  return r;
}

report::ReportInputs ReportInputsOf(const ReportSource& s) {
  report::ReportInputs in;
  in.bundle = s.bundle;
  in.cad = s.mesh;
  in.pipeline = std::make_shared<const PipelineResult>(s.pipeline);
  in.mapping = s.mapping;
  in.comparison = s.comparison;
  in.mosaic = s.mosaic;
  in.mosaic_path = s.mosaic_path;
  in.bundle_path = QFile::encodeName(s.bundle_path).toStdString();
  in.mesh_path = QFile::encodeName(s.mesh_path).toStdString();
  in.results_path = s.results_path;
  return in;
}

}  // namespace hull::ui
