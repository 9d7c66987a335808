// DVL returns in g: the beam geometry by hand, against the simulator's truth,
// and the depth/IMU correction of the initial poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "registration/dvl_points.h"
#include "simulate/survey_simulator.h"

namespace hull {
namespace {

// 4x4 homogeneous matrix of [x, y, z, roll, pitch, yaw] written out from the
// contract (R = Rz(yaw) Ry(pitch) Rx(roll)), independent of Pose.
Eigen::Matrix4d H(double x, double y, double z, double roll, double pitch, double yaw) {
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Rz * Ry * Rx;
  T.topRightCorner<3, 1>() = Eigen::Vector3d(x, y, z);
  return T;
}

SurveyBundle OneKeyframeBundle() {
  SurveyBundle b;
  b.manifest.servo_mount << 0.4, 0.05, 0.2, 0.01, -0.02, 0.03;
  b.manifest.servo_to_dvl << 0.22, 0.12, 0.05, M_PI / 2, 0, M_PI / 2;
  // Deliberately not unit length: readers normalise the beams.
  b.manifest.beams = {Eigen::Vector3d(1, 0, 2), Eigen::Vector3d(-0.5, 0, 0.866), Eigen::Vector3d(0, 0.5, 0.866),
                      Eigen::Vector3d(0, -3, 5)};
  NavRecord n;
  n.keyframe = 7;
  n.t = 0;
  n.x_gv << 3.0, -2.0, 5.5, 0.05, -0.03, 1.2;
  n.servo = 0.9;
  b.nav.push_back(n);
  DvlRecord d;
  d.keyframe = 7;
  d.range = {1.5, kNoReturn, 2.25, 0.8};
  b.dvl.push_back(d);
  return b;
}

TEST(DvlPoints, BeamGeometryMatchesTheContractByHand) {
  const SurveyBundle b = OneKeyframeBundle();
  const auto pts = DvlPointsFromInitialNav(b);
  ASSERT_EQ(pts.size(), 3u);  // beam 2 has no return
  const Vector6d& v = b.nav[0].x_gv;
  const Vector6d& m = b.manifest.servo_mount;
  const Vector6d& d = b.manifest.servo_to_dvl;
  const Eigen::Matrix4d T_gd = H(v[0], v[1], v[2], v[3], v[4], v[5]) * H(m[0], m[1], m[2], m[3], m[4], m[5]) *
                               H(0, 0, 0, 0, b.nav[0].servo, 0) * H(d[0], d[1], d[2], d[3], d[4], d[5]);
  const int beams[3] = {0, 2, 3};
  for (int k = 0; k < 3; ++k) {
    const int bm = beams[k];
    const Eigen::Vector3d dir_d = b.manifest.beams[static_cast<std::size_t>(bm)].normalized();
    const Eigen::Vector3d origin = T_gd.topRightCorner<3, 1>();
    const Eigen::Vector3d dir = T_gd.topLeftCorner<3, 3>() * dir_d;
    const double r = b.dvl[0].range[static_cast<std::size_t>(bm)];
    EXPECT_EQ(pts[static_cast<std::size_t>(k)].beam, bm);
    EXPECT_EQ(pts[static_cast<std::size_t>(k)].keyframe, 7);
    EXPECT_EQ(pts[static_cast<std::size_t>(k)].nav_index, 0);
    EXPECT_DOUBLE_EQ(pts[static_cast<std::size_t>(k)].range, r);
    EXPECT_LT((pts[static_cast<std::size_t>(k)].origin - origin).norm(), 1e-12);
    EXPECT_LT((pts[static_cast<std::size_t>(k)].direction - dir).norm(), 1e-12);
    EXPECT_NEAR(pts[static_cast<std::size_t>(k)].direction.norm(), 1.0, 1e-12);
    EXPECT_LT((pts[static_cast<std::size_t>(k)].point - (origin + r * dir)).norm(), 1e-12);
  }
  EXPECT_EQ(PointsOf(pts).size(), 3u);
}

TEST(DvlPoints, RejectsUnknownKeyframesAndMismatchedPoses) {
  SurveyBundle b = OneKeyframeBundle();
  EXPECT_THROW(DvlPointsInG(b, {}, {}), std::invalid_argument);
  b.dvl[0].keyframe = 8;
  try {
    DvlPointsFromInitialNav(b);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "dvl.csv");
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().field, "keyframe");
  }
}

