// What the report's sections are written with (internal to ui/report):
// number formats that print "–" for a missing value, the document's block
// builders, table columns, and look-ups into the pipeline's results.
#pragma once

#include <string>
#include <vector>

#include "ui/report/report_document.h"

namespace hull::report {

__attribute__((format(printf, 1, 2))) std::string Format(const char* fmt, ...);
std::string Num(double v, int digits);                 // "–" when not finite
std::string Metres(double v, int digits = 3);          // "1.234 m"
std::string Percent(double fraction, int digits = 1);  // 0.5 -> "50.0 %"
std::string Count(long long n);                        // thin-space thousands
std::string Rounded(double v);                         // Count of the nearest integer
std::string Duration(double seconds);                  // "12.3 s", "4 min 05 s", "2 h 10 min"
std::string Quantile(std::vector<double> v, double q, int digits);
std::string Ranges(std::vector<int> v);  // "0–7, 11, 13–19"
// Where a hull figure is seen from: "from below", "from the port side", ...;
// with_orientation adds which way the bow points ("... (bow to the right)").
std::string ViewWords(HullView v, bool with_orientation = false);
// The views the deviation heatmaps were planned for (the figures that follow
// them are drawn from the same sides).
std::vector<HullView> HeatmapViews(const std::vector<FigureRef>& figures);
// A figure of `kind` seen from v, its id "<id_prefix>-<view name>".
FigureRef ViewFigure(FigureKind kind, const std::string& id_prefix, HullView v, std::string title, std::string caption);

Block Paragraph(std::string text);
Block Note(std::string text);
Block Subheading(std::string text);
Block Facts(std::vector<std::pair<std::string, std::string>> facts);
Block TableBlock(Table t);
Block List(std::vector<std::string> items);
Block FigureBlock(const FigureRef& f);

// A table column: its heading and whether its cells are numbers (right-aligned).
struct Column {
  std::string name;
  bool numeric = false;
};
// A table with these columns and no rows.
Table MakeTable(const std::vector<Column>& columns);
void AddColumn(Table& t, const Column& column);
// Colours every row's cell in `column` by the IMO rating it holds (RatingTone).
void ToneByRating(Table& t, int column);

std::string ModelTitle(SurfaceModel m);  // "naive", "all-on-surface", "max-mixture"
const char* YesNo(bool b);
// The evaluation of one of the pipeline's adjustments (null: none).
const AdjustmentEvaluation* EvaluationOf(const PipelineResult& r, const AdjustmentResult* a);
// The planned figure of this kind (null: not planned).
const FigureRef* FindFigure(const std::vector<FigureRef>& figures, FigureKind kind);

}  // namespace hull::report
