// A small 2-D plot drawn with QPainter: lines, points, step histograms and
// bars over linear or logarithmic axes with "nice" ticks, vertical markers,
// a legend and a title. The solver plots and the sonar error plots are made
// of these; they are static figures (no interaction) that scale with the
// widget.
#pragma once

#include <QSize>
#include <QWidget>
#include <vector>

#include "ui/models/plot_data.h"

namespace hull::ui {

class PlotWidget : public QWidget {
  Q_OBJECT

 public:
  explicit PlotWidget(QWidget* parent = nullptr);

  void SetData(PlotData data);
  const PlotData& data() const { return data_; }
  bool HasPoints() const;

  QSize sizeHint() const override { return {420, 260}; }
  QSize minimumSizeHint() const override { return {260, 180}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  PlotData data_;
};

}  // namespace hull::ui
