// The acoustic camera model: H (eq. 10) and G (eq. 6) against numerical
// derivatives and autodiff, the inverse model and the field of view.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <random>

#include "sonar/acoustic_camera.h"

namespace hull {
namespace {

Vector6d RandomPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> t(-2, 2), a(-3.0, 3.0), p(-1.0, 1.0);
  Vector6d x;
  x << t(rng), t(rng), t(rng), a(rng), p(rng), a(rng);
  return x;
}

// A point seen from the pose at a random range, azimuth and elevation.
Eigen::Vector3d PointInFront(const Vector6d& pose, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> r(0.8, 4.5), az(-0.27, 0.27), el(-0.12, 0.12);
  return SonarBackProject<double>(pose, r(rng), az(rng), el(rng));
}

TEST(AcousticCamera, MeasurementMatchesTheContractModel) {
  // Sonar at (1, 2, 3) yawed by 90 deg: its boresight is world +y, its right (y) is world -x.
  Vector6d pose;
  pose << 1, 2, 3, 0, 0, M_PI / 2;
  const Eigen::Vector3d p(1 - 0.5, 2 + 2.0, 3 + 0.3);  // 2 m ahead, 0.5 m right, 0.3 m below
  const Eigen::Vector3d q = WorldToSonar<double>(pose, p);
  EXPECT_NEAR(q.x(), 2.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.5, 1e-12);
  EXPECT_NEAR(q.z(), 0.3, 1e-12);
  const Eigen::Vector2d z = SonarMeasure<double>(pose, p);
  EXPECT_NEAR(z[0], std::sqrt(4 + 0.25 + 0.09), 1e-12);
  EXPECT_NEAR(z[1], std::atan2(0.5, 2.0), 1e-12);
  const Eigen::Vector3d polar = SonarPolarOf(pose, p);
  EXPECT_NEAR(polar[2], std::asin(0.3 / z[0]), 1e-12);
  // Back projection inverts it.
  EXPECT_LT((SonarBackProject<double>(pose, polar[0], polar[1], polar[2]) - p).norm(), 1e-12);
}

TEST(AcousticCamera, HMatchesNumericalDerivativesAndAutodiff) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector6d pose = RandomPose(rng);
    const Eigen::Vector3d p = PointInFront(pose, rng);
    Eigen::Matrix<double, 2, 6> Hp;
    Eigen::Matrix<double, 2, 3> Hl;
    const Eigen::Vector2d z = SonarMeasureJacobians(pose, p, &Hp, &Hl);
    EXPECT_LT((z - SonarMeasure<double>(pose, p)).norm(), 1e-12);
    // Central differences.
    const double h = 1e-6;
    Eigen::Matrix<double, 2, 6> Np;
    Eigen::Matrix<double, 2, 3> Nl;
    for (int i = 0; i < 6; ++i) {
      Vector6d a = pose, b = pose;
      a[i] += h;
      b[i] -= h;
      Np.col(i) = (SonarMeasure<double>(a, p) - SonarMeasure<double>(b, p)) / (2 * h);
    }
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d a = p, b = p;
      a[i] += h;
      b[i] -= h;
      Nl.col(i) = (SonarMeasure<double>(pose, a) - SonarMeasure<double>(pose, b)) / (2 * h);
    }
    EXPECT_LT((Hp - Np).cwiseAbs().maxCoeff(), 1e-6 * (1 + Np.cwiseAbs().maxCoeff())) << "trial " << trial;
    EXPECT_LT((Hl - Nl).cwiseAbs().maxCoeff(), 1e-6 * (1 + Nl.cwiseAbs().maxCoeff())) << "trial " << trial;
    // Forward-mode autodiff of the templated model.
    using Jet = ceres::Jet<double, 9>;
    Eigen::Matrix<Jet, 6, 1> xj;
    Eigen::Matrix<Jet, 3, 1> pj;
    for (int i = 0; i < 6; ++i) xj[i] = Jet(pose[i], i);
    for (int i = 0; i < 3; ++i) pj[i] = Jet(p[i], 6 + i);
    const Eigen::Matrix<Jet, 2, 1> zj = SonarMeasure<Jet>(xj, pj);
    for (int r = 0; r < 2; ++r) {
      EXPECT_LT((Hp.row(r).transpose() - zj[r].v.head<6>()).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_LT((Hl.row(r).transpose() - zj[r].v.tail<3>()).cwiseAbs().maxCoeff(), 1e-9);
    }
  }
}

