// The report of a sonar run (ReportInputs::sonar: the results of
// `hullinspect-cli sonar` or the GUI's sonar dock, results/sonar_files.h):
// what the acoustic images or the given measurements gave, the features
// the filter (and the smoother) placed with their uncertainty, whether that
// uncertainty is consistent with what the run saw (NIS without truth, NEES
// with it), and the errors against the truth when the sequence has one.
// WriteReport() takes this path when the inputs hold a sonar run; the HTML
// and PDF writers lay the document out as they do the hull report's.
#pragma once

#include <string>
#include <vector>

#include "ui/report/report_document.h"

namespace hull::report {

// Section ids of the sonar report, in order.
std::vector<std::string> SonarSectionIds();

// The figures: the plan view of trajectory and features, and (with truth)
// the errors per step.
std::vector<FigureRef> PlanSonarFigures(const ReportInputs& in);

ReportDocument BuildSonarReportDocument(const ReportInputs& in, const ReportOptions& options,
                                        const std::vector<FigureRef>& figures, const std::string& generated);

// A chi-square consistency check: a normalised error `value` with `dof`
// degrees of freedom against the two-sided 95 % interval of its
// distribution.
struct ConsistencyCheck {
  double value = 0;
  int dof = 0;
  double low = 0, high = 0;  // the 2.5 % and 97.5 % quantiles
  bool consistent = false;   // low <= value <= high
  bool known = false;        // a finite value with dof >= 1
};
ConsistencyCheck CheckConsistency(double value, int dof);

}  // namespace hull::report
