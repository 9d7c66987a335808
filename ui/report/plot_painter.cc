#include "ui/report/plot_painter.h"

#include <QFontMetricsF>
#include <algorithm>
#include <cmath>

#include "base/deviation_colours.h"

namespace hull::report {

QColor DivergingColour(double t) {
  const std::array<double, 3> rgb = DivergingRgb(t);  // ColorBrewer RdBu, blue (t = -1) to red (t = 1)
  return QColor::fromRgbF(rgb[0], rgb[1], rgb[2]);
}

QColor SequentialColour(double t) {
  static const double stops[9][3] = {{0.267, 0.005, 0.329}, {0.278, 0.175, 0.483}, {0.230, 0.322, 0.546},
                                     {0.173, 0.449, 0.558}, {0.128, 0.567, 0.551}, {0.153, 0.680, 0.504},
                                     {0.361, 0.785, 0.388}, {0.668, 0.862, 0.196}, {0.993, 0.906, 0.144}};
  const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 8.0;
  const int i = std::min(7, static_cast<int>(x));
  const double f = x - i;
  return QColor::fromRgbF(stops[i][0] + f * (stops[i + 1][0] - stops[i][0]),
                          stops[i][1] + f * (stops[i + 1][1] - stops[i][1]),
                          stops[i][2] + f * (stops[i + 1][2] - stops[i][2]));
}

QColor ModelColour(SurfaceModel m) {
  switch (m) {
    case SurfaceModel::kNaive:
      return QColor(0xe6, 0x9f, 0x00);  // orange (Okabe-Ito)
    case SurfaceModel::kAllOnSurface:
      return QColor(0x56, 0xb4, 0xe9);  // sky blue
    case SurfaceModel::kMaxMixture:
      return QColor(0x00, 0x72, 0xb2);  // blue
  }
  return Qt::black;
}

QString ModelLabel(SurfaceModel m) { return QString::fromLatin1(SurfaceModelName(m)); }

QFont FigureFont(double size, bool bold) {
  QFont f(QStringLiteral("DejaVu Sans"));
  f.setStyleHint(QFont::SansSerif);
  f.setPixelSize(std::max(1, static_cast<int>(std::lround(size))));
  f.setBold(bold);
  // Glyph positions at the design size, so text measures the same in a PNG
  // and in a PDF.
  f.setHintingPreference(QFont::PreferNoHinting);
  return f;
}

QString TickLabel(double v, double step) {
  if (step <= 0) {  // logarithmic
    if (v >= 0.01 && v < 1e4) return QString::number(v, 'g', 6);
    const int e = static_cast<int>(std::floor(std::log10(v) + 1e-9));
    const long m = std::lround(v / std::pow(10.0, e));
    static const QString kSuperscript = QStringLiteral("⁰¹²³⁴⁵⁶⁷⁸⁹");
    QString exponent = e < 0 ? QStringLiteral("⁻") : QString();
    for (const QChar c : QString::number(std::abs(e))) exponent += kSuperscript[c.digitValue()];
    return (m == 1 ? QString() : QStringLiteral("%1×").arg(m)) + QStringLiteral("10") + exponent;
  }
  return QString::number(v, 'f', TickDecimals(step));  // as exact as the step (0.25: two)
}

QPointF PlotFrame::Map(double x, double y) const {
  const double fx = (x - x0) / (x1 - x0);
  double fy;
  if (log_y) {
    fy = (std::log10(std::max(y, 1e-300)) - std::log10(y0)) / (std::log10(y1) - std::log10(y0));
  } else {
    fy = (y - y0) / (y1 - y0);
  }
  return {rect.left() + fx * rect.width(), rect.bottom() - fy * rect.height()};
}

void DrawAxes(QPainter& p, const PlotFrame& frame, const AxisLabels& labels) {
  p.save();
  const QRectF& r = frame.rect;
  p.setFont(FigureFont(10));
  const QFontMetricsF fm(p.font());
  QPen grid(QColor(0xe4, 0xe4, 0xe4), 0.8);
  QPen axis(QColor(0x40, 0x40, 0x40), 1.0);
  for (double x : labels.x_ticks) {
    const QPointF a = frame.Map(x, frame.y0);
    if (a.x() < r.left() - 0.5 || a.x() > r.right() + 0.5) continue;
    p.setPen(grid);
    p.drawLine(QPointF(a.x(), r.top()), QPointF(a.x(), r.bottom()));
    p.setPen(axis);
    p.drawLine(QPointF(a.x(), r.bottom()), QPointF(a.x(), r.bottom() + 4));
    const QString t = TickLabel(x, labels.x_step);
    p.drawText(QRectF(a.x() - 40, r.bottom() + 5, 80, fm.height()), Qt::AlignHCenter | Qt::AlignTop, t);
  }
  for (double y : labels.y_ticks) {
    const QPointF a = frame.Map(frame.x0, y);
    if (a.y() < r.top() - 0.5 || a.y() > r.bottom() + 0.5) continue;
    p.setPen(grid);
    p.drawLine(QPointF(r.left(), a.y()), QPointF(r.right(), a.y()));
    p.setPen(axis);
    p.drawLine(QPointF(r.left() - 4, a.y()), QPointF(r.left(), a.y()));
    if (!labels.y_tick_labels) continue;
    const QString t = TickLabel(y, frame.log_y ? 0 : labels.y_step);
    p.drawText(QRectF(r.left() - 86, a.y() - fm.height() / 2, 80, fm.height()), Qt::AlignRight | Qt::AlignVCenter, t);
  }
  p.setPen(axis);
  p.setBrush(Qt::NoBrush);
  p.drawRect(r);
  p.setFont(FigureFont(11));
  if (!labels.x.isEmpty()) {
    p.drawText(QRectF(r.left(), r.bottom() + 6 + fm.height(), r.width(), fm.height() + 4), Qt::AlignHCenter, labels.x);
  }
  if (!labels.y.isEmpty()) {
    p.save();
    p.translate(r.left() - 52, r.center().y());
    p.rotate(-90);
    p.drawText(QRectF(-r.height() / 2 - 40, -fm.height() - 2, r.height() + 80, fm.height() + 4),
               Qt::AlignHCenter | Qt::AlignBottom, labels.y);
    p.restore();
  }
  p.restore();
}

void DrawTitle(QPainter& p, const QRectF& rect, const QString& title) {
  p.save();
  p.setFont(FigureFont(12, true));
  p.setPen(QColor(0x20, 0x20, 0x20));
  p.drawText(QRectF(rect.left(), rect.top() - 20, rect.width(), 18), Qt::AlignLeft | Qt::AlignBottom, title);
  p.restore();
}

namespace {

void DrawMark(QPainter& p, const LegendEntry& e, const QRectF& box) {
  switch (e.mark) {
    case LegendEntry::Mark::kLine:
      p.setPen(QPen(e.colour, 2.2));
      p.drawLine(QPointF(box.left(), box.center().y()), QPointF(box.right(), box.center().y()));
      break;
    case LegendEntry::Mark::kBox:
      p.setPen(QPen(e.colour.darker(130), 0.8));
      p.setBrush(e.colour);
      p.drawRect(box.adjusted(2, 1, -2, -1));
      break;
    case LegendEntry::Mark::kDash:
      p.setPen(QPen(e.colour, 1.4, Qt::DashLine));
      p.drawLine(QPointF(box.left(), box.center().y()), QPointF(box.right(), box.center().y()));
      break;
    case LegendEntry::Mark::kDot:
      p.setPen(Qt::NoPen);
      p.setBrush(e.colour);
      p.drawEllipse(box.center(), 3.2, 3.2);
      break;
  }
}

}  // namespace

void DrawLegend(QPainter& p, const QPointF& corner, const std::vector<LegendEntry>& entries, bool left) {
  if (entries.empty()) return;
  p.save();
  p.setFont(FigureFont(10));
  const QFontMetricsF fm(p.font());
  double w = 0;
  for (const LegendEntry& e : entries) w = std::max(w, fm.horizontalAdvance(e.label));
  const double row = fm.height() + 3;
  const QRectF box(left ? corner.x() + 6 : corner.x() - w - 40, corner.y() + 6, w + 34, row * entries.size() + 6);
  p.setPen(QPen(QColor(0xb0, 0xb0, 0xb0), 0.8));
  p.setBrush(QColor(255, 255, 255, 230));
  p.drawRect(box);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double y = box.top() + 3 + i * row;
    DrawMark(p, entries[i], QRectF(box.left() + 5, y, 18, row));
    p.setPen(QColor(0x20, 0x20, 0x20));
    p.drawText(QRectF(box.left() + 28, y, w + 4, row), Qt::AlignLeft | Qt::AlignVCenter, entries[i].label);
  }
  p.restore();
}

