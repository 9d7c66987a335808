// Poses: the algebra of (+) and (-) (Smith, Self and Cheeseman), the Z-Y-X
// Euler convention of the survey contract, and the Jacobians against
// central differences.
#include "geometry/pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hull {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Vector6d V(double x, double y, double z, double r, double p, double w) {
  Vector6d v;
  v << x, y, z, r, p, w;
  return v;
}

// Random poses with pitch kept `margin` away from gimbal lock.
Vector6d RandomPose(std::mt19937& rng, double margin = 0.05) {
  std::uniform_real_distribution<double> t(-20, 20), a(-M_PI, M_PI), p(-M_PI / 2 + margin, M_PI / 2 - margin);
  return V(t(rng), t(rng), t(rng), a(rng), p(rng), a(rng));
}

// Two Euler vectors describe the same pose (angles compared on SO(3)).
void ExpectSamePose(const Vector6d& a, const Vector6d& b, double tol) {
  EXPECT_LT((a.head<3>() - b.head<3>()).norm(), tol) << a.transpose() << "\n vs " << b.transpose();
  const Matrix3d Ra = RotationFromEuler(a[3], a[4], a[5]), Rb = RotationFromEuler(b[3], b[4], b[5]);
  EXPECT_LT((Ra - Rb).norm(), tol) << a.transpose() << "\n vs " << b.transpose();
}

TEST(Pose, RotationIsRzRyRx) {
  std::mt19937 rng(1);
  for (int i = 0; i < 100; ++i) {
    const Vector6d x = RandomPose(rng, 0);
    const Matrix3d R = RotationFromEuler(x[3], x[4], x[5]);
    const Matrix3d expect = (Eigen::AngleAxisd(x[5], Vector3d::UnitZ()) * Eigen::AngleAxisd(x[4], Vector3d::UnitY()) *
                             Eigen::AngleAxisd(x[3], Vector3d::UnitX()))
                                .toRotationMatrix();
    EXPECT_LT((R - expect).norm(), 1e-14);
    EXPECT_LT((Pose::FromVector(x).rotation() - expect).norm(), 1e-14);
  }
}

TEST(Pose, KnownCompositions) {
  // Turn left 90 degrees, then step forward: the step goes along +y.
  ExpectSamePose(Oplus(V(1, 0, 0, 0, 0, M_PI / 2), V(1, 0, 0, 0, 0, 0)), V(1, 1, 0, 0, 0, M_PI / 2), 1e-15);
  // Pitch up 90 degrees: forward becomes down (-z).
  ExpectSamePose(Oplus(V(0, 0, 0, 0, M_PI / 2, 0), V(2, 0, 0, 0, 0, 0)), V(0, 0, -2, 0, M_PI / 2, 0), 1e-15);
  // Roll 90 degrees: y becomes z.
  ExpectSamePose(Oplus(V(0, 0, 0, M_PI / 2, 0, 0), V(0, 3, 0, 0, 0, 0)), V(0, 0, 3, M_PI / 2, 0, 0), 1e-15);
  // Yaws add.
  ExpectSamePose(Oplus(V(0, 0, 0, 0, 0, 0.3), V(0, 0, 0, 0, 0, 0.4)), V(0, 0, 0, 0, 0, 0.7), 1e-15);
  ExpectSamePose(Ominus(V(1, 2, 3, 0, 0, M_PI / 2)), V(-2, 1, -3, 0, 0, -M_PI / 2), 1e-15);
}

TEST(Pose, OplusIsAssociative) {
  std::mt19937 rng(2);
  for (int i = 0; i < 200; ++i) {
    const Vector6d a = RandomPose(rng), b = RandomPose(rng), c = RandomPose(rng);
    ExpectSamePose(Oplus(Oplus(a, b), c), Oplus(a, Oplus(b, c)), 1e-11);
    const Pose A = Pose::FromVector(a), B = Pose::FromVector(b), C = Pose::FromVector(c);
    ExpectSamePose(((A * B) * C).ToVector(), (A * (B * C)).ToVector(), 1e-11);
    ExpectSamePose((A * B).ToVector(), Oplus(a, b), 1e-11);
  }
}

