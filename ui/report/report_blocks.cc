// The report's text helpers: number formats, block builders, table columns.
#include "ui/report/report_blocks.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace hull::report {

std::string Format(const char* fmt, ...) {
  char buffer[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

std::string Num(double v, int digits) { return std::isfinite(v) ? Format("%.*f", digits, v) : "–"; }
std::string Metres(double v, int digits) { return std::isfinite(v) ? Num(v, digits) + " m" : "–"; }
std::string Percent(double fraction, int digits) { return Num(100 * fraction, digits) + " %"; }
std::string Count(long long n) {
  std::string s = std::to_string(n);
  const int first = n < 0 ? 1 : 0;
  for (int i = static_cast<int>(s.size()) - 3; i > first; i -= 3) s.insert(static_cast<std::size_t>(i), "\u2009");
  return s;
}
std::string Rounded(double v) { return std::isfinite(v) && std::abs(v) < 1e15 ? Count(std::llround(v)) : "–"; }

std::string Duration(double s) {
  if (!(s >= 0)) return "–";
  if (s < 60) return Format("%.1f s", s);
  const long total = std::lround(s);
  if (total < 3600) return Format("%ld min %02ld s", total / 60, total % 60);
  return Format("%ld h %02ld min", total / 3600, (total % 3600) / 60);
}

std::string Quantile(std::vector<double> v, double q, int digits) {
  if (v.empty()) return "–";
  std::sort(v.begin(), v.end());
  return Num(v[static_cast<std::size_t>(q * (v.size() - 1))], digits);
}

// "0–7, 11, 13–19"
std::string Ranges(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  std::string s;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i;
    while (j + 1 < v.size() && v[j + 1] == v[j] + 1) ++j;
    if (!s.empty()) s += ", ";
    s += std::to_string(v[i]);
    if (j > i) s += "–" + std::to_string(v[j]);
    i = j + 1;
  }
  return s;
}

Block Paragraph(std::string text) {
  Block b;
  b.text = std::move(text);
  return b;
}
Block Note(std::string text) {
  Block b;
  b.kind = Block::Kind::kNote;
  b.text = std::move(text);
  return b;
}
Block Subheading(std::string text) {
  Block b;
  b.kind = Block::Kind::kSubheading;
  b.text = std::move(text);
  return b;
}
Block Facts(std::vector<std::pair<std::string, std::string>> facts) {
  Block b;
  b.kind = Block::Kind::kFacts;
  b.facts = std::move(facts);
  return b;
}
Block TableBlock(Table t) {
  Block b;
  b.kind = Block::Kind::kTable;
  b.table = std::move(t);
  return b;
}
Block List(std::vector<std::string> items) {
  Block b;
  b.kind = Block::Kind::kList;
  b.items = std::move(items);
  return b;
}
Block FigureBlock(const FigureRef& f) {
  Block b;
  b.kind = Block::Kind::kFigure;
  b.figure = f;
  return b;
}

std::string ModelTitle(SurfaceModel m) { return SurfaceModelName(m); }

const char* YesNo(bool b) { return b ? "yes" : "no"; }

const AdjustmentEvaluation* EvaluationOf(const PipelineResult& r, const AdjustmentResult* a) {
  if (a == &r.adjustment) return r.evaluation ? &*r.evaluation : nullptr;
  for (std::size_t i = 0; i < r.baselines.size(); ++i) {
    if (&r.baselines[i] == a) return i < r.baseline_evaluations.size() ? &r.baseline_evaluations[i] : nullptr;
  }
  return nullptr;
}

const FigureRef* FindFigure(const std::vector<FigureRef>& figures, FigureKind kind) {
  for (const FigureRef& f : figures) {
    if (f.kind == kind) return &f;
  }
  return nullptr;
}

Table MakeTable(const std::vector<Column>& columns) {
  Table t;
  for (const Column& c : columns) AddColumn(t, c);
  return t;
}

void AddColumn(Table& t, const Column& column) {
  t.header.push_back(column.name);
  t.numeric.push_back(column.numeric);
}

void ToneByRating(Table& t, int column) {
  t.tone.clear();
  for (const std::vector<std::string>& row : t.rows) t.tone.push_back(RatingTone(row[column]));
  t.tone_column = column;
}

std::string ViewWords(HullView v, bool with_orientation) {
  switch (v) {
    case HullView::kBottom:
      return with_orientation ? "from below (bow to the right, starboard up)" : "from below";
    case HullView::kPort:
      return with_orientation ? "from the port side (bow to the left)" : "from the port side";
    case HullView::kStarboard:
      return with_orientation ? "from the starboard side (bow to the right)" : "from the starboard side";
  }
  return "";
}

std::vector<HullView> HeatmapViews(const std::vector<FigureRef>& figures) {
  std::vector<HullView> views;
  for (const FigureRef& f : figures) {
    if (f.kind == FigureKind::kHeatmap) views.push_back(f.view);
  }
  return views;
}

FigureRef ViewFigure(FigureKind kind, const std::string& id_prefix, HullView v, std::string title,
                     std::string caption) {
  FigureRef f;
  f.id = id_prefix + "-" + HullViewName(v);
  f.kind = kind;
  f.view = v;
  f.title = std::move(title);
  f.caption = std::move(caption);
  return f;
}

}  // namespace hull::report
