// Where the fan view puts a range and azimuth: the polar image's sector
// (ranges r0..r1 of the sensor's, the whole azimuth field of view) fitted
// into a widget rectangle with the sonar's apex below it, the boresight up
// and positive azimuth (+y, to the right of the sonar) to the right, one
// scale for both axes (what an ARIS or DIDSON display shows).
#pragma once

#include <Eigen/Core>
#include <QPointF>
#include <QRectF>
#include <vector>

#include "survey/acoustic_sequence.h"

namespace hull::ui {

class SonarFanGeometry {
 public:
  SonarFanGeometry() = default;
  // Fits the sector [r0, r1] (clamped to the sensor's range) into `rect`,
  // centred. Throws std::invalid_argument for an empty rect or r1 <= r0.
  SonarFanGeometry(const SonarSensor& sensor, const SonarImageFormat& format, double r0, double r1, const QRectF& rect);

  // Widget pixel of a range (m) and azimuth (rad), and back ((range, azimuth)).
  QPointF ToPixel(double range, double azimuth) const;
  Eigen::Vector2d FromPixel(const QPointF& p) const;
  // Widget pixel of a polar image's (fractional) row and column, and back
  // ((row, column)): the bin centres of SonarImageFormat.
  QPointF BinToPixel(double row, double col) const;
  Eigen::Vector2d PixelToBin(const QPointF& p) const;
  // Inside the drawn sector.
  bool Contains(double range, double azimuth) const;

  // The outline of a sector piece (ranges a..b, azimuths c..d), sampled along its arcs.
  std::vector<QPointF> Sector(double r_a, double r_b, double az_c, double az_d) const;

  double pixels_per_metre() const { return scale_; }
  QPointF apex() const { return apex_; }
  double range_min() const { return r0_; }
  double range_max() const { return r1_; }
  double half_fov() const { return sensor_.azimuth_fov / 2; }
  QRectF bounds() const { return bounds_; }  // the sector's bounding box in the widget
  const SonarSensor& sensor() const { return sensor_; }
  const SonarImageFormat& format() const { return format_; }

 private:
  SonarSensor sensor_;
  SonarImageFormat format_;
  double r0_ = 0, r1_ = 1;
  double scale_ = 1;  // pixels per metre
  QPointF apex_;
  QRectF bounds_;
};

}  // namespace hull::ui