TEST(Pose, InverseIdentities) {
  std::mt19937 rng(3);
  const Vector6d zero = Vector6d::Zero();
  for (int i = 0; i < 200; ++i) {
    const Vector6d a = RandomPose(rng), b = RandomPose(rng);
    ExpectSamePose(Oplus(Ominus(a), a), zero, 1e-12);
    ExpectSamePose(Oplus(a, Ominus(a)), zero, 1e-12);
    ExpectSamePose(Ominus(Oplus(a, b)), Oplus(Ominus(b), Ominus(a)), 1e-11);
    ExpectSamePose(Ominus(Ominus(a)), a, 1e-12);
    const Pose A = Pose::FromVector(a);
    ExpectSamePose((A.Inverse() * A).ToVector(), zero, 1e-12);
    ExpectSamePose(Ominus(A).ToVector(), Ominus(a), 1e-12);
  }
}

TEST(Pose, EulerRoundTrips) {
  std::mt19937 rng(4);
  for (int i = 0; i < 500; ++i) {
    const Vector6d x = RandomPose(rng, 1e-3);
    const Vector6d y = Pose::FromVector(x).ToVector();
    // Away from gimbal lock the angles themselves come back.
    EXPECT_LT(PoseVectorDifference(x, y).norm(), 1e-9) << x.transpose() << "\n" << y.transpose();
    EXPECT_LE(std::abs(y[4]), M_PI / 2);
  }
}

TEST(Pose, EulerNearAndAtGimbalLock) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> a(-M_PI, M_PI);
  for (double pitch : {M_PI / 2, -M_PI / 2, M_PI / 2 - 1e-9, -M_PI / 2 + 1e-7, M_PI / 2 - 1e-5}) {
    for (int i = 0; i < 50; ++i) {
      const double roll = a(rng), yaw = a(rng);
      const Matrix3d R = RotationFromEuler(roll, pitch, yaw);
      const Eigen::Vector3d e = EulerFromRotation<double>(R);
      // The angles may differ (roll and yaw share an axis) but the rotation not.
      EXPECT_LT((RotationFromEuler(e[0], e[1], e[2]) - R).norm(), 1e-9) << "pitch " << pitch;
      EXPECT_TRUE(std::isfinite(e[0]) && std::isfinite(e[2]));
      const Pose P = Pose::FromVector(V(1, 2, 3, roll, pitch, yaw));
      EXPECT_LT((P.rotation() - R).norm(), 1e-12);
    }
  }
  // Composition through gimbal lock stays on SO(3).
  const Pose up = Pose::FromXyzRpy(0, 0, 0, 0.3, M_PI / 2, -0.2);
  EXPECT_NEAR((up * up.Inverse()).rotation().trace(), 3.0, 1e-14);
}

