#include "support/test_scenes.h"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace hull::testing {

cv::Mat RandomTexture(int size, int seed) {
  cv::RNG rng(static_cast<std::uint64_t>(seed) * 7919 + 17);
  cv::Mat sum = cv::Mat::zeros(size, size, CV_32F);
  double amplitude = 1.0;
  for (int cell = 64; cell >= 4; cell /= 2) {
    const int n = size / cell + 3;
    cv::Mat coarse(n, n, CV_32F);
    rng.fill(coarse, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::Mat fine;
    cv::resize(coarse, fine, cv::Size(n * cell, n * cell), 0, 0, cv::INTER_CUBIC);
    sum += amplitude * fine(cv::Rect(cell, cell, size, size));
    amplitude *= 0.8;
  }
  cv::normalize(sum, sum, 0.0, 1.0, cv::NORM_MINMAX);
  return sum;
}

std::optional<Eigen::Vector3d> TexturedSurface::Intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
  if (kind == Kind::kPlane) {
    const Eigen::Vector3d n = axis_u.cross(axis_v);
    const double den = n.dot(d);
    if (std::abs(den) < 1e-12) return std::nullopt;
    const double t = n.dot(origin - o) / den;
    if (t <= 0) return std::nullopt;
    return o + t * d;
  }
  // Cylinder: |(q - origin) - ((q - origin).a) a| = radius.
  const Eigen::Vector3d a = axis_u;
  const Eigen::Vector3d w = o - origin;
  const Eigen::Vector3d dp = d - d.dot(a) * a, wp = w - w.dot(a) * a;
  const double A = dp.squaredNorm(), B = 2 * dp.dot(wp), C = wp.squaredNorm() - radius * radius;
  const double disc = B * B - 4 * A * C;
  if (A < 1e-12 || disc < 0) return std::nullopt;
  const double sq = std::sqrt(disc);
  double t = (-B - sq) / (2 * A);
  if (t <= 0) t = (-B + sq) / (2 * A);
  if (t <= 0) return std::nullopt;
  return o + t * d;
}

float TexturedSurface::Albedo(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d q = p - origin;
  double s, t;
  if (kind == Kind::kPlane) {
    s = q.dot(axis_u);
    t = q.dot(axis_v);
  } else {
    s = q.dot(axis_u);
    const Eigen::Vector3d w = axis_u.cross(axis_v);
    t = radius * std::atan2(q.dot(w), q.dot(axis_v));
  }
  const int n = texture.cols;
  const double x = s * texels_per_metre + n / 2.0, y = t * texels_per_metre + n / 2.0;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  auto at = [&](double i, double j) {
    const int ii = ((static_cast<int>(i) % n) + n) % n, jj = ((static_cast<int>(j) % n) + n) % n;
    return texture.at<float>(jj, ii);
  };
  return static_cast<float>((1 - ax) * (1 - ay) * at(fx, fy) + ax * (1 - ay) * at(fx + 1, fy) +
                            (1 - ax) * ay * at(fx, fy + 1) + ax * ay * at(fx + 1, fy + 1));
}

std::optional<Eigen::Vector3d> BackProject(const TexturedSurface& s, const Pose& x_w_c, const Eigen::Matrix3d& K,
                                           const Eigen::Vector2d& uv) {
  const Eigen::Vector3d ray = K.inverse() * uv.homogeneous();
  return s.Intersect(x_w_c.translation(), x_w_c.Rotate(ray.normalized()));
}

cv::Mat RenderSurface(const TexturedSurface& s, const Pose& x_w_c, const Eigen::Matrix3d& K, int width, int height,
                      const RenderOptions& o) {
  cv::Mat out(height, width, CV_8U);
  cv::RNG rng(static_cast<std::uint64_t>(o.seed) * 104729 + 3);
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Matrix3d R = x_w_c.rotation();
  const Eigen::Vector3d c = x_w_c.translation();
  const double r0 = 0.5 * std::hypot(width, height);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      // Supersample 2 x 2 for a little anti-aliasing.
      double sum = 0;
      int hits = 0;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d uv(u - 0.25 + 0.5 * (k & 1), v - 0.25 + 0.5 * (k >> 1));
        const auto p = s.Intersect(c, R * (Kinv * uv.homogeneous()).normalized());
        if (p) {
          sum += s.Albedo(*p);
          ++hits;
        }
      }
      double value = hits ? (40 + 200 * sum / 4) * hits / 4 : 0.0;
      if (o.strobe) {
        const double r = std::hypot(u - width / 2.0, v - height / 2.0) / r0;
        value *= 1.0 - 0.75 * r * r;
      }
      value += rng.gaussian(o.noise);
      out.at<unsigned char>(v, u) = cv::saturate_cast<unsigned char>(value);
    }
  }
  return out;
}

}  // namespace hull::testing
