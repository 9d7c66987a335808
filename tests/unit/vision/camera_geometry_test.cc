// Two-view geometry written by hand, checked against OpenCV's own routines.
#include "vision/camera_geometry.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <random>

#include "base/error.h"
#include "simulate/survey_plan.h"
#include "vision/stereo_matching.h"
#include "vision/vision_options.h"

namespace hull {
namespace {

Pose RandomPose(std::mt19937& rng, double t_scale) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Pose::FromXyzRpy(t_scale * u(rng), t_scale * u(rng), t_scale * u(rng), 0.3 * u(rng), 0.3 * u(rng),
                          0.3 * u(rng));
}

TEST(CameraGeometry, TriangulateDltMatchesOpenCv) {
  std::mt19937 rng(3);
  const Eigen::Matrix3d K = CameraMatrix({900, 910, 640, 500});
  for (int trial = 0; trial < 20; ++trial) {
    const Pose c1 = RandomPose(rng, 0.2), c2 = c1 * Pose::FromXyzRpy(0.3, 0.05, 0.02, 0.02, -0.05, 0.03);
    const Eigen::Matrix<double, 3, 4> P1 = ProjectionMatrix(K, c1), P2 = ProjectionMatrix(K, c2);
    const Eigen::Vector3d X = c1 * Eigen::Vector3d(0.2 * trial / 20.0 - 0.1, 0.1, 2.0 + 0.1 * trial);
    Eigen::Vector2d x1 = (P1 * X.homogeneous()).hnormalized(), x2 = (P2 * X.homogeneous()).hnormalized();
    x1 += Eigen::Vector2d(0.7, -0.4);  // noisy pixels: the two must agree off the exact solution too
    x2 += Eigen::Vector2d(-0.3, 0.5);
    const Eigen::Vector3d mine = TriangulateDlt(P1, P2, x1, x2);
    cv::Mat P1c, P2c, out;
    cv::eigen2cv(P1, P1c);
    cv::eigen2cv(P2, P2c);
    cv::Mat a = (cv::Mat_<double>(2, 1) << x1.x(), x1.y()), b = (cv::Mat_<double>(2, 1) << x2.x(), x2.y());
    cv::triangulatePoints(P1c, P2c, a, b, out);
    const Eigen::Vector3d cvp(out.at<double>(0) / out.at<double>(3), out.at<double>(1) / out.at<double>(3),
                              out.at<double>(2) / out.at<double>(3));
    EXPECT_LT((mine - cvp).norm(), 1e-7) << trial;
    EXPECT_LT((mine - X).norm(), 0.05) << trial;
  }
}

TEST(CameraGeometry, FundamentalMatrixHoldsForTrueCorrespondencesAndMatchesOpenCv) {
  std::mt19937 rng(5);
  const Eigen::Matrix3d K1 = CameraMatrix({900, 900, 640, 500}), K2 = CameraMatrix({950, 940, 600, 520});
  const Pose x_c1_c2 = Pose::FromXyzRpy(0.1, 0.3, -0.05, 0.05, 0.1, -0.08);
  const Eigen::Matrix3d F = FundamentalMatrix(K1, K2, x_c1_c2);
  std::vector<cv::Point2d> p1, p2;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector3d X(u(rng), u(rng), 3 + u(rng));
    const Eigen::Vector2d x1 = (K1 * X).hnormalized(), x2 = (K2 * (x_c1_c2.Inverse() * X)).hnormalized();
    EXPECT_LT(EpipolarDistance(F, x1, x2), 1e-9);
    EXPECT_GT(EpipolarDistance(F, x1, x2 + Eigen::Vector2d(5, -5)), 0.1);
    p1.emplace_back(x1.x(), x1.y());
    p2.emplace_back(x2.x(), x2.y());
  }
  // OpenCV's 8-point estimate from exact correspondences is the same F up to scale.
  cv::Mat Fcv = cv::findFundamentalMat(p1, p2, cv::FM_8POINT);
  Eigen::Matrix3d Fo;
  cv::cv2eigen(Fcv, Fo);
  Eigen::Matrix3d a = F / F.norm(), b = Fo / Fo.norm();
  if (a.cwiseProduct(b).sum() < 0) b = -b;
  EXPECT_LT((a - b).norm(), 1e-6);
}