void DrawLegendRow(QPainter& p, const QRectF& rect, const std::vector<LegendEntry>& entries) {
  p.save();
  p.setFont(FigureFont(10.5));
  const QFontMetricsF fm(p.font());
  double total = 0;
  for (const LegendEntry& e : entries) total += 24 + fm.horizontalAdvance(e.label) + 18;
  double x = rect.center().x() - total / 2;
  for (const LegendEntry& e : entries) {
    DrawMark(p, e, QRectF(x, rect.top(), 18, rect.height()));
    p.setPen(QColor(0x20, 0x20, 0x20));
    const double w = fm.horizontalAdvance(e.label);
    p.drawText(QRectF(x + 24, rect.top(), w + 2, rect.height()), Qt::AlignLeft | Qt::AlignVCenter, e.label);
    x += 24 + w + 18;
  }
  p.restore();
}

void DrawColourBar(QPainter& p, const QRectF& rect, double range, const QString& label) {
  p.save();
  constexpr int n = 128;
  p.setPen(Qt::NoPen);
  for (int i = 0; i < n; ++i) {
    const double t = -1 + 2 * (i + 0.5) / n;
    p.setBrush(DivergingColour(t));
    p.drawRect(QRectF(rect.left() + rect.width() * i / n, rect.top(), rect.width() / n + 0.6, rect.height()));
  }
  p.setPen(QPen(QColor(0x40, 0x40, 0x40), 0.8));
  p.setBrush(Qt::NoBrush);
  p.drawRect(rect);
  p.setFont(FigureFont(10));
  const QFontMetricsF fm(p.font());
  const std::vector<double> ticks = NiceTicks(-range, range, 4);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : range;
  for (double v : ticks) {
    const double x = rect.left() + (v + range) / (2 * range) * rect.width();
    p.drawLine(QPointF(x, rect.bottom()), QPointF(x, rect.bottom() + 3));
    p.drawText(QRectF(x - 30, rect.bottom() + 3, 60, fm.height()), Qt::AlignHCenter | Qt::AlignTop, TickLabel(v, step));
  }
  p.setFont(FigureFont(10.5));
  p.drawText(QRectF(rect.left() - 330, rect.top() - 4, 322, rect.height() + 8), Qt::AlignRight | Qt::AlignVCenter,
             label);
  p.restore();
}

