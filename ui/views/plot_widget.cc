#include "ui/views/plot_widget.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

#include "base/axis_ticks.h"

namespace hull::ui {

namespace {

struct Range {
  double lo = 0, hi = 1;
  bool valid = false;
  void Add(double v) {
    if (!std::isfinite(v)) return;
    if (!valid) {
      lo = hi = v;
      valid = true;
    } else {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
};

// Compact scientific text: 2e5, 2.5e-3.
QString Scientific(double v) {
  if (v == 0) return QStringLiteral("0");
  const int e = static_cast<int>(std::floor(std::log10(std::abs(v)) + 1e-9));
  const double m = v / std::pow(10.0, e);
  return QString::number(m, 'g', 2) + QStringLiteral("e") + QString::number(e);
}

QString TickText(double v, double step) {
  if (std::abs(v) < 1e-12 * std::max(1.0, step)) return QStringLiteral("0");
  const double a = std::abs(v);
  if (a >= 1e5 || a < 1e-3) return Scientific(v);
  // As exact as the step, as on paper (0.25 apart: 0.25, 0.50, not 0.3, 0.5).
  return QString::number(v, 'f', std::min(TickDecimals(step), 4));
}

// The plot's data rectangle and its axes' ranges (y transformed: log10 on a
// logarithmic axis), mapping data to widget coordinates.
struct PlotFrame {
  QRectF area;
  Range x, y;
  bool log_y = false;
  double Ty(double v) const { return log_y ? (v > 0 ? std::log10(v) : NAN) : v; }
  double X(double v) const { return area.left() + (v - x.lo) / (x.hi - x.lo) * area.width(); }
  double Y(double v) const { return area.bottom() - (v - y.lo) / (y.hi - y.lo) * area.height(); }
};

// The ranges over the data, markers and fixed ranges, widened when empty and
// padded for bars' labels; false when there is nothing to plot.
bool FitRanges(const PlotData& data, PlotFrame* f) {
  Range& xr = f->x;
  Range& yr = f->y;
  for (const PlotSeries& s : data.series) {
    for (const QPointF& q : s.points) {
      const double y = f->Ty(q.y());
      if (!std::isfinite(y)) continue;
      if (s.style == PlotSeries::Style::kHistogram) {
        xr.Add(q.x());
        xr.Add(q.x() + s.bin_width);
        yr.Add(0);
      } else if (s.style == PlotSeries::Style::kBars) {
        xr.Add(q.x() - 0.5 * s.bin_width);
        xr.Add(q.x() + 0.5 * s.bin_width);
        if (!data.log_y) yr.Add(0);
      } else {
        xr.Add(q.x());
      }
      yr.Add(y);
    }
  }
  for (const PlotMarker& m : data.markers) xr.Add(m.x);
  if (data.x_range) {
    xr = {data.x_range->first, data.x_range->second, true};
  }
  if (data.y_range) yr = {f->Ty(data.y_range->first), f->Ty(data.y_range->second), true};
  if (!xr.valid || !yr.valid) return false;
  if (xr.hi - xr.lo < 1e-12) {
    xr.lo -= 0.5;
    xr.hi += 0.5;
  }
  if (yr.hi - yr.lo < 1e-12) {
    yr.lo -= data.log_y ? 0.5 : std::max(0.5, std::abs(yr.lo) * 0.1);
    yr.hi += data.log_y ? 0.5 : std::max(0.5, std::abs(yr.hi) * 0.1);
  }
  if (!data.y_range) {
    bool bars = false;
    for (const PlotSeries& s : data.series) bars = bars || s.style == PlotSeries::Style::kBars;
    const double pad = (bars ? 0.22 : 0.06) * (yr.hi - yr.lo);
    if (!(yr.lo == 0 && !data.log_y)) yr.lo -= pad;
    yr.hi += pad;
  }
  return true;
}

// The y ticks (transformed): decades on a logarithmic axis, and 2 and 5 times
// them when the axis spans few decades; nice ticks on a linear one.
std::vector<double> YTicks(const PlotFrame& f) {
  if (!f.log_y) return NiceTicks(f.y.lo, f.y.hi, std::max(3, static_cast<int>(f.area.height() / 40)));
  std::vector<double> ticks;
  const double subs2[] = {1.0, 2.0, 5.0};
  const bool fine = f.y.hi - f.y.lo < 2.5;
  for (double e = std::floor(f.y.lo); e <= f.y.hi + 1e-9; e += 1.0) {
    for (double m : subs2) {
      if (!fine && m != 1.0) continue;
      const double t = e + std::log10(m);
      if (t >= f.y.lo - 1e-9 && t <= f.y.hi + 1e-9) ticks.push_back(t);
    }
  }
  return ticks;
}

// What every part of the plot draws with.
struct PlotStyle {
  QColor text, grid;
  QFontMetrics fm;
  int left;  // the margin for the y tick labels
};

// Grid lines with their tick labels, category labels, and the axis titles.
void DrawAxes(QPainter& p, const PlotData& data, const PlotFrame& f, const PlotStyle& st) {
  const QFontMetrics& fm = st.fm;
  const std::vector<double> yticks = YTicks(f);
  const double ystep = yticks.size() > 1 ? yticks[1] - yticks[0] : 1.0;
  for (double t : yticks) {
    const double y = f.Y(t);
    p.setPen(QPen(st.grid, 1));
    p.drawLine(QPointF(f.area.left(), y), QPointF(f.area.right(), y));
    p.setPen(st.text);
    const double value = std::pow(10.0, t);
    const QString label = data.log_y
                              ? (value >= 1e4 || value < 1e-2 ? Scientific(value) : QString::number(value, 'g', 3))
                              : TickText(t, ystep);
    p.drawText(QRectF(0, y - fm.height() / 2.0, st.left - 6, fm.height()), Qt::AlignRight | Qt::AlignVCenter, label);
  }
  if (!data.x_categories.isEmpty()) {
    p.setPen(st.text);
    const double spacing = f.X(1) - f.X(0) - 4;
    for (int i = 0; i < data.x_categories.size(); ++i) {
      if (i < f.x.lo || i > f.x.hi) continue;
      p.drawText(QRectF(f.X(i) - spacing / 2, f.area.bottom() + 3, spacing, 3 * fm.height()),
                 Qt::AlignHCenter | Qt::AlignTop | Qt::TextWordWrap, data.x_categories[i]);
    }
  } else {
    const std::vector<double> xticks = NiceTicks(f.x.lo, f.x.hi, std::max(2, static_cast<int>(f.area.width() / 70)));
    const double xstep = xticks.size() > 1 ? xticks[1] - xticks[0] : 1.0;
    for (double t : xticks) {
      const double x = f.X(t);
      p.setPen(QPen(st.grid, 1));
      p.drawLine(QPointF(x, f.area.top()), QPointF(x, f.area.bottom()));
      p.setPen(st.text);
      p.drawText(QRectF(x - 40, f.area.bottom() + 3, 80, fm.height()), Qt::AlignHCenter | Qt::AlignTop,
                 TickText(t, xstep));
    }
  }
  p.setPen(st.text);
  p.drawText(QRectF(f.area.left(), f.area.bottom() + fm.height() + 6, f.area.width(), fm.height() + 2),
             Qt::AlignHCenter | Qt::AlignTop, data.x_label);
  p.save();
  p.translate(10, f.area.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-f.area.height() / 2, -fm.height() / 2.0 - 2, f.area.height(), fm.height() + 4), Qt::AlignCenter,
             data.y_label);
  p.restore();
}

void DrawLine(QPainter& p, const PlotSeries& s, const PlotFrame& f) {
  QPainterPath path;
  bool started = false;
  for (const QPointF& q : s.points) {
    const double y = f.Ty(q.y());
    if (!std::isfinite(y)) {
      started = false;
      continue;
    }
    const QPointF at(f.X(q.x()), f.Y(y));
    if (started) {
      path.lineTo(at);
    } else {
      path.moveTo(at);
      started = true;
    }
  }
  p.drawPath(path);
}

void DrawHistogram(QPainter& p, const PlotSeries& s, const PlotFrame& f) {
  QColor fill = s.colour;
  fill.setAlpha(70);
  for (const QPointF& q : s.points) {
    if (q.y() <= 0) continue;
    const QRectF bar(QPointF(f.X(q.x()), f.Y(f.Ty(q.y()))),
                     QPointF(f.X(q.x() + s.bin_width), f.Y(std::max(f.y.lo, 0.0))));
    p.fillRect(bar, fill);
    p.drawLine(bar.topLeft(), bar.topRight());
    p.drawLine(bar.topLeft(), bar.bottomLeft());
    p.drawLine(bar.topRight(), bar.bottomRight());
  }
}

// Bars with their value above each (pen: the series' pen, restored after each label).
void DrawBars(QPainter& p, const PlotSeries& s, const PlotFrame& f, const PlotStyle& st, const QPen& pen) {
  for (const QPointF& q : s.points) {
    const double y = f.Ty(q.y());
    if (!std::isfinite(y)) continue;
    const QRectF bar(QPointF(f.X(q.x() - 0.4 * s.bin_width), f.Y(y)),
                     QPointF(f.X(q.x() + 0.4 * s.bin_width), f.Y(f.log_y ? f.y.lo : 0.0)));
    p.fillRect(bar, s.colour);
    p.setPen(st.text);
    p.drawText(QRectF(bar.left() - 30, bar.top() - st.fm.height() - 2, bar.width() + 60, st.fm.height()),
               Qt::AlignHCenter | Qt::AlignBottom, QString::number(q.y(), 'g', 3));
    p.setPen(pen);
  }
}

// Every series and the vertical markers, clipped to the area.
void DrawData(QPainter& p, const PlotData& data, const PlotFrame& f, const PlotStyle& st) {
  p.save();
  p.setClipRect(f.area.adjusted(-1, -1, 1, 1));
  for (const PlotSeries& s : data.series) {
    QPen pen(s.colour, s.width);
    if (s.dashed) pen.setStyle(Qt::DashLine);
    p.setPen(pen);
    switch (s.style) {
      case PlotSeries::Style::kLine:
        DrawLine(p, s, f);
        break;
      case PlotSeries::Style::kPoints:
        p.setBrush(s.colour);
        for (const QPointF& q : s.points) {
          const double y = f.Ty(q.y());
          if (std::isfinite(y)) p.drawEllipse(QPointF(f.X(q.x()), f.Y(y)), 2.6, 2.6);
        }
        p.setBrush(Qt::NoBrush);
        break;
      case PlotSeries::Style::kHistogram:
        DrawHistogram(p, s, f);
        break;
      case PlotSeries::Style::kBars:
        DrawBars(p, s, f, st, pen);
        break;
    }
  }
  for (const PlotMarker& m : data.markers) {
    QPen pen(m.colour, 1.4, Qt::DashLine);
    p.setPen(pen);
    const double x = f.X(m.x);
    p.drawLine(QPointF(x, f.area.top()), QPointF(x, f.area.bottom()));
    if (!m.label.isEmpty()) {
      p.drawText(QRectF(x + 3, f.area.top() + 2, 120, st.fm.height()), Qt::AlignLeft | Qt::AlignTop, m.label);
    }
  }
  p.restore();
}

// Of the area's four corners, the one where a box of `size` hides the fewest
// data points.
QRectF LegendBox(const PlotData& data, const PlotFrame& f, const QSizeF& size) {
  const QRectF& area = f.area;
  const double y0 = area.top() + 4;
  const QRectF corners[4] = {QRectF(QPointF(area.right() - size.width() - 4, y0), size),
                             QRectF(QPointF(area.left() + 4, y0), size),
                             QRectF(QPointF(area.right() - size.width() - 4, area.bottom() - size.height() - 4), size),
                             QRectF(QPointF(area.left() + 4, area.bottom() - size.height() - 4), size)};
  int best = 0, fewest = -1;
  for (int c = 0; c < 4; ++c) {
    int hidden = 0;
    for (const PlotSeries& s : data.series) {
      for (const QPointF& q : s.points) {
        const double y = f.Ty(q.y());
        if (std::isfinite(y) && corners[c].contains(QPointF(f.X(q.x()), f.Y(y)))) ++hidden;
      }
    }
    if (fewest < 0 || hidden < fewest) {
      fewest = hidden;
      best = c;
    }
  }
  return corners[best];
}

// The legend of the named series: in the corner of the area that hides the
// fewest data points.
void DrawLegend(QPainter& p, const PlotData& data, const PlotFrame& f, const PlotStyle& st, const QPalette& pal) {
  const QFontMetrics& fm = st.fm;
  int rows = 0, legend_width = 0;
  const int max_text = static_cast<int>(0.62 * f.area.width()) - 34;
  for (const PlotSeries& s : data.series) {
    if (s.name.isEmpty()) continue;
    ++rows;
    legend_width = std::max(legend_width, std::min(max_text, fm.horizontalAdvance(s.name)));
  }
  if (rows == 0) return;
  const QRectF box = LegendBox(data, f, QSizeF(legend_width + 34, rows * (fm.height() + 2) + 6));
  QColor bg = pal.color(QPalette::Base);
  bg.setAlpha(225);
  p.fillRect(box, bg);
  p.setPen(pal.color(QPalette::Mid));
  p.drawRect(box);
  double y = box.top() + 3;
  for (const PlotSeries& s : data.series) {
    if (s.name.isEmpty()) continue;
    QPen pen(s.colour, std::max(2.0, s.width));
    if (s.dashed) pen.setStyle(Qt::DashLine);
    p.setPen(pen);
    const double cy = y + fm.height() / 2.0;
    if (s.style == PlotSeries::Style::kPoints) {
      p.setBrush(s.colour);
      p.drawEllipse(QPointF(box.left() + 14, cy), 3, 3);
      p.setBrush(Qt::NoBrush);
    } else {
      p.drawLine(QPointF(box.left() + 5, cy), QPointF(box.left() + 23, cy));
    }
    p.setPen(st.text);
    p.drawText(QRectF(box.left() + 28, y, legend_width + 4, fm.height()), Qt::AlignLeft | Qt::AlignVCenter,
               fm.elidedText(s.name, Qt::ElideRight, legend_width + 2));
    y += fm.height() + 2;
  }
}

}  // namespace

PlotWidget::PlotWidget(QWidget* parent) : QWidget(parent) {
  setAttribute(Qt::WA_OpaquePaintEvent);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void PlotWidget::SetData(PlotData data) {
  data_ = std::move(data);
  update();
}

bool PlotWidget::HasPoints() const {
  for (const PlotSeries& s : data_.series) {
    if (!s.points.empty()) return true;
  }
  return false;
}

void PlotWidget::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QPalette& pal = palette();
  p.fillRect(rect(), pal.base());
  const PlotStyle st{pal.color(QPalette::Text), pal.color(QPalette::Mid).lighter(150), QFontMetrics(font()), 70};
  const QFontMetrics& fm = st.fm;

  const int top = (data_.title.isEmpty() ? 10 : fm.height() + 12) + (data_.note.isEmpty() ? 0 : fm.height() + 2);
  const int right = 14;
  const int bottom = fm.height() * (data_.x_categories.isEmpty() ? 2 : 3) + 14;
  PlotFrame f;
  f.area = QRectF(st.left, top, std::max(10, width() - st.left - right), std::max(10, height() - top - bottom));
  f.log_y = data_.log_y;

  if (!data_.title.isEmpty()) {
    QFont bold = font();
    bold.setBold(true);
    p.setFont(bold);
    p.setPen(st.text);
    p.drawText(QRectF(0, 4, width(), fm.height() + 4), Qt::AlignHCenter | Qt::AlignTop, data_.title);
    p.setFont(font());
  }
  if (!data_.note.isEmpty()) {
    p.setPen(pal.color(QPalette::PlaceholderText));
    p.drawText(QRectF(4, fm.height() + 8, width() - 8, fm.height() + 2), Qt::AlignHCenter | Qt::AlignTop,
               fm.elidedText(data_.note, Qt::ElideRight, width() - 8));
  }
  if (!FitRanges(data_, &f)) {
    p.setPen(pal.color(QPalette::PlaceholderText));
    p.drawRect(f.area);
    p.drawText(f.area, Qt::AlignCenter | Qt::TextWordWrap,
               data_.empty_text.isEmpty() ? QStringLiteral("No data") : data_.empty_text);
    return;
  }
  p.setPen(QPen(st.grid, 1));
  DrawAxes(p, data_, f, st);
  DrawData(p, data_, f, st);
  p.setPen(pal.color(QPalette::Mid));
  p.drawRect(f.area);
  DrawLegend(p, data_, f, st, pal);
}

}  // namespace hull::ui