TEST(AcousticCamera, GMatchesNumericalDerivatives) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> small(-0.3, 0.3);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector6d x = RandomPose(rng);
    Vector6d u;
    for (int i = 0; i < 6; ++i) u[i] = small(rng);
    Matrix6d G, Gu;
    const Vector6d y = SonarMotion(x, u, &G, &Gu);
    EXPECT_LT((Pose::FromVector(y).Matrix() - (Pose::FromVector(x) * Pose::FromVector(u)).Matrix()).norm(), 1e-12);
    const double h = 1e-6;
    Matrix6d NG, NGu;
    for (int i = 0; i < 6; ++i) {
      Vector6d a = x, b = x;
      a[i] += h;
      b[i] -= h;
      NG.col(i) =
          PoseVectorDifference(SonarMotion(a, u, nullptr, nullptr), SonarMotion(b, u, nullptr, nullptr)) / (2 * h);
      Vector6d c = u, d = u;
      c[i] += h;
      d[i] -= h;
      NGu.col(i) =
          PoseVectorDifference(SonarMotion(x, c, nullptr, nullptr), SonarMotion(x, d, nullptr, nullptr)) / (2 * h);
    }
    EXPECT_LT((G - NG).cwiseAbs().maxCoeff(), 1e-6 * (1 + NG.cwiseAbs().maxCoeff())) << "trial " << trial;
    EXPECT_LT((Gu - NGu).cwiseAbs().maxCoeff(), 1e-6 * (1 + NGu.cwiseAbs().maxCoeff())) << "trial " << trial;
  }
}

TEST(AcousticCamera, BackProjectionJacobiansMatchNumericalDerivatives) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> r(0.8, 4.5), az(-0.27, 0.27), el(-0.12, 0.12);
  for (int trial = 0; trial < 100; ++trial) {
    const Vector6d pose = RandomPose(rng);
    const Eigen::Vector3d polar(r(rng), az(rng), el(rng));
    Eigen::Matrix<double, 3, 6> Jx;
    Eigen::Matrix3d Jz;
    const Eigen::Vector3d p = SonarBackProjectJacobians(pose, polar[0], polar[1], polar[2], &Jx, &Jz);
    EXPECT_LT((SonarPolarOf(pose, p) - polar).norm(), 1e-10);
    const double h = 1e-6;
    for (int i = 0; i < 6; ++i) {
      Vector6d a = pose, b = pose;
      a[i] += h;
      b[i] -= h;
      const Eigen::Vector3d d = (SonarBackProject<double>(a, polar[0], polar[1], polar[2]) -
                                 SonarBackProject<double>(b, polar[0], polar[1], polar[2])) /
                                (2 * h);
      EXPECT_LT((Jx.col(i) - d).cwiseAbs().maxCoeff(), 1e-6);
    }
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d a = polar, b = polar;
      a[i] += h;
      b[i] -= h;
      const Eigen::Vector3d d =
          (SonarBackProject<double>(pose, a[0], a[1], a[2]) - SonarBackProject<double>(pose, b[0], b[1], b[2])) /
          (2 * h);
      EXPECT_LT((Jz.col(i) - d).cwiseAbs().maxCoeff(), 1e-6);
    }
  }
}

TEST(AcousticCamera, FieldOfView) {
  const SonarSensor s;  // ARIS Explorer 3000: 0.7..5 m, 32 x 14 deg
  EXPECT_TRUE(InSonarView(s, Eigen::Vector3d(2.5, 0, 0)));
  EXPECT_TRUE(InSonarView(s, Eigen::Vector3d(0.7, s.azimuth_fov / 2, -s.elevation_fov / 2)));
  EXPECT_TRUE(InSonarView(s, Eigen::Vector3d(5.0, -s.azimuth_fov / 2, s.elevation_fov / 2)));
  EXPECT_FALSE(InSonarView(s, Eigen::Vector3d(0.69, 0, 0)));
  EXPECT_FALSE(InSonarView(s, Eigen::Vector3d(5.01, 0, 0)));
  EXPECT_FALSE(InSonarView(s, Eigen::Vector3d(2.5, s.azimuth_fov / 2 + 1e-9, 0)));
  EXPECT_FALSE(InSonarView(s, Eigen::Vector3d(2.5, 0, -s.elevation_fov / 2 - 1e-9)));
}

TEST(AcousticCamera, ControlSigmaFollowsTheContract) {
  SonarMotionNoise n;
  Vector6d u;
  u << 0.2, -0.01, 0.0, 0.5, -0.001, 0.0;
  const Vector6d s = ControlSigma(n, u);
  EXPECT_DOUBLE_EQ(s[0], 0.01);
  EXPECT_DOUBLE_EQ(s[1], 5e-4);
  EXPECT_DOUBLE_EQ(s[2], 1e-4);  // floor
  EXPECT_DOUBLE_EQ(s[3], 0.025);
  EXPECT_DOUBLE_EQ(s[4], 1e-4);  // 5e-5 is below the floor
  EXPECT_DOUBLE_EQ(s[5], 1e-4);
}

}  // namespace
}  // namespace hull
