#include "ui/views/plot_widget.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

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
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  return QString::number(v, 'f', std::min(decimals, 4));
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

std::vector<double> PlotWidget::NiceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || target < 1) return ticks;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

void PlotWidget::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QPalette& pal = palette();
  p.fillRect(rect(), pal.base());
  const QColor text = pal.color(QPalette::Text);
  const QColor grid = pal.color(QPalette::Mid).lighter(150);
  const QFontMetrics fm(font());

  const int top = (data_.title.isEmpty() ? 10 : fm.height() + 12) + (data_.note.isEmpty() ? 0 : fm.height() + 2);
  const int left = 70, right = 14;
  const int bottom = fm.height() * (data_.x_categories.isEmpty() ? 2 : 3) + 14;
  const QRectF area(left, top, std::max(10, width() - left - right), std::max(10, height() - top - bottom));

  if (!data_.title.isEmpty()) {
    QFont bold = font();
    bold.setBold(true);
    p.setFont(bold);
    p.setPen(text);
    p.drawText(QRectF(0, 4, width(), fm.height() + 4), Qt::AlignHCenter | Qt::AlignTop, data_.title);
    p.setFont(font());
  }
  if (!data_.note.isEmpty()) {
    p.setPen(pal.color(QPalette::PlaceholderText));
    p.drawText(QRectF(4, fm.height() + 8, width() - 8, fm.height() + 2), Qt::AlignHCenter | Qt::AlignTop,
               fm.elidedText(data_.note, Qt::ElideRight, width() - 8));
  }
  auto ty = [this](double y) { return data_.log_y ? (y > 0 ? std::log10(y) : NAN) : y; };

  // Ranges over the data (transformed y).
  Range xr, yr;
  for (const PlotSeries& s : data_.series) {
    for (const QPointF& q : s.points) {
      const double y = ty(q.y());
      if (!std::isfinite(y)) continue;
      if (s.style == PlotSeries::Style::kHistogram) {
        xr.Add(q.x());
        xr.Add(q.x() + s.bin_width);
        yr.Add(0);
      } else if (s.style == PlotSeries::Style::kBars) {
        xr.Add(q.x() - 0.5 * s.bin_width);
        xr.Add(q.x() + 0.5 * s.bin_width);
        if (!data_.log_y) yr.Add(0);
      } else {
        xr.Add(q.x());
      }
      yr.Add(y);
    }
  }
  for (const PlotMarker& m : data_.markers) xr.Add(m.x);
  if (data_.x_range) {
    xr = {data_.x_range->first, data_.x_range->second, true};
  }
  if (data_.y_range) yr = {ty(data_.y_range->first), ty(data_.y_range->second), true};
  if (!xr.valid || !yr.valid) {
    p.setPen(pal.color(QPalette::PlaceholderText));
    p.drawRect(area);
    p.drawText(area, Qt::AlignCenter | Qt::TextWordWrap,
               data_.empty_text.isEmpty() ? QStringLiteral("No data") : data_.empty_text);
    return;
  }
  if (xr.hi - xr.lo < 1e-12) {
    xr.lo -= 0.5;
    xr.hi += 0.5;
  }
  if (yr.hi - yr.lo < 1e-12) {
    yr.lo -= data_.log_y ? 0.5 : std::max(0.5, std::abs(yr.lo) * 0.1);
    yr.hi += data_.log_y ? 0.5 : std::max(0.5, std::abs(yr.hi) * 0.1);
  }
  if (!data_.y_range) {
    bool bars = false;
    for (const PlotSeries& s : data_.series) bars = bars || s.style == PlotSeries::Style::kBars;
    const double pad = (bars ? 0.22 : 0.06) * (yr.hi - yr.lo);
    if (!(yr.lo == 0 && !data_.log_y)) yr.lo -= pad;
    yr.hi += pad;
  }
  auto X = [&](double x) { return area.left() + (x - xr.lo) / (xr.hi - xr.lo) * area.width(); };
  auto Y = [&](double y) { return area.bottom() - (y - yr.lo) / (yr.hi - yr.lo) * area.height(); };

  // Grid and ticks.
  p.setPen(QPen(grid, 1));
  std::vector<double> yticks;
  if (data_.log_y) {
    // Decades, and 2 and 5 times them when the axis spans few decades.
    const double subs2[] = {1.0, 2.0, 5.0};
    const bool fine = yr.hi - yr.lo < 2.5;
    for (double e = std::floor(yr.lo); e <= yr.hi + 1e-9; e += 1.0) {
      for (double m : subs2) {
        if (!fine && m != 1.0) continue;
        const double t = e + std::log10(m);
        if (t >= yr.lo - 1e-9 && t <= yr.hi + 1e-9) yticks.push_back(t);
      }
    }
  } else {
    yticks = NiceTicks(yr.lo, yr.hi, std::max(3, static_cast<int>(area.height() / 40)));
  }
  const double ystep = yticks.size() > 1 ? yticks[1] - yticks[0] : 1.0;
  for (double t : yticks) {
    const double y = Y(t);
    p.setPen(QPen(grid, 1));
    p.drawLine(QPointF(area.left(), y), QPointF(area.right(), y));
    p.setPen(text);
    const double value = std::pow(10.0, t);
    const QString label = data_.log_y
                              ? (value >= 1e4 || value < 1e-2 ? Scientific(value) : QString::number(value, 'g', 3))
                              : TickText(t, ystep);
    p.drawText(QRectF(0, y - fm.height() / 2.0, left - 6, fm.height()), Qt::AlignRight | Qt::AlignVCenter, label);
  }
  if (!data_.x_categories.isEmpty()) {
    p.setPen(text);
    const double spacing = X(1) - X(0) - 4;
    for (int i = 0; i < data_.x_categories.size(); ++i) {
      if (i < xr.lo || i > xr.hi) continue;
      p.drawText(QRectF(X(i) - spacing / 2, area.bottom() + 3, spacing, 3 * fm.height()),
                 Qt::AlignHCenter | Qt::AlignTop | Qt::TextWordWrap, data_.x_categories[i]);
    }
  } else {
    const std::vector<double> xticks = NiceTicks(xr.lo, xr.hi, std::max(2, static_cast<int>(area.width() / 70)));
    const double xstep = xticks.size() > 1 ? xticks[1] - xticks[0] : 1.0;
    for (double t : xticks) {
      const double x = X(t);
      p.setPen(QPen(grid, 1));
      p.drawLine(QPointF(x, area.top()), QPointF(x, area.bottom()));
      p.setPen(text);
      p.drawText(QRectF(x - 40, area.bottom() + 3, 80, fm.height()), Qt::AlignHCenter | Qt::AlignTop,
                 TickText(t, xstep));
    }
  }
  p.setPen(text);
  p.drawText(QRectF(area.left(), area.bottom() + fm.height() + 6, area.width(), fm.height() + 2),
             Qt::AlignHCenter | Qt::AlignTop, data_.x_label);
  p.save();
  p.translate(10, area.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-area.height() / 2, -fm.height() / 2.0 - 2, area.height(), fm.height() + 4), Qt::AlignCenter,
             data_.y_label);
  p.restore();

  // Data, clipped to the area.
  p.save();
  p.setClipRect(area.adjusted(-1, -1, 1, 1));
  for (const PlotSeries& s : data_.series) {
    QPen pen(s.colour, s.width);
    if (s.dashed) pen.setStyle(Qt::DashLine);
    p.setPen(pen);
    switch (s.style) {
      case PlotSeries::Style::kLine: {
        QPainterPath path;
        bool started = false;
        for (const QPointF& q : s.points) {
          const double y = ty(q.y());
          if (!std::isfinite(y)) {
            started = false;
            continue;
          }
          const QPointF at(X(q.x()), Y(y));
          if (started) {
            path.lineTo(at);
          } else {
            path.moveTo(at);
            started = true;
          }
        }
        p.drawPath(path);
        break;
      }
      case PlotSeries::Style::kPoints:
        p.setBrush(s.colour);
        for (const QPointF& q : s.points) {
          const double y = ty(q.y());
          if (std::isfinite(y)) p.drawEllipse(QPointF(X(q.x()), Y(y)), 2.6, 2.6);
        }
        p.setBrush(Qt::NoBrush);
        break;
      case PlotSeries::Style::kHistogram: {
        QColor fill = s.colour;
        fill.setAlpha(70);
        for (const QPointF& q : s.points) {
          if (q.y() <= 0) continue;
          const QRectF bar(QPointF(X(q.x()), Y(ty(q.y()))), QPointF(X(q.x() + s.bin_width), Y(std::max(yr.lo, 0.0))));
          p.fillRect(bar, fill);
          p.drawLine(bar.topLeft(), bar.topRight());
          p.drawLine(bar.topLeft(), bar.bottomLeft());
          p.drawLine(bar.topRight(), bar.bottomRight());
        }
        break;
      }
      case PlotSeries::Style::kBars:
        for (const QPointF& q : s.points) {
          const double y = ty(q.y());
          if (!std::isfinite(y)) continue;
          const QRectF bar(QPointF(X(q.x() - 0.4 * s.bin_width), Y(y)),
                           QPointF(X(q.x() + 0.4 * s.bin_width), Y(data_.log_y ? yr.lo : 0.0)));
          p.fillRect(bar, s.colour);
          p.setPen(text);
          p.drawText(QRectF(bar.left() - 30, bar.top() - fm.height() - 2, bar.width() + 60, fm.height()),
                     Qt::AlignHCenter | Qt::AlignBottom, QString::number(q.y(), 'g', 3));
          p.setPen(pen);
        }
        break;
    }
  }
  for (const PlotMarker& m : data_.markers) {
    QPen pen(m.colour, 1.4, Qt::DashLine);
    p.setPen(pen);
    const double x = X(m.x);
    p.drawLine(QPointF(x, area.top()), QPointF(x, area.bottom()));
    if (!m.label.isEmpty()) {
      p.drawText(QRectF(x + 3, area.top() + 2, 120, fm.height()), Qt::AlignLeft | Qt::AlignTop, m.label);
    }
  }
  p.restore();
  p.setPen(pal.color(QPalette::Mid));
  p.drawRect(area);

  // The legend: in the corner of the area that hides the fewest data points.
  const double y0 = area.top() + 4;
  int rows = 0, legend_width = 0;
  const int max_text = static_cast<int>(0.62 * area.width()) - 34;
  for (const PlotSeries& s : data_.series) {
    if (s.name.isEmpty()) continue;
    ++rows;
    legend_width = std::max(legend_width, std::min(max_text, fm.horizontalAdvance(s.name)));
  }
  if (rows == 0) return;
  const QSizeF size(legend_width + 34, rows * (fm.height() + 2) + 6);
  const QRectF corners[4] = {QRectF(QPointF(area.right() - size.width() - 4, y0), size),
                             QRectF(QPointF(area.left() + 4, y0), size),
                             QRectF(QPointF(area.right() - size.width() - 4, area.bottom() - size.height() - 4), size),
                             QRectF(QPointF(area.left() + 4, area.bottom() - size.height() - 4), size)};
  int best = 0, fewest = -1;
  for (int c = 0; c < 4; ++c) {
    int hidden = 0;
    for (const PlotSeries& s : data_.series) {
      for (const QPointF& q : s.points) {
        const double y = ty(q.y());
        if (std::isfinite(y) && corners[c].contains(QPointF(X(q.x()), Y(y)))) ++hidden;
      }
    }
    if (fewest < 0 || hidden < fewest) {
      fewest = hidden;
      best = c;
    }
  }
  const QRectF box = corners[best];
  QColor bg = pal.color(QPalette::Base);
  bg.setAlpha(225);
  p.fillRect(box, bg);
  p.setPen(pal.color(QPalette::Mid));
  p.drawRect(box);
  double y = box.top() + 3;
  for (const PlotSeries& s : data_.series) {
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
    p.setPen(text);
    p.drawText(QRectF(box.left() + 28, y, legend_width + 4, fm.height()), Qt::AlignLeft | Qt::AlignVCenter,
               fm.elidedText(s.name, Qt::ElideRight, legend_width + 2));
    y += fm.height() + 2;
  }
}

}  // namespace hull::ui
