// What a 2-D plot shows, as plain values (no widget): series of points
// drawn as lines, dots, step histograms or bars, vertical markers, axis
// labels and ranges, a title and a note. Built by models (solver_plot_data,
// the sonar panel's error plots) and drawn by views/plot_widget.
#pragma once

#include <QColor>
#include <QPointF>
#include <QString>
#include <QStringList>
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

}  // namespace hull::ui
