#include "sonar/sonar_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "base/error.h"

namespace hull {
namespace {

// Offset in (-0.5, 0.5) of the vertex of the parabola through (-1, a), (0, b), (1, c).
double ParabolaPeak(double a, double b, double c) {
  const double den = a - 2 * b + c;
  if (!(den < 0)) return 0;
  return std::clamp(0.5 * (a - c) / den, -0.5, 0.5);
}

}  // namespace

bool SonarDetectorOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& field, const std::string& reason) {
    if (why) *why = field + ": " + reason;
    return false;
  };
  if (!(smooth_sigma >= 0 && smooth_sigma <= 20)) return fail("smooth_sigma", "must be in [0, 20] pixels");
  if (guard_rows < 0 || guard_cols < 0) return fail("guard_rows", "guard half sizes must not be negative");
  if (train_rows <= guard_rows || train_cols <= guard_cols) {
    return fail("train_rows", "the training window must be larger than the guard window in both directions");
  }
  if (train_rows > 1000 || train_cols > 1000) return fail("train_rows", "training half sizes must be at most 1000");
  if (!(shape_sigma > 0 && shape_sigma <= 20)) return fail("shape_sigma", "must be in (0, 20] pixels");
  if (!(min_contrast >= 0)) return fail("min_contrast", "must not be negative");
  if (nms_rows < 1 || nms_cols < 1 || nms_rows > 100 || nms_cols > 100) {
    return fail("nms_rows", "suppression half sizes must be in 1..100");
  }
  if (!(min_point_ratio >= 0 && min_point_ratio <= 1)) return fail("min_point_ratio", "must be in [0, 1]");
  if (!(sigma_bins > 0 && sigma_beams > 0)) return fail("sigma_bins", "standard deviations must be positive");
  if (max_detections < 1) return fail("max_detections", "must be at least 1");
  return true;
}