// The simulator casts its beams with its own code: the returns placed by
// the true poses and servo angles must land on the true surface.
TEST(DvlPoints, ReturnsFromTruePosesLieOnTheSimulatedHull) {
  NullProgress np;
  const SimulatedSurvey s = SimulateSurvey(SurveyPreset("demo"), np);
  const SurveyBundle& b = s.bundle;
  ASSERT_TRUE(b.truth);
  std::vector<Pose> x_gv;
  std::vector<double> servo;
  for (const TruePose& p : b.truth->poses) {
    x_gv.push_back(Pose::FromVector(p.x_gv));
    servo.push_back(p.servo);
  }
  ASSERT_EQ(x_gv.size(), b.nav.size());
  const auto pts = DvlPointsInG(b, x_gv, servo);
  ASSERT_GT(pts.size(), 1000u);
  const MeshIndex cad(s.cad);
  const Pose x_Mg = Pose::FromVector(b.truth->x_gM).Inverse();
  std::vector<double> d;
  for (const DvlPoint& p : pts) d.push_back(cad.Closest(x_Mg * p.point).distance);
  std::sort(d.begin(), d.end());
  // Range noise is 3 mm; returns on the foreign objects sit up to 0.15 m off the CAD.
  EXPECT_LT(d[d.size() / 2], 0.005);
  EXPECT_LT(d[d.size() * 9 / 10], 0.02);
}

TEST(DvlPoints, DepthAndImuCorrectionOfTheInitialPoses) {
  SurveyBundle b;
  for (int i = 0; i < 50; ++i) {
    NavRecord n;
    n.keyframe = i;
    n.t = i;
    n.x_gv << i * 0.3, 0.1 * i, 4.0 + 0.01 * i, 0.02, -0.01, 0.5;
    n.depth = n.x_gv[2] + 0.5;  // dead reckoning 0.5 m too shallow throughout
    n.roll_meas = 0.001 * i;
    n.pitch_meas = -0.002 * i;
    b.nav.push_back(n);
  }
  const auto same = InitialPosesWithZpr(b, 0.0, false);
  const auto corrected = InitialPosesWithZpr(b, 10.0, true);
  ASSERT_EQ(corrected.size(), b.nav.size());
  for (std::size_t i = 0; i < b.nav.size(); ++i) {
    const Vector6d v0 = same[i].ToVector(), v1 = corrected[i].ToVector();
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(v0[k], b.nav[i].x_gv[k], 1e-12);
    EXPECT_NEAR(v1[0], b.nav[i].x_gv[0], 1e-12);
    EXPECT_NEAR(v1[1], b.nav[i].x_gv[1], 1e-12);
    EXPECT_NEAR(v1[2], b.nav[i].x_gv[2] + 0.5, 1e-12);
    EXPECT_NEAR(v1[3], b.nav[i].roll_meas, 1e-12);
    EXPECT_NEAR(v1[4], b.nav[i].pitch_meas, 1e-12);
    EXPECT_NEAR(v1[5], b.nav[i].x_gv[5], 1e-12);
  }
}

// On the demo survey the corrected depths are closer to the truth than dead
// reckoning (which drifts by decimetres).
TEST(DvlPoints, DepthCorrectionReducesTheDemoDepthError) {
  NullProgress np;
  const SimulatedSurvey s = SimulateSurvey(SurveyPreset("demo"), np);
  const auto corrected = InitialPosesWithZpr(s.bundle, 60.0, true);
  double e_dr = 0, e_c = 0;
  for (std::size_t i = 0; i < s.bundle.nav.size(); ++i) {
    const double z = s.bundle.truth->poses[i].x_gv[2];
    e_dr += std::pow(s.bundle.nav[i].x_gv[2] - z, 2);
    e_c += std::pow(corrected[i].translation().z() - z, 2);
  }
  e_dr = std::sqrt(e_dr / static_cast<double>(s.bundle.nav.size()));
  e_c = std::sqrt(e_c / static_cast<double>(s.bundle.nav.size()));
  std::printf("[ measured ] depth RMS error: dead reckoning %.4f m, corrected %.4f m\n", e_dr, e_c);
  EXPECT_LT(e_c, e_dr);
  EXPECT_LT(e_c, 0.05);
}

}  // namespace
}  // namespace hull
