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

}  // namespace hull::report
