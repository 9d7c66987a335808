// The report's result sections (internal to ui/report): what mapping found
// (objects, zone ratings), how the solver ran, the evaluation against truth
// and what was not inspected. BuildReportDocument puts them after the survey,
// method, deviation and cross-section sections.
#pragma once

#include <vector>

#include "ui/report/report_document.h"

namespace hull::report {

Section ObjectsSection(const ReportInputs& in);
Section ZonesSection(const ReportInputs& in);
Section SolverSection(const ReportInputs& in, const std::vector<FigureRef>& figures);
Section EvaluationSection(const ReportInputs& in);
Section NotInspectedSection(const ReportInputs& in);
// The first section's one-line account of what was not seen (zones, keyframes).
std::string NotSeenSummary(const ReportInputs& in);

// report_trust_sections.cc: uncertainty, significance and change between
// surveys. PlanTrustFigures appends, for every heatmap view already planned
// in `figures`, the sigma and significance heatmaps (when the fused model
// has per-vertex sigmas) and the change heatmap (with a comparison).
void PlanTrustFigures(const ReportInputs& in, const ReportOptions& options, std::vector<FigureRef>& figures);
Section UncertaintySection(const ReportInputs& in, const ReportOptions& options, const std::vector<FigureRef>& figures);
Section ChangeSection(const ReportInputs& in, const std::vector<FigureRef>& figures);

// The photomosaic (with a mosaic in the inputs): PlanMosaicFigures appends a
// mosaic figure for every heatmap view already planned; MosaicSection shows
// them, or says how to make a mosaic.
void PlanMosaicFigures(const ReportInputs& in, std::vector<FigureRef>& figures);
Section MosaicSection(const ReportInputs& in, const std::vector<FigureRef>& figures);

}  // namespace hull::report
