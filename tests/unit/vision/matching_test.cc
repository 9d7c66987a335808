// Detection, stereo and temporal matching on rendered textured surfaces
// whose true correspondences are known (vision_scene.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <set>

#include "unit/vision/vision_scene.h"
#include "vision/feature_detection.h"
#include "vision/stereo_matching.h"
#include "vision/temporal_matching.h"

namespace hull {
namespace {

using testing::MakeVisionScene;
using testing::VisionScene;

KeyframeView MakeView(const VisionScene& s, std::size_t i, const FrontEndOptions& o) {
  KeyframeView v;
  v.keyframe = s.nav[i].keyframe;
  v.x_g_cT = CameraPoseFromNav(s.manifest, s.nav[i]);  // the prior, not the truth
  v.top = DetectFeatures(s.Render(i), o.detection);
  if (s.manifest.camera.stereo())
    v.stereo = MatchStereo(v.top, DetectFeatures(s.Render(i, true), o.detection), s.manifest.camera, o.stereo);
  return v;
}

// Fraction of temporal matches that are true (within 2 px of the transfer).
double Precision(const VisionScene& s, std::size_t i, std::size_t j, const KeyframeView& a, const KeyframeView& b,
                 const std::vector<TemporalMatch>& m) {
  int good = 0;
  for (const auto& t : m) {
    const auto x = s.Transfer(i, a.top.points[static_cast<std::size_t>(t.a)], j);
    if (x && (*x - b.top.points[static_cast<std::size_t>(t.b)]).norm() < 2.0) ++good;
  }
  return m.empty() ? 0.0 : static_cast<double>(good) / static_cast<double>(m.size());
}

TEST(FeatureDetection, ClaheFindsFeaturesInTheDarkCorners) {
  const VisionScene s = MakeVisionScene(false, false, 1);
  const cv::Mat image = s.Render(0);
  DetectionOptions with, without;
  without.clahe = false;
  with.max_features = without.max_features = 0;
  auto corner_count = [&](const ImageFeatures& f) {
    return std::count_if(f.points.begin(), f.points.end(), [&](const Eigen::Vector2d& p) {
      return std::hypot(p.x() - 320, p.y() - 256) > 280;  // where the strobe falls to < 40 %
    });
  };
  const ImageFeatures a = DetectFeatures(image, with), b = DetectFeatures(image, without);
  EXPECT_GT(corner_count(a), 1.5 * corner_count(b) + 10) << corner_count(a) << " vs " << corner_count(b);
  // 16-bit and colour images give the same features as the 8-bit grey one.
  cv::Mat wide, colour;
  image.convertTo(wide, CV_16U, 257.0);
  cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
  EXPECT_EQ(DetectFeatures(wide, with).size(), a.size());
  EXPECT_EQ(DetectFeatures(colour, with).size(), a.size());
  EXPECT_THROW(DetectFeatures(cv::Mat(), with), std::invalid_argument);
}

// An image larger than max_image_size is detected at that size, the
// keypoints in full-resolution pixels: the 640 x 512 scene rendered at twice
// its size and detected with max_image_size 640 gives the features of the
// original image at twice their coordinates (pixel centres mapped), where
// SIFT on the full image would need four times the memory.
TEST(FeatureDetection, LargeImagesAreDetectedAtMaxImageSize) {
  const VisionScene s = MakeVisionScene(false, false, 1);
  const cv::Mat image = s.Render(0);
  cv::Mat large;
  cv::resize(image, large, cv::Size(), 2, 2, cv::INTER_CUBIC);
  DetectionOptions o;
  o.max_image_size = image.cols;
  const ImageFeatures small = DetectFeatures(image, o), big = DetectFeatures(large, o);
  ASSERT_GT(small.size(), 200u);
  ASSERT_GT(big.size(), 200u);
  std::vector<double> distance;
  for (const Eigen::Vector2d& p : big.points) {
    ASSERT_TRUE(p.x() >= -0.5 && p.x() < large.cols - 0.5 && p.y() >= -0.5 && p.y() < large.rows - 0.5);
    double best = 1e9;
    for (const Eigen::Vector2d& q : small.points)
      best = std::min(best, (p - (2 * (q.array() + 0.5) - 0.5).matrix()).norm());
    distance.push_back(best);
  }
  std::nth_element(distance.begin(), distance.begin() + distance.size() / 2, distance.end());
  EXPECT_LT(distance[distance.size() / 2], 1.0);  // px of the large image
  // Below the limit nothing changes; 0 turns it off.
  o.max_image_size = 0;
  EXPECT_EQ(DetectFeatures(image, o).points, DetectFeatures(image, DetectionOptions{}).points);
  o.max_image_size = 10;
  EXPECT_THROW(o.Check(), OptionError);
}

TEST(StereoMatching, MatchesAreTrueAndTriangulateWithinCentimetres) {
  const VisionScene s = MakeVisionScene(true, false, 1);
  FrontEndOptions o;
  const ImageFeatures top = DetectFeatures(s.Render(0), o.detection);
  const ImageFeatures bottom = DetectFeatures(s.Render(0, true), o.detection);
  const auto m = MatchStereo(top, bottom, s.manifest.camera, o.stereo);
  ASSERT_GT(m.size(), 300u) << "of " << top.size() << " top features";
  int good = 0;
  std::vector<double> err;
  std::set<int> bottoms;
  for (const auto& x : m) {
    EXPECT_TRUE(bottoms.insert(x.bottom).second) << "a bottom feature matched twice";
    const auto t = s.Transfer(0, top.points[static_cast<std::size_t>(x.top)], 0, true);
    if (t && (*t - x.bottom_uv).norm() < 2.0) ++good;
    const auto p = s.SurfacePoint(0, top.points[static_cast<std::size_t>(x.top)]);
    if (p) err.push_back((s.TruePose(0) * x.p_top - *p).norm());
  }
  EXPECT_GE(good, 0.95 * static_cast<double>(m.size())) << good << " of " << m.size();
  std::sort(err.begin(), err.end());
  // Depth 1.5 m, baseline 0.1 m, f 560 px: 1 px of disparity is ~4 cm.
  EXPECT_LT(err[err.size() / 2], 0.015);
  EXPECT_LT(err[err.size() * 9 / 10], 0.04);
  // The epipolar constraint is what makes them right: a rig with the wrong
  // baseline direction finds few matches, nearly all false.
  CameraRig wrong = s.manifest.camera;
  wrong.top_to_bottom << 0.1, 0, 0, 0, 0, 0;
  const auto w = MatchStereo(top, bottom, wrong, o.stereo);
  EXPECT_LT(w.size(), m.size() / 5);
  int wrong_good = 0;
  for (const auto& x : w) {
    const auto t = s.Transfer(0, top.points[static_cast<std::size_t>(x.top)], 0, true);
    if (t && (*t - x.bottom_uv).norm() < 2.0) ++wrong_good;
  }
  EXPECT_LT(wrong_good, static_cast<int>(w.size()) / 10 + 1);
}

TEST(TemporalMatching, StereoRigidRansacIsPreciseAndRecoversTheMotion) {
  const VisionScene s = MakeVisionScene(true, false, 3);
  FrontEndOptions o;
  const KeyframeView a = MakeView(s, 0, o), b = MakeView(s, 2, o);
  const PairMatches r = MatchKeyframes(a, b, s.manifest.camera, o.temporal);
  ASSERT_TRUE(r.accepted) << r.note;
  EXPECT_TRUE(r.stereo);
  EXPECT_GT(r.inliers, 100);
  EXPECT_GE(Precision(s, 0, 2, a, b, r.matches), 0.95);
  const Pose truth = s.TruePose(0).Inverse() * s.TruePose(2);
  EXPECT_LT(Pose::AngleBetween(r.x_ca_cb, truth), 0.3 * M_PI / 180);
  EXPECT_LT((r.x_ca_cb.translation() - truth.translation()).norm(), 0.01);
}

TEST(TemporalMatching, RansacAdaptiveStop) {
  EXPECT_EQ(RansacDrawsNeeded(0.0, 3, 0.999, 500), 500);  // no inliers: no information, keep drawing
  EXPECT_EQ(RansacDrawsNeeded(1.0, 3, 0.999, 500), 0);
  EXPECT_EQ(RansacDrawsNeeded(0.5, 3, 0.99, 500), 35);  // log(0.01) / log(1 - 0.125) = 34.5
  EXPECT_EQ(RansacDrawsNeeded(0.05, 3, 0.999, 500), 500);
}

TEST(TemporalMatching, StereoRigidRansacSurvivesABadFirstDraw) {
  // 60 % of b's triangulated points moved 30 cm: most 3-point draws are then
  // hypotheses with no inliers at all. The search must go on past them (it
  // used to stop at the first such draw and drop the pair with 0 inliers).
  const VisionScene s = MakeVisionScene(true, false, 3);
  FrontEndOptions o;
  const KeyframeView a = MakeView(s, 0, o);
  KeyframeView b = MakeView(s, 2, o);
  for (std::size_t k = 0; k < b.stereo.size(); ++k) {
    if (k % 5 < 3) b.stereo[k].p_top += Eigen::Vector3d(0.3, -0.2, 0.1);
  }
  const PairMatches r = MatchKeyframes(a, b, s.manifest.camera, o.temporal);
  ASSERT_TRUE(r.accepted) << r.note;
  EXPECT_GE(Precision(s, 0, 2, a, b, r.matches), 0.95);
  const Pose truth = s.TruePose(0).Inverse() * s.TruePose(2);
  EXPECT_LT(Pose::AngleBetween(r.x_ca_cb, truth), 0.3 * M_PI / 180);
}

// A plane seen by one camera (a flat stretch of hull) fits two motions; the
// one the essential matrix gives may not be the vehicle's, and the planar
// homography's motion nearest the prior is taken then. Every pair of a
// planar mono survey is accepted with the true motion.
TEST(TemporalMatching, MonoOnAPlaneTakesTheMotionOfThePrior) {
  const VisionScene s = MakeVisionScene(false, false, 4);
  FrontEndOptions o;
  int accepted = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < std::min(i + 3, 4); ++j) {
      const KeyframeView a = MakeView(s, i, o), b = MakeView(s, j, o);
      const PairMatches r = MatchKeyframes(a, b, s.manifest.camera, o.temporal);
      EXPECT_TRUE(r.accepted) << i << "-" << j << ": " << r.note;
      if (!r.accepted) continue;
      ++accepted;
      EXPECT_GE(Precision(s, i, j, a, b, r.matches), 0.95);
      const Pose truth = s.TruePose(i).Inverse() * s.TruePose(j);
      EXPECT_LT(Pose::AngleBetween(r.x_ca_cb, truth), 1.0 * M_PI / 180) << i << "-" << j;
    }
  }
  EXPECT_EQ(accepted, 5);
}