void DrawSequentialColourBar(QPainter& p, const QRectF& rect, double max, const QString& label) {
  p.save();
  constexpr int n = 128;
  p.setPen(Qt::NoPen);
  for (int i = 0; i < n; ++i) {
    p.setBrush(SequentialColour((i + 0.5) / n));
    p.drawRect(QRectF(rect.left() + rect.width() * i / n, rect.top(), rect.width() / n + 0.6, rect.height()));
  }
  p.setPen(QPen(QColor(0x40, 0x40, 0x40), 0.8));
  p.setBrush(Qt::NoBrush);
  p.drawRect(rect);
  p.setFont(FigureFont(10));
  const QFontMetricsF fm(p.font());
  const std::vector<double> ticks = NiceTicks(0, max, 4);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : max;
  for (double v : ticks) {
    if (v < 0 || v > max) continue;
    const double x = rect.left() + v / max * rect.width();
    p.drawLine(QPointF(x, rect.bottom()), QPointF(x, rect.bottom() + 3));
    p.drawText(QRectF(x - 30, rect.bottom() + 3, 60, fm.height()), Qt::AlignHCenter | Qt::AlignTop, TickLabel(v, step));
  }
  p.setFont(FigureFont(10.5));
  p.drawText(QRectF(rect.left() - 330, rect.top() - 4, 322, rect.height() + 8), Qt::AlignRight | Qt::AlignVCenter,
             label);
  p.restore();
}

}  // namespace hull::report
