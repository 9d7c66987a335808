// The point detector on images made in code: sub-bin positions of point
// returns on speckle, ridges (walls, faces seen head-on) refused, close
// neighbours kept apart, 16-bit input, and its contract.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "base/error.h"
#include "sonar/sonar_detector.h"

namespace hull {
namespace {

struct Point {
  double row, col, amplitude;
};

// Intensity: speckled background (Gamma(2) around `background`) plus
// Gaussian point returns and, optionally, a ridge along a row and one along a
// column; stored as 8-bit dB (255 at 0 dB, 60 dB range), as the simulator
// and ARIS store it.
cv::Mat MakeImage(const std::vector<Point>& points, double background, int ridge_row = -1, int ridge_col = -1,
                  std::uint64_t seed = 1) {
  const SonarImageFormat f;
  cv::RNG rng(seed);
  cv::Mat out(f.range_bins, f.beams, CV_8U);
  for (int i = 0; i < f.range_bins; ++i) {
    for (int j = 0; j < f.beams; ++j) {
      double I = background * -std::log(rng.uniform(1e-12, 1.0) * rng.uniform(1e-12, 1.0)) / 2;
      for (const Point& p : points) {
        I += p.amplitude * std::exp(-0.5 * (std::pow((i - p.row) / 0.9, 2) + std::pow((j - p.col) / 0.7, 2)));
      }
      if (ridge_row >= 0) I += 0.05 * std::exp(-0.5 * std::pow((i - ridge_row) / 0.8, 2));
      if (ridge_col >= 0) I += 0.05 * std::exp(-0.5 * std::pow((j - ridge_col) / 0.7, 2));
      const double db = 10 * std::log10(std::max(I, 1e-30));
      out.at<std::uint8_t>(i, j) = static_cast<std::uint8_t>(std::lround(std::clamp(255 * (db + 60) / 60, 0.0, 255.0)));
    }
  }
  return out;
}

TEST(SonarDetector, FindsPointsToAFractionOfABin) {
  const SonarSensor s;
  const SonarImageFormat f;
  std::vector<Point> points;
  cv::RNG rng(5);
  for (int k = 0; k < 12; ++k) {
    points.push_back({40.0 + 38 * k + rng.uniform(-0.5, 0.5), 10 + 9.0 * k + rng.uniform(-0.5, 0.5), 0.3});
  }
  const cv::Mat image = MakeImage(points, 1e-4);
  const std::vector<SonarDetection> d = DetectSonarFeatures(image, s, f);
  double sr = 0, sc = 0;
  for (const Point& p : points) {
    const SonarDetection* best = nullptr;
    for (const SonarDetection& x : d) {
      if (std::abs(x.row - p.row) <= 2 && std::abs(x.col - p.col) <= 2) best = &x;
    }
    ASSERT_NE(best, nullptr) << "point at " << p.row << ", " << p.col << " missed";
    sr += std::pow(best->row - p.row, 2);
    sc += std::pow(best->col - p.col, 2);
    EXPECT_NEAR(best->range, f.RowToRange(s, best->row), 1e-12);
    EXPECT_NEAR(best->azimuth, f.ColumnToAzimuth(s, best->col), 1e-12);
    EXPECT_NEAR(std::sqrt(best->covariance(0, 0)), 0.5 * f.RangeBin(s), 1e-12);
    EXPECT_NEAR(std::sqrt(best->covariance(1, 1)), 0.5 * f.BeamWidth(s), 1e-12);
    EXPECT_EQ(best->covariance(0, 1), 0.0);
  }
  EXPECT_LT(std::sqrt(sr / points.size()), 0.25);
  EXPECT_LT(std::sqrt(sc / points.size()), 0.25);
  EXPECT_EQ(d.size(), points.size()) << "false detections on the speckle";
  for (std::size_t i = 1; i < d.size(); ++i) EXPECT_GE(d[i - 1].strength, d[i].strength);
}

TEST(SonarDetector, RefusesRidgesButKeepsPointsOnThem) {
  const SonarSensor s;
  const SonarImageFormat f;
  // A wall along row 250 and a face edge down column 64, with speckle, and
  // one point far stronger than either, on the wall.
  const std::vector<Point> points = {{250.2, 30.4, 0.5}};
  for (std::uint64_t seed : {1, 2, 3}) {
    const cv::Mat image = MakeImage(points, 1e-4, 250, 64, seed);
    const std::vector<SonarDetection> d = DetectSonarFeatures(image, s, f);
    ASSERT_EQ(d.size(), 1u) << "seed " << seed << ": ridges must not give points";
    EXPECT_NEAR(d[0].row, 250.2, 0.3);
    EXPECT_NEAR(d[0].col, 30.4, 0.3);
  }
  // Without the prominence and shape tests the speckle on the ridges passes.
  SonarDetectorOptions loose;
  loose.min_point_ratio = 0;
  loose.min_prominence = 0;
  loose.min_contrast = 25;
  EXPECT_GT(DetectSonarFeatures(MakeImage(points, 1e-4, 250, 64), s, f, loose).size(), 5u);
}

TEST(SonarDetector, NeighboursAndSixteenBitImages) {
  const SonarSensor s;
  const SonarImageFormat f;
  // Two points 4 beams apart (a vertex pair under roll) and a group of four.
  const std::vector<Point> points = {{100, 40, 0.3}, {100.4, 44, 0.3}, {300, 60, 0.3},
                                     {304, 60, 0.2}, {300, 65, 0.3},   {305, 65, 0.2}};
  const cv::Mat image = MakeImage(points, 1e-4);
  const std::vector<SonarDetection> d8 = DetectSonarFeatures(image, s, f);
  EXPECT_EQ(d8.size(), points.size());
  cv::Mat wide;
  image.convertTo(wide, CV_16U, 257.0);
  const std::vector<SonarDetection> d16 = DetectSonarFeatures(wide, s, f);
  ASSERT_EQ(d16.size(), d8.size());
  for (std::size_t i = 0; i < d8.size(); ++i) {
    EXPECT_NEAR(d16[i].row, d8[i].row, 1e-4);
    EXPECT_NEAR(d16[i].col, d8[i].col, 1e-4);
  }
}

TEST(SonarDetector, RefusesBadInputAndOptions) {
  const SonarSensor s;
  const SonarImageFormat f;
  EXPECT_THROW(DetectSonarFeatures(cv::Mat::zeros(100, 128, CV_8U), s, f), std::invalid_argument);
  EXPECT_THROW(DetectSonarFeatures(cv::Mat::zeros(512, 128, CV_32F), s, f), std::invalid_argument);
  EXPECT_THROW(DetectSonarFeatures(cv::Mat::zeros(512, 128, CV_8UC3), s, f), std::invalid_argument);
  EXPECT_TRUE(DetectSonarFeatures(cv::Mat::zeros(512, 128, CV_8U), s, f).empty());
  SonarDetectorOptions o;
  std::string why;
  o.train_rows = o.guard_rows;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("train_rows:", 0), 0u) << why;
  o = SonarDetectorOptions();
  o.sigma_beams = 0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_THROW(DetectSonarFeatures(cv::Mat::zeros(512, 128, CV_8U), s, f, o), OptionError);
}

}  // namespace
}  // namespace hull
