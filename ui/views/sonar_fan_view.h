// The sonar's fan view (issue 11): the polar acoustic image of the current
// step resampled into its fan (range x azimuth -> x, y with the sequence's
// sensor geometry, SonarFanGeometry), range rings labelled in metres and
// azimuth lines labelled in degrees; on it the image chain of that step:
// the front end's detections, the EKF's predicted features with their
// 2-sigma ellipses in (range, azimuth) (drawn in polar coordinates and
// mapped into the fan, so they curve with it), the associations (a line from
// each paired detection to its prediction, in the feature's colour) and
// the detections that paired with nothing and start new tentative features.
// QPainter only.
#pragma once

#include <QImage>
#include <QWidget>
#include <memory>
#include <opencv2/core/mat.hpp>

#include "ui/session/sonar_results.h"
#include "ui/views/sonar_fan_geometry.h"

namespace hull::ui {

class SonarFanView : public QWidget {
  Q_OBJECT

 public:
  enum class Zoom { kWholeFan, kFeatures };

  explicit SonarFanView(QWidget* parent = nullptr);

  void SetRun(std::shared_ptr<const SonarRun> run);  // nullptr clears
  void SetStep(int step);
  int step() const { return step_; }
  // The whole fan, or the ranges where the run's features are (the same
  // window for every step).
  void SetZoom(Zoom zoom);
  Zoom zoom() const { return zoom_; }
  // The ellipses are drawn at 2 sigma times this factor.
  void SetEllipseScale(double scale);

  // Where things are drawn at the widget's current size (invalid without a run).
  SonarFanGeometry FanGeometry() const;
  bool HasGeometry() const;

  // What the current step shows.
  struct Counts {
    int detections = 0, in_state_pairs = 0, waiting_pairs = 0, unassociated = 0;
    int predictions = 0, waiting_predictions = 0, ellipses = 0, rings = 0, azimuth_lines = 0;
  };
  Counts counts() const { return counts_; }

  QSize sizeHint() const override { return {520, 460}; }
  QSize minimumSizeHint() const override { return {200, 120}; }

  // The colour of a feature's prediction and association lines.
  static QColor FeatureColour(std::int64_t id);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  QRectF FanRect() const;
  QRectF RectFor(bool legend_at_side) const;
  bool LegendAtSide() const;
  double LegendWidth() const;
  double LegendRowsHeight() const;
  double LegendHeight() const;
  void UpdateWindow();  // the zoom's range window
  const QImage& FanImage(const SonarFanGeometry& g);
  void DrawGrid(QPainter& p, const SonarFanGeometry& g);
  void DrawFrame(QPainter& p, const SonarFanGeometry& g, const SonarFrame& frame);
  void DrawLegend(QPainter& p);

  std::shared_ptr<const SonarRun> run_;
  int step_ = 0;
  Zoom zoom_ = Zoom::kWholeFan;
  double ellipse_scale_ = 1.0;
  double r0_ = 0, r1_ = 1;  // the range window
  Counts counts_;
  // The fan image of (step, size, window), and the remap tables of (size, window).
  QImage image_;
  int image_step_ = -1;
  QRectF maps_for_;
  double maps_r0_ = -1, maps_r1_ = -1;
  cv::Mat map_x_, map_y_;
};

}  // namespace hull::ui
