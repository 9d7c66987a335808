// The report of a results folder, one job for `hullinspect-cli report` and
// `hullinspect --report` (and the GUI's File > Export report through
// WriteReportFolder): the folder's kind is read from what it holds --
//   a pipeline's results (summary.json of `run`, `hullinspect --demo`, the
//     GUI), with its mapping/ and mosaic/ when present: the hull report;
//   a comparison's (`compare`: compare.json): the hull report of survey B
//     (the results its manifest names) with the change since survey A;
//   a sonar run's (`sonar`: summary.json "hull-sonar-result"): the sonar
//     report (sonar_report.h)
// -- and the report (report.html, report.pdf, figures/*.png) is written as a
// results folder of its own (results/results_folder.h: --out absent, empty
// or a report of ours; replaced as a whole, so a failed or cancelled report
// leaves the previous one byte-identical).
#pragma once

#include <string>

#include "base/progress.h"
#include "results/results_folder.h"
#include "ui/report/report.h"

namespace hull::report {

enum class ReportSourceKind { kPipeline, kComparison, kSonar };
const char* ReportSourceKindName(ReportSourceKind kind);  // "pipeline", "comparison", "sonar"

// What `results` holds. Throws InputError naming the folder when it is
// none of the above (a mapping folder alone, a folder of something else).
ReportSourceKind ClassifyReportSource(const std::string& results);

struct FolderReportRequest {
  std::string results;  // the results folder to report on
  std::string earlier;  // pipeline results only: an earlier survey's results ("" : none)
  OutputFolder out;     // where the report goes
};

// Before any work: the request makes sense (the output is not the results
// folder nor holds it, --compare-with only with pipeline results) and the
// output folder can be written (CheckResultsFolder). Throws OptionError
// (exit 2) or InputError (exit 3) naming the folder.
void CheckFolderReportRequest(const FolderReportRequest& request);

// Reads the results (and compares with `earlier` when given).
ReportInputs ReadFolderReportInputs(const FolderReportRequest& request, Progress& progress);

// Writes `inputs`' report as the results folder `out` (report.html,
// report.pdf, figures/), recording `run`. Returns the files at their final
// paths. hull::Cancelled when progress asks to stop between figures: the
// previous folder is then untouched.
ReportFiles WriteReportFolder(const ReportInputs& inputs, const OutputFolder& out, ResultsRun run, Progress& progress,
                              const ReportOptions& options = {});

// CheckFolderReportRequest, ReadFolderReportInputs and WriteReportFolder
// with the run recorded as `command` (e.g. "report", "hullinspect --report").
ReportFiles RunFolderReport(const FolderReportRequest& request, const std::string& command, Progress& progress);

}  // namespace hull::report
