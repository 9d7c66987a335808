// hullinspect-cli report: the inspection report (PDF and HTML) of a results
// folder, the same job as `hullinspect --report` (ui/report/report_job.h).
#include <QGuiApplication>
#include <cstdio>
#include <memory>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "ui/report/headless_job.h"
#include "ui/report/report_job.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli report RESULTS --out DIR [options]

The inspection report of a results folder: DIR/report.pdf (A4),
DIR/report.html (self-contained) and every figure as DIR/figures/*.png.
RESULTS is
  a pipeline's results ('run', 'hullinspect --demo', the GUI's saved
  results; with its mapping/ and mosaic/ when present): the hull report
  (summary and what was not seen, method, deviation and uncertainty
  heatmaps, cross-section, photomosaic, objects, zones with their IMO
  rating, solver, evaluation against truth when there is one);
  a comparison's ('compare'): the hull report of survey B with the change
  since survey A;
  a sonar run's ('sonar'): the sonar report (features with their
  uncertainty, the consistency of the estimate, the images, the smoother,
  the errors against truth when there is one).
DIR is a folder of its own (not RESULTS, nor one holding it; RESULTS/report
will do), replaced as a whole: a report that fails or is interrupted leaves
the previous one as it was. Needs no display (Qt's offscreen platform).

options:
  --out DIR            output folder (required)
  --compare-with A     with a pipeline's results: compare with an earlier
                       survey's results A (both mapped against the same CAD
                       mesh) for the report's "Change between surveys"
  --quiet              no progress output
  --force              write into an --out folder that holds files HullInspect
                       did not write (they are kept; none is replaced)
)";

// The report draws with QPainter into images and a PDF: a QGuiApplication on
// the offscreen platform, whatever the display.
std::unique_ptr<QGuiApplication> OffscreenApplication() {
  if (QGuiApplication::instance()) return nullptr;
  static int argc = 1;
  static char name[] = "hullinspect-cli";
  static char* argv[] = {name, nullptr};
  report::PrepareHeadless();
  return std::make_unique<QGuiApplication>(argc, argv);
}

}  // namespace

int RunReport(const CommandArgs& argv) {
  Args a(argv, {"help", "quiet", "force"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out", "compare-with", "quiet", "force"});
  if (a.positionals().size() != 1) throw UsageError("expected one results folder");
  if (!a.Has("out")) throw UsageError("--out DIR is required");
  const report::FolderReportRequest request{a.positionals()[0], a.Get("compare-with", ""),
                                            OutputFolder{a.Get("out"), a.Has("force")}};
  report::CheckFolderReportRequest(request);
  const std::unique_ptr<QGuiApplication> app = OffscreenApplication();
  ConsoleProgress progress(a.Has("quiet"));
  const report::ReportFiles files = report::RunFolderReport(request, "report", progress);
  progress.Finish();
  std::printf("report:   %s\n          %s (%d pages)\n", files.pdf.toStdString().c_str(),
              files.html.toStdString().c_str(), files.pdf_pages);
  std::printf("figures:  %d in %s/figures\n", static_cast<int>(files.figures.size()), a.Get("out").c_str());
  return kExitOk;
}

}  // namespace hull::cli