TEST(TemporalMatching, MonoEssentialMatrixIsPreciseAndAgreesWithThePrior) {
  const VisionScene s = MakeVisionScene(false, true, 3);
  FrontEndOptions o;
  const KeyframeView a = MakeView(s, 0, o), b = MakeView(s, 2, o);
  const PairMatches r = MatchKeyframes(a, b, s.manifest.camera, o.temporal);
  ASSERT_TRUE(r.accepted) << r.note;
  EXPECT_FALSE(r.stereo);
  EXPECT_GT(r.inliers, 100);
  EXPECT_GE(Precision(s, 0, 2, a, b, r.matches), 0.95);
  const Pose truth = s.TruePose(0).Inverse() * s.TruePose(2);
  EXPECT_LT(Pose::AngleBetween(r.x_ca_cb, truth), 0.5 * M_PI / 180);
  EXPECT_LT(AngleBetweenDirections(r.x_ca_cb.translation(), truth.translation()), 3 * M_PI / 180);

  // A prior that disagrees (20 degrees of yaw): the pair is dropped.
  KeyframeView off = b;
  off.x_g_cT = b.x_g_cT * Pose::FromXyzRpy(0, 0, 0, 0, 0, 20 * M_PI / 180);
  TemporalOptions wide = o.temporal;
  wide.window = 400;  // let matches through, so the check against the prior decides
  const PairMatches bad = MatchKeyframes(a, off, s.manifest.camera, wide);
  EXPECT_FALSE(bad.accepted);
  EXPECT_TRUE(bad.matches.empty());
}

}  // namespace
}  // namespace hull
