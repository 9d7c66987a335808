#include "sonar/sonar_fan.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace hull {

SonarFan::SonarFan(const SonarSensor& sensor, const SonarImageFormat& format, int width)
    : sensor_(sensor), format_(format), width_(width) {
  if (width < 16) throw std::invalid_argument("SonarFan: the fan must be at least 16 pixels wide");
  const double half = sensor.azimuth_fov / 2;
  // Horizontal extent: the far arc's corners (or the whole far arc beyond 90 degrees).
  const double half_width_m = half < M_PI / 2 ? sensor.range_max * std::sin(half) : sensor.range_max;
  const double bottom_m = half < M_PI / 2 ? sensor.range_min * std::cos(half) : sensor.range_max * std::cos(half);
  const double top_m = sensor.range_max;
  scale_ = (width - 1) / (2 * half_width_m);
  height_ = static_cast<int>(std::ceil((top_m - std::min(0.0, bottom_m)) * scale_)) + 1;
  apex_x_ = (width - 1) / 2.0;
  apex_y_ = top_m * scale_;
  map_x_.create(height_, width_, CV_32F);
  map_y_.create(height_, width_, CV_32F);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const Eigen::Vector2d ra = FromPixel(x, y);
      map_x_.at<float>(y, x) = static_cast<float>(format_.AzimuthToColumn(sensor_, ra[1]));
      map_y_.at<float>(y, x) = static_cast<float>(format_.RangeToRow(sensor_, ra[0]));
      if (ra[0] < sensor_.range_min || ra[0] > sensor_.range_max || std::abs(ra[1]) > half) {
        map_x_.at<float>(y, x) = -10;  // outside: the border value
        map_y_.at<float>(y, x) = -10;
      }
    }
  }
}

Eigen::Vector2d SonarFan::ToPixel(double range, double azimuth) const {
  return {apex_x_ + range * std::sin(azimuth) * scale_, apex_y_ - range * std::cos(azimuth) * scale_};
}

Eigen::Vector2d SonarFan::FromPixel(double x, double y) const {
  const double right = (x - apex_x_) / scale_, forward = (apex_y_ - y) / scale_;
  return {std::hypot(right, forward), std::atan2(right, forward)};
}

cv::Mat SonarFan::Render(const cv::Mat& polar, double outside) const {
  if (polar.rows != format_.range_bins || polar.cols != format_.beams || polar.channels() != 1) {
    throw std::invalid_argument("SonarFan::Render: the polar image is not range_bins x beams, one channel");
  }
  cv::Mat out;
  cv::remap(polar, out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(outside));
  return out;
}

}  // namespace hull