std::vector<SonarDetection> DetectSonarFeatures(const cv::Mat& image, const SonarSensor& sensor,
                                                const SonarImageFormat& format, const SonarDetectorOptions& o) {
  std::string why;
  if (!o.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  if (image.rows != format.range_bins || image.cols != format.beams || image.channels() != 1 ||
      (image.depth() != CV_8U && image.depth() != CV_16U)) {
    throw std::invalid_argument("DetectSonarFeatures: expected an 8- or 16-bit grey image of range_bins x beams");
  }
  cv::Mat v;
  image.convertTo(v, CV_32F, image.depth() == CV_16U ? 1.0 / 257.0 : 1.0);
  cv::Mat coarse;
  cv::GaussianBlur(v, coarse, cv::Size(), o.shape_sigma, o.shape_sigma, cv::BORDER_REFLECT);
  if (o.smooth_sigma > 0) cv::GaussianBlur(v, v, cv::Size(), o.smooth_sigma, o.smooth_sigma, cv::BORDER_REFLECT);

  // Background mean: training window minus guard window, from box sums.
  const cv::Size outer(2 * o.train_cols + 1, 2 * o.train_rows + 1), inner(2 * o.guard_cols + 1, 2 * o.guard_rows + 1);
  const double n = static_cast<double>(outer.area() - inner.area());
  cv::Mat s_out, s_in;
  cv::boxFilter(v, s_out, CV_32F, outer, cv::Point(-1, -1), false, cv::BORDER_REFLECT);
  cv::boxFilter(v, s_in, CV_32F, inner, cv::Point(-1, -1), false, cv::BORDER_REFLECT);
  cv::Mat local_max;
  cv::dilate(v, local_max, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * o.nms_cols + 1, 2 * o.nms_rows + 1)));
  std::vector<float> cells;
  cells.reserve(static_cast<std::size_t>(n));

  const double bin = format.RangeBin(sensor), beam = format.BeamWidth(sensor);
  std::vector<SonarDetection> out;
  // Cells closer to the border than the ring cannot be judged (their beam
  // pattern or their background is cut off).
  const int margin = std::max(1, static_cast<int>(std::ceil(o.ring_radius)));
  for (int i = margin; i + margin < v.rows; ++i) {
    const float* row = v.ptr<float>(i);
    for (int j = margin; j + margin < v.cols; ++j) {
      const double x = row[j];
      if (x < local_max.at<float>(i, j)) continue;
      // The mean background (cheap) rules out most cells; the rest are tested below.
      const double mean = (s_out.at<float>(i, j) - s_in.at<float>(i, j)) / n;
      if (x - mean < o.min_contrast) continue;
      // A plateau counts once: only its first cell in raster order.
      bool first = true;
      for (int di = -o.nms_rows; di <= 0 && first; ++di) {
        for (int dj = -o.nms_cols; dj <= o.nms_cols; ++dj) {
          if (di == 0 && dj >= 0) break;
          const int a = i + di, b = j + dj;
          if (a >= 0 && b >= 0 && b < v.cols && v.at<float>(a, b) == x) {
            first = false;
            break;
          }
        }
      }
      if (!first) continue;
      // Point-like: curvatures of the peak along range, azimuth and their mix.
      const double up = v.at<float>(i - 1, j), down = v.at<float>(i + 1, j);
      const double left = row[j - 1], right = row[j + 1];
      const double dyy = up + down - 2 * x, dxx = left + right - 2 * x;
      const double dxy = (v.at<float>(i + 1, j + 1) - v.at<float>(i + 1, j - 1) - v.at<float>(i - 1, j + 1) +
                          v.at<float>(i - 1, j - 1)) /
                         4;
      // Eigenvalues of -H.
      const double tr = -(dxx + dyy), det = dxx * dyy - dxy * dxy;
      const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
      const double l_big = tr / 2 + disc, l_small = tr / 2 - disc;
      const double ratio = l_small > 0 ? l_small / l_big : 0;
      if (ratio < o.min_point_ratio) continue;
      // Prominence: a ridge stays high on both sides along itself, a point
      // falls off in every direction (though a neighbour may be high on one
      // side): over the 4 axes through the peak, the lower of the two ring
      // samples on either side; the peak must top the highest of those.
      const auto ring_at = [&](int k) {
        const double ang = k * M_PI / 4;
        const int a = std::clamp(static_cast<int>(std::lround(i + o.ring_radius * std::sin(ang))), 0, v.rows - 1);
        const int b = std::clamp(static_cast<int>(std::lround(j + o.ring_radius * std::cos(ang))), 0, v.cols - 1);
        return static_cast<double>(v.at<float>(a, b));
      };
      double ring = -INFINITY;
      for (int k = 0; k < 4; ++k) ring = std::max(ring, std::min(ring_at(k), ring_at(k + 4)));
      if (x - ring < o.min_prominence) continue;
      // Ordered-statistics CFAR: the background is the median of the training
      // cells, which other targets nearby (an object's other vertices, its
      // bright faces) do not raise as they would raise a mean.
      cells.clear();
      for (int a = i - o.train_rows; a <= i + o.train_rows; ++a) {
        const int ra = std::clamp(a < 0 ? -a - 1 : (a >= v.rows ? 2 * v.rows - a - 1 : a), 0, v.rows - 1);
        const float* r = v.ptr<float>(ra);
        const bool guard_row = std::abs(a - i) <= o.guard_rows;
        for (int b = j - o.train_cols; b <= j + o.train_cols; ++b) {
          if (guard_row && std::abs(b - j) <= o.guard_cols) continue;
          const int cb = std::clamp(b < 0 ? -b - 1 : (b >= v.cols ? 2 * v.cols - b - 1 : b), 0, v.cols - 1);
          cells.push_back(r[cb]);
        }
      }
      const auto mid = cells.begin() + static_cast<std::ptrdiff_t>(cells.size() / 2);
      std::nth_element(cells.begin(), mid, cells.end());
      const double median = *mid;
      if (x - median < o.min_contrast) continue;
      SonarDetection d;
      d.row = i + ParabolaPeak(up, x, down);
      d.col = j + ParabolaPeak(left, x, right);
      d.range = format.RowToRange(sensor, d.row);
      d.azimuth = format.ColumnToAzimuth(sensor, d.col);
      d.covariance = Eigen::Vector2d(std::pow(o.sigma_bins * bin, 2), std::pow(o.sigma_beams * beam, 2)).asDiagonal();
      d.strength = x;
      d.contrast = x - median;
      d.point_ratio = ratio;
      d.prominence = x - ring;
      out.push_back(d);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const SonarDetection& a, const SonarDetection& b) { return a.strength > b.strength; });
  if (static_cast<int>(out.size()) > o.max_detections) out.resize(static_cast<std::size_t>(o.max_detections));
  return out;
}

}  // namespace hull
