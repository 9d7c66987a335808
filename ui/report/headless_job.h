// hullinspect's headless main job, for machines without a display:
//
//   hullinspect --demo [--out DIR]          (DIR defaults to ./demo-output)
//     simulates the embedded demo survey into DIR/demo-survey, runs the whole
//     pipeline on it (alignment, the three surface models, mapping) and
//     writes the results (WritePipelineResult's files and DIR/mapping/ with
//     the remeshed model as PLY with deviation, OBJ and STL, objects and
//     zones as CSV and JSON) and the report (DIR/report.html, report.pdf,
//     DIR/figures/*.png);
//   hullinspect --report RESULTS [--compare-with EARLIER] --out DIR
//     writes the report again from a results folder (results_reader.h);
//     with --compare-with, the change since an earlier survey's results
//     (mapping/survey_compare.h) makes its "Change between surveys" section.
//
// Progress goes to stderr, the paths written to stdout. The caller creates a
// QGuiApplication first, on the offscreen platform (PrepareHeadless()): the
// report's figures are drawn with QPainter, never through VTK or X.
#pragma once

#include <QString>
#include <QStringList>

namespace hull::report {

struct HeadlessCommand {
  enum class Mode { kNone, kDemo, kReport };
  Mode mode = Mode::kNone;
  QString out;      // output folder
  QString results;  // --report: the results folder
  QString earlier;  // --compare-with: an earlier survey's results folder ("" : none)
  bool help = false;
  QString error;  // non-empty: the command line is wrong (exit code 2)
};

// True when the arguments ask for the headless job whatever the display:
// --report, or --demo with --out (a batch run). `hullinspect --demo` alone
// opens the GUI when there is a display.
bool IsBatchCommand(const QStringList& arguments);

// Parses --demo, --report RESULTS, --out DIR, --help (without argv[0]).
HeadlessCommand ParseHeadlessCommand(const QStringList& arguments);
QString HeadlessUsage();

// Sets QT_QPA_PLATFORM=offscreen for the QGuiApplication about to be made.
void PrepareHeadless();

// Runs the command; returns the process exit code (0 done, 1 failed, 2 usage,
// 3 bad input, 4 insufficient data: as hullinspect-cli).
int RunHeadlessJob(const HeadlessCommand& command);

}  // namespace hull::report
