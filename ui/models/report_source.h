// The hook for reports: everything the report needs from the application's
// current state, in the core's types (core/pipeline/pipeline.h's
// PipelineResult for the alignment, the adjustment on screen, the other
// models' runs and their evaluations; the mapping on screen), plus the
// inputs, the parameters and whether the results match them. Collecting
// copies the adjustment results (a few MB at most) and shares the rest; the
// report itself is written elsewhere.
#pragma once

#include <QString>
#include <memory>
#include <optional>
#include <string>

#include "mapping/mapping_result.h"
#include "pipeline/pipeline.h"
#include "results/compare_files.h"
#include "ui/report/report_inputs.h"
#include "ui/session/parameters.h"
#include "ui/session/session.h"

namespace hull::ui {

struct ReportSource {
  QString bundle_path, mesh_path;
  std::shared_ptr<const SurveyBundle> bundle;
  std::shared_ptr<const TriangleMesh> mesh;  // the CAD mesh in M
  ParameterValues parameters;                // the parameters in force
  bool up_to_date = false;                   // the results were computed with them
  // alignment, adjustment (the model on screen), baselines (the other models
  // run for the same parameters, if any) and the evaluations against truth.
  PipelineResult pipeline;
  std::shared_ptr<const MappingResult> mapping;  // nullptr: not mapped
  // The comparison with another survey on screen (nullptr: none).
  std::shared_ptr<const SurveyComparisonRun> comparison;
  // The photomosaic of the adjustment on screen (Inspection > Build
  // photomosaic): mosaic.ply's mesh with its per-vertex colour, for the
  // report's Photomosaic section (report_inputs.h: mosaic, mosaic_path), and
  // the results folder it was written into. nullptr / "": none, or the
  // mosaic on screen was opened from a folder or made from other results.
  std::shared_ptr<const TriangleMesh> mosaic;
  std::string mosaic_path;
  std::string results_path;
};

// The report library's inputs (ui/report/report_inputs.h) of a snapshot.
report::ReportInputs ReportInputsOf(const ReportSource& source);

// nullopt until the session holds an alignment and an adjustment.
std::optional<ReportSource> CollectReportSource(const Session& session, const ParameterValues& parameters,
                                                bool up_to_date);

}  // namespace hull::ui