TEST(Pose, WrapAngle) {
  EXPECT_DOUBLE_EQ(WrapAngle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(WrapAngle(-M_PI), M_PI);
  EXPECT_NEAR(WrapAngle(3 * M_PI), M_PI, 1e-15);
  EXPECT_NEAR(WrapAngle(2 * M_PI + 0.1), 0.1, 1e-15);
  EXPECT_NEAR(WrapAngle(-2 * M_PI - 0.1), -0.1, 1e-15);
  const Vector6d d = PoseVectorDifference(V(0, 0, 0, 0, 0, M_PI - 0.1), V(0, 0, 0, 0, 0, -M_PI + 0.1));
  EXPECT_NEAR(d[5], -0.2, 1e-15);
}

TEST(Pose, MatrixPointsAndDistances) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int i = 0; i < 50; ++i) {
    const Pose A = Pose::FromVector(RandomPose(rng)), B = Pose::FromVector(RandomPose(rng));
    const Vector3d p(u(rng), u(rng), u(rng));
    EXPECT_LT(((A * B) * p - A * (B * p)).norm(), 1e-12);
    EXPECT_LT((A.Inverse() * (A * p) - p).norm(), 1e-12);
    const Eigen::Vector4d h = A.Matrix() * p.homogeneous();
    EXPECT_LT((h.head<3>() - A * p).norm(), 1e-12);
    ExpectSamePose(Pose::FromMatrix(A.Matrix()).ToVector(), A.ToVector(), 1e-12);
    EXPECT_LT((A.Rotate(p) - A.rotation() * p).norm(), 1e-12);
  }
  const Pose a = Pose::FromXyzRpy(0, 0, 0, 0, 0, 0.1), b = Pose::FromXyzRpy(3, 4, 0, 0, 0, 0.4);
  EXPECT_NEAR(Pose::AngleBetween(a, b), 0.3, 1e-14);
  EXPECT_DOUBLE_EQ(Pose::DistanceBetween(a, b), 5.0);
  double arr[6] = {1, 2, 3, 0.1, 0.2, 0.3};
  ExpectSamePose(Pose::FromArray(arr).ToVector(), V(1, 2, 3, 0.1, 0.2, 0.3), 1e-15);
}

// Central differences of f at x, with the angle outputs wrapped.
template <typename F>
Matrix6d NumericJacobian(F f, const Vector6d& x) {
  const double h = 1e-6;
  Matrix6d J;
  for (int i = 0; i < 6; ++i) {
    Vector6d xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    J.col(i) = PoseVectorDifference(f(xp), f(xm)) / (2 * h);
  }
  return J;
}

TEST(Pose, OplusJacobiansMatchCentralDifferences) {
  std::mt19937 rng(7);
  for (int i = 0; i < 100; ++i) {
    const Vector6d a = RandomPose(rng, 0.2), b = RandomPose(rng, 0.2);
    if (std::abs(Oplus(a, b)[4]) > M_PI / 2 - 0.1) continue;  // the composition near gimbal lock
    Matrix6d Ja, Jb;
    OplusJacobians(a, b, &Ja, &Jb);
    const Matrix6d Na = NumericJacobian([&](const Vector6d& x) { return Oplus(x, b); }, a);
    const Matrix6d Nb = NumericJacobian([&](const Vector6d& x) { return Oplus(a, x); }, b);
    EXPECT_LT((Ja - Na).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, Na.cwiseAbs().maxCoeff()));
    EXPECT_LT((Jb - Nb).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, Nb.cwiseAbs().maxCoeff()));
    // Either output may be skipped.
    Matrix6d Ja_only;
    OplusJacobians(a, b, &Ja_only, nullptr);
    EXPECT_EQ(Ja_only, Ja);
  }
  // Known: the translation part of d(a (+) b)/db is R_a.
  const Vector6d a = V(1, 2, 3, 0.1, 0.2, 0.3);
  Matrix6d Ja, Jb;
  OplusJacobians(a, V(0.5, -1, 2, 0.2, -0.1, 0.4), &Ja, &Jb);
  EXPECT_LT((Jb.topLeftCorner<3, 3>() - RotationFromEuler(0.1, 0.2, 0.3)).norm(), 1e-14);
  EXPECT_LT((Ja.topLeftCorner<3, 3>() - Matrix3d::Identity()).norm(), 1e-14);
}

TEST(Pose, OminusJacobianMatchesCentralDifferences) {
  std::mt19937 rng(8);
  for (int i = 0; i < 100; ++i) {
    const Vector6d a = RandomPose(rng, 0.2);
    if (std::abs(Ominus(a)[4]) > M_PI / 2 - 0.1) continue;
    const Matrix6d J = OminusJacobian(a);
    const Matrix6d N = NumericJacobian([](const Vector6d& x) { return Ominus(x); }, a);
    EXPECT_LT((J - N).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, N.cwiseAbs().maxCoeff()));
  }
}

}  // namespace
}  // namespace hull
