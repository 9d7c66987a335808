// A small 2-D plot drawn with QPainter: lines, points, step histograms and
// bars over linear or logarithmic axes with "nice" ticks, vertical markers,
// a legend and a title. The solver plots and the sonar error plots are made
// of these; they are static figures (no interaction) that scale with the
// widget.
#pragma once

#include <QColor>
#include <QPointF>
#include <QString>
#include <QStringList>
#include <QWidget>
#include <optional>
#include <utility>
#include <vector>

namespace hull::ui {

struct PlotSeries {
  enum class Style {
    kLine,       // a polyline through the points
    kPoints,     // a dot per point
    kHistogram,  // a filled step outline: point i is the bin starting at x (width bin_width)
    kBars,       // a bar per point, centred on x, bin_width wide
  };
  QString name;  // in the legend ("" keeps it out)
  QColor colour = QColor(40, 110, 200);
  Style style = Style::kLine;
  std::vector<QPointF> points;
  double bin_width = 1.0;
  bool dashed = false;
  double width = 1.8;  // pen width (px)
};

struct PlotMarker {
  double x = 0;
  QString label;
  QColor colour = QColor(120, 120, 120);
};

struct PlotData {
  QString title;
  QString x_label, y_label;
  std::vector<PlotSeries> series;
  std::vector<PlotMarker> markers;  // vertical lines
  bool log_y = false;
  // Fixed ranges (otherwise the data's, with a margin).
  std::optional<std::pair<double, double>> x_range, y_range;
  // Bar charts: labels under x = 0, 1, 2, ... instead of numeric ticks.
  QStringList x_categories;
  // Shown in the middle when no series has points.
  QString empty_text;
  // A line of text under the title (e.g. a summary).
  QString note;
};

class PlotWidget : public QWidget {
  Q_OBJECT

 public:
  explicit PlotWidget(QWidget* parent = nullptr);

  void SetData(PlotData data);
  const PlotData& data() const { return data_; }
  bool HasPoints() const;

  QSize sizeHint() const override { return {420, 260}; }
  QSize minimumSizeHint() const override { return {260, 180}; }

  // "Nice" tick positions covering [lo, hi] (about `target` of them).
  static std::vector<double> NiceTicks(double lo, double hi, int target);

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  PlotData data_;
};

}  // namespace hull::ui