TEST(CameraGeometry, RectifiedRigWithVerticalBaselineMeansSameColumn) {
  CameraRig rig;  // the contract's example: bottom camera 0.10 m along the top camera's y, no rotation
  const Eigen::Matrix3d F =
      FundamentalMatrix(CameraMatrix(rig.top), CameraMatrix(rig.bottom), Pose::FromVector(rig.top_to_bottom));
  for (double du : {-3.0, 0.0, 1.5}) {
    EXPECT_NEAR(EpipolarDistance(F, {300, 400}, {300 + du, 250}), std::abs(du), 1e-9);
  }
  // And the triangulated depth follows the disparity along y: z = f b / d.
  const Eigen::Vector3d p = TriangulateStereo(rig, {700, 600}, {700, 600 - 1150 * 0.1 / 2.0});
  EXPECT_NEAR(p.z(), 2.0, 1e-9);
}

TEST(CameraGeometry, AlignRigidMatchesOpenCvUmeyama) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, 0.01);
  const Pose T = RandomPose(rng, 1.0);
  std::vector<Eigen::Vector3d> src, dst;
  std::vector<cv::Point3d> s, d;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 40; ++i) {
    src.emplace_back(u(rng), u(rng), 2 + u(rng));
    dst.push_back(T * src.back() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    s.emplace_back(src.back().x(), src.back().y(), src.back().z());
    d.emplace_back(dst.back().x(), dst.back().y(), dst.back().z());
  }
  const Pose mine = AlignRigid(src, dst);
  const cv::Mat A = cv::estimateAffine3D(s, d, nullptr, true);  // Umeyama, scale fixed to 1
  Eigen::Matrix<double, 3, 4> Ae;
  cv::cv2eigen(A, Ae);
  EXPECT_LT((mine.rotation() - Ae.leftCols<3>()).norm(), 1e-9);
  EXPECT_LT((mine.translation() - Ae.col(3)).norm(), 1e-9);
  EXPECT_LT(Pose::AngleBetween(mine, T), 0.01);
  // Exact data, and a planar set (the reflection case): the exact transform.
  for (auto& p : src) p.z() = 2.0;
  for (std::size_t i = 0; i < src.size(); ++i) dst[i] = T * src[i];
  const Pose exact = AlignRigid(src, dst);
  EXPECT_LT(Pose::AngleBetween(exact, T), 1e-9);
  EXPECT_LT((exact.translation() - T.translation()).norm(), 1e-9);
  EXPECT_GT(exact.rotation().determinant(), 0);
}

TEST(CameraGeometry, CameraPoseFromNavMatchesTheSimulator) {
  SurveyManifest m;
  NavRecord nav;
  nav.x_gv << 1, 2, 3, 0.1, -0.2, 0.3;
  nav.servo = 1.2;
  const Pose x_s_cT = Pose::FromVector(m.camera.servo_to_top);
  const Pose expected = Pose::FromVector(nav.x_gv) * VehicleToCamera(m, x_s_cT, nav.servo);
  const Pose got = CameraPoseFromNav(m, nav);
  EXPECT_LT(Pose::AngleBetween(got, expected), 1e-12);
  EXPECT_LT((got.translation() - expected.translation()).norm(), 1e-12);
  const Pose bottom = CameraPoseFromNav(m, nav, true);
  EXPECT_NEAR((bottom.translation() - got.translation()).norm(), 0.10, 1e-12);
}

TEST(VisionOptions, CheckNamesTheField) {
  FrontEndOptions o;
  EXPECT_NO_THROW(o.Check());
  auto field_of = [](const FrontEndOptions& bad) {
    try {
      bad.Check();
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  FrontEndOptions b = o;
  b.detection.clahe_tiles = 0;
  EXPECT_EQ(field_of(b), "clahe_tiles");
  b = o;
  b.stereo.ratio = 1.5;
  EXPECT_EQ(field_of(b), "ratio");
  b = o;
  b.stereo.max_depth = b.stereo.min_depth;
  EXPECT_EQ(field_of(b), "max_depth");
  b = o;
  b.temporal.window = -1;
  EXPECT_EQ(field_of(b), "window");
  b = o;
  b.temporal.min_inliers = 3;
  EXPECT_EQ(field_of(b), "min_inliers");
  b = o;
  b.tracks.min_keyframes = 1;
  EXPECT_EQ(field_of(b), "min_keyframes");
  b = o;
  b.detection.clahe_clip = std::nan("");
  EXPECT_EQ(field_of(b), "clahe_clip");
}

}  // namespace
}  // namespace hull
