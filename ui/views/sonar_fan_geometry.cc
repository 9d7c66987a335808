#include "ui/views/sonar_fan_geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hull::ui {

SonarFanGeometry::SonarFanGeometry(const SonarSensor& sensor, const SonarImageFormat& format, double r0, double r1,
                                   const QRectF& rect)
    : sensor_(sensor), format_(format) {
  if (!(rect.width() > 0 && rect.height() > 0)) throw std::invalid_argument("SonarFanGeometry: empty rectangle");
  r0_ = std::clamp(r0, sensor.range_min, sensor.range_max);
  r1_ = std::clamp(r1, sensor.range_min, sensor.range_max);
  if (!(r1_ > r0_)) throw std::invalid_argument("SonarFanGeometry: the range window is empty");
  const double half = sensor.azimuth_fov / 2;
  // The sector's extent in metres: right (x) and forward (y) of the apex.
  const double half_width = half < M_PI / 2 ? r1_ * std::sin(half) : r1_;
  const double near = half < M_PI / 2 ? r0_ * std::cos(half) : r1_ * std::cos(half);
  const double far = r1_;
  scale_ = std::min(rect.width() / (2 * half_width), rect.height() / (far - near));
  const double w = 2 * half_width * scale_, h = (far - near) * scale_;
  bounds_ = QRectF(rect.center().x() - w / 2, rect.center().y() - h / 2, w, h);
  apex_ = QPointF(rect.center().x(), bounds_.top() + far * scale_);
}

QPointF SonarFanGeometry::ToPixel(double range, double azimuth) const {
  return {apex_.x() + range * std::sin(azimuth) * scale_, apex_.y() - range * std::cos(azimuth) * scale_};
}

Eigen::Vector2d SonarFanGeometry::FromPixel(const QPointF& p) const {
  const double right = (p.x() - apex_.x()) / scale_, forward = (apex_.y() - p.y()) / scale_;
  return {std::hypot(right, forward), std::atan2(right, forward)};
}

QPointF SonarFanGeometry::BinToPixel(double row, double col) const {
  return ToPixel(format_.RowToRange(sensor_, row), format_.ColumnToAzimuth(sensor_, col));
}

Eigen::Vector2d SonarFanGeometry::PixelToBin(const QPointF& p) const {
  const Eigen::Vector2d ra = FromPixel(p);
  return {format_.RangeToRow(sensor_, ra[0]), format_.AzimuthToColumn(sensor_, ra[1])};
}

bool SonarFanGeometry::Contains(double range, double azimuth) const {
  return range >= r0_ && range <= r1_ && std::abs(azimuth) <= half_fov();
}

std::vector<QPointF> SonarFanGeometry::Sector(double r_a, double r_b, double az_c, double az_d) const {
  constexpr int kArc = 48;
  std::vector<QPointF> out;
  for (int i = 0; i <= kArc; ++i) out.push_back(ToPixel(r_b, az_c + (az_d - az_c) * i / kArc));
  for (int i = kArc; i >= 0; --i) out.push_back(ToPixel(r_a, az_c + (az_d - az_c) * i / kArc));
  return out;
}

}  // namespace hull::ui
