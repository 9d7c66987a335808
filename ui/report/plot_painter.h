// Small drawing helpers the report's figures share: colour maps, fonts,
// "nice" axis ticks, plot axes with labels, legends and a colour bar. All in
// figure units (a figure is kFigureWidth units wide; see figures.h), so the
// same code paints a PNG and a PDF page.
#pragma once

#include <QColor>
#include <QFont>
#include <QPainter>
#include <QPointF>
#include <QRectF>
#include <QString>
#include <vector>

#include "adjust/adjust_options.h"
#include "base/axis_ticks.h"

namespace hull::report {

// Diverging blue - near-white - red for t in [-1, 1] (ColorBrewer RdBu).
QColor DivergingColour(double t);
// Sequential viridis for t in [0, 1] (clamped).
QColor SequentialColour(double t);
// The colour each surface model has in every figure.
QColor ModelColour(SurfaceModel m);
QString ModelLabel(SurfaceModel m);  // "naive", "all-on-surface", "max-mixture"

// A sans-serif font of `size` figure units.
QFont FigureFont(double size, bool bold = false);

// NiceTicks and LogTicks: base/axis_ticks.h, shared with the screen's plots.
// A tick label with the precision of the step; step <= 0: a logarithmic
// axis ("10⁵", "2×10⁵", "500").
QString TickLabel(double v, double step);

// A data rectangle mapped onto a rectangle of the figure.
struct PlotFrame {
  QRectF rect;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool log_y = false;
  QPointF Map(double x, double y) const;
};

struct AxisLabels {
  QString x, y;
  std::vector<double> x_ticks, y_ticks;
  double x_step = 0, y_step = 0;  // for the tick labels' precision
  bool y_tick_labels = true;      // false: ticks only (a panel beside another)
};

// Frame, grid lines, ticks and labels around frame.rect.
void DrawAxes(QPainter& p, const PlotFrame& frame, const AxisLabels& labels);
// A panel title above a rectangle.
void DrawTitle(QPainter& p, const QRectF& rect, const QString& title);

struct LegendEntry {
  QColor colour;
  QString label;
  enum class Mark { kLine, kBox, kDot, kDash } mark = Mark::kLine;
};
// A legend box anchored at the top-right corner `corner` of a plot (or its
// top-left when left is true).
void DrawLegend(QPainter& p, const QPointF& corner, const std::vector<LegendEntry>& entries, bool left = false);
// A horizontal legend in one row centred in `rect`.
void DrawLegendRow(QPainter& p, const QRectF& rect, const std::vector<LegendEntry>& entries);

// A horizontal colour bar of DivergingColour over [-range, range] with ticks
// and a label below.
void DrawColourBar(QPainter& p, const QRectF& rect, double range, const QString& label);
// The same for SequentialColour over [0, max].
void DrawSequentialColourBar(QPainter& p, const QRectF& rect, double max, const QString& label);

}  // namespace hull::report
