// The fan view of a polar acoustic image (what an ARIS or DIDSON display
// shows): polar to Cartesian, the sonar at the bottom centre, the boresight
// up, azimuth to the right (+y) on the right.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "survey/acoustic_sequence.h"

namespace hull {

class SonarFan {
 public:
  // A fan image `width` pixels wide (its height follows from the field of view).
  SonarFan(const SonarSensor& sensor, const SonarImageFormat& format, int width);

  int width() const { return width_; }
  int height() const { return height_; }
  // Pixel (x right, y down) of a range and azimuth, and back.
  Eigen::Vector2d ToPixel(double range, double azimuth) const;
  Eigen::Vector2d FromPixel(double x, double y) const;  // (range, azimuth)

  // Resamples a polar image (any depth, one channel) into the fan
  // (bilinear); pixels outside the fan get `outside`.
  cv::Mat Render(const cv::Mat& polar, double outside = 0) const;

 private:
  SonarSensor sensor_;
  SonarImageFormat format_;
  int width_ = 0, height_ = 0;
  double scale_ = 1;  // pixels per metre
  double apex_x_ = 0, apex_y_ = 0;
  cv::Mat map_x_, map_y_;  // fan pixel -> polar (column, row)
};

}  // namespace hull
