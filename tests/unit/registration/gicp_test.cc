// GICP: the real scans in ../shared/data (the 1 cm / 0.1 deg), a
// cloud made in code with a known transform, options and edge cases.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "base/error.h"
#include "geometry/mesh_io.h"
#include "registration/gicp.h"

namespace hull {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

struct RealScans {
  std::vector<Eigen::Vector3d> source, target;
  Pose truth;  // x_target_source
};

// Empty when ../shared/data is absent.
std::optional<RealScans> LoadRealScans() {
  namespace fs = std::filesystem;
  const fs::path dir = HI_SHARED_DATA_DIR;
  const fs::path src = dir / "gicp-source.ply", tgt = dir / "gicp-target.ply", tf = dir / "gicp-T_target_source.txt";
  if (!fs::exists(src) || !fs::exists(tgt) || !fs::exists(tf)) return std::nullopt;
  RealScans s;
  s.source = LoadPointCloud(src.string());
  s.target = LoadPointCloud(tgt.string());
  std::ifstream in(tf);
  Eigen::Matrix4d T;
  for (int i = 0; i < 16; ++i) in >> T(i / 4, i % 4);
  if (!in) return std::nullopt;
  s.truth = Pose::FromMatrix(T);
  return s;
}

const std::optional<RealScans>& Scans() {
  static const std::optional<RealScans> scans = LoadRealScans();
  return scans;
}

void ExpectRecovered(const GicpResult& r, const Pose& truth, const char* what) {
  const double dt = Pose::DistanceBetween(r.transform, truth);
  const double dr = Pose::AngleBetween(r.transform, truth) * kRadToDeg;
  std::printf("[ measured ] %s: error %.3f cm, %.4f deg; %s after %d iterations, fitness %.4f m, %zu/%zu paired\n",
              what, 100 * dt, dr, GicpStatusName(r.status), r.iterations, r.fitness, r.correspondences,
              r.source_points);
  EXPECT_TRUE(r.converged) << GicpStatusName(r.status);
  EXPECT_LT(dt, 0.01);
  EXPECT_LT(dr, 0.1);
}

TEST(GicpRealScans, RecoversTheTransformFromTheScansOwnFrames) {
  if (!Scans()) GTEST_SKIP() << "no gicp-*.ply / gicp-T_target_source.txt in " << HI_SHARED_DATA_DIR;
  const RealScans& s = *Scans();
  ASSERT_GT(s.source.size(), 10000u);
  ASSERT_GT(s.target.size(), 10000u);
  // The scans start 0.5 m and 0.7 deg apart.
  ExpectRecovered(AlignGicp(s.source, s.target, Pose::Identity()), s.truth, "real scans from identity");
}

TEST(GicpRealScans, RecoversTheTransformFromAWorseStart) {
  if (!Scans()) GTEST_SKIP() << "no gicp-*.ply / gicp-T_target_source.txt in " << HI_SHARED_DATA_DIR;
  const RealScans& s = *Scans();
  // 0.36 m and 2.3 deg from the truth: without the coarse stage PCL's GICP
  // stops 0.9 deg away (a local minimum of these scans).
  const Pose start = s.truth * Pose::FromXyzRpy(0.27, -0.20, 0.13, 0.028, 0.028, 0.002);
  ExpectRecovered(AlignGicp(s.source, s.target, start), s.truth, "real scans from 2.3 deg off");
}

// Points on three walls of a room corner with a ball in it: every direction
// of a rigid motion is observable.
std::vector<Eigen::Vector3d> CornerWithBall(const Eigen::Vector3d& offset) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 6000; ++i) {
    const double a = 6 * u(rng), b = 4 * u(rng);
    switch (i % 4) {
      case 0:
        pts.emplace_back(a, b, 0.0);  // floor
        break;
      case 1:
        pts.emplace_back(a, 0.0, 0.75 * b);  // wall
        break;
      case 2:
        pts.emplace_back(0.0, b, 0.75 * a / 2);  // wall
        break;
      default: {
        const double th = M_PI * u(rng), ph = 2 * M_PI * u(rng);
        pts.emplace_back(Eigen::Vector3d(3, 2, 0.8) +
                         0.8 * Eigen::Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
      }
    }
  }
  for (auto& p : pts) p += offset;
  return pts;
}

TEST(Gicp, RecoversAKnownTransformFarFromTheOrigin) {
  // Far from the origin: PCL computes covariances in float, so AlignGicp
  // must centre the clouds.
  const Eigen::Vector3d far(5000, -3000, 20);
  const std::vector<Eigen::Vector3d> target = CornerWithBall(far);
  // x_target_source: 0.15 m and 2.8 deg about a point of the corner.
  const Pose about(Eigen::Quaterniond::Identity(), far + Eigen::Vector3d(2, 1, 0.5));
  const Pose truth = about * Pose::FromXyzRpy(0.12, -0.08, 0.05, 0.02, -0.015, 0.04) * about.Inverse();
  std::vector<Eigen::Vector3d> source;
  const Pose x_st = truth.Inverse();
  for (const auto& p : target) source.push_back(x_st * p);
  GicpOptions o;
  o.voxel_size = 0;  // the clouds are the same points: exact pairs at the truth
  o.coarse_voxel_size = 0.2;
  o.max_correspondence_distance = 0.5;
  const GicpResult r = AlignGicp(source, target, Pose::Identity(), o);
  EXPECT_TRUE(r.converged) << GicpStatusName(r.status);
  EXPECT_LT(Pose::DistanceBetween(r.transform, truth), 1e-3);
  EXPECT_LT(Pose::AngleBetween(r.transform, truth) * kRadToDeg, 0.01);
  EXPECT_LT(r.fitness, 1e-3);
  EXPECT_GT(r.correspondences, r.source_points * 9 / 10);
}

TEST(Gicp, TooFewPointsIsAStatusNotACrash) {
  const std::vector<Eigen::Vector3d> few = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  GicpOptions o;
  o.coarse_voxel_size = 0;
  o.voxel_size = 0;
  const Pose start = Pose::FromXyzRpy(1, 2, 3, 0, 0, 0.5);
  const GicpResult r = AlignGicp(few, CornerWithBall(Eigen::Vector3d::Zero()), start, o);
  EXPECT_EQ(r.status, GicpStatus::kTooFewPoints);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(Pose::DistanceBetween(r.transform, start), 1e-12);
}

TEST(Gicp, OptionsCheckNamesTheField) {
  EXPECT_NO_THROW(GicpOptions{}.Check());
  auto field_of = [](const GicpOptions& o) -> std::string {
    try {
      o.Check();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  GicpOptions o;
  o.voxel_size = -1;
  EXPECT_EQ(field_of(o), "voxel_size");
  o = {};
  o.max_correspondence_distance = 0;
  EXPECT_EQ(field_of(o), "max_correspondence_distance");
  o = {};
  o.coarse_voxel_size = o.voxel_size;  // not coarser
  EXPECT_EQ(field_of(o), "coarse_voxel_size");
  o = {};
  o.coarse_max_correspondence_distance = -1;
  EXPECT_EQ(field_of(o), "coarse_max_correspondence_distance");
  o.coarse_voxel_size = 0;  // no coarse stage: its reach is not used
  EXPECT_EQ(field_of(o), "");
  o = {};
  o.max_iterations = 0;
  EXPECT_EQ(field_of(o), "max_iterations");
  o = {};
  o.transformation_epsilon = 0;
  EXPECT_EQ(field_of(o), "transformation_epsilon");
  o = {};
  o.rotation_epsilon = -1;
  EXPECT_EQ(field_of(o), "rotation_epsilon");
  o = {};
  o.correspondence_randomness = 2;
  EXPECT_EQ(field_of(o), "correspondence_randomness");
  o = {};
  o.max_optimizer_iterations = 0;
  EXPECT_EQ(field_of(o), "max_optimizer_iterations");
  o = {};
  o.translation_gradient_tolerance = 0;
  EXPECT_EQ(field_of(o), "translation_gradient_tolerance");
  o = {};
  o.rotation_gradient_tolerance = 0;
  EXPECT_EQ(field_of(o), "rotation_gradient_tolerance");
  o = {};
  o.voxel_size = std::nan("");
  EXPECT_THROW(AlignGicp({}, {}, Pose::Identity(), o), OptionError);
}

TEST(Gicp, VoxelDownsampleKeepsOneCentroidPerVoxel) {
  const std::vector<Eigen::Vector3d> pts = {
      {0.1, 0.1, 0.1}, {0.3, 0.1, 0.1}, {1.2, 0.1, 0.1}, {1.4, 0.5, 0.3}, {-0.1, 0, 0}};
  const auto v = VoxelDownsample(pts, 1.0);
  ASSERT_EQ(v.size(), 3u);  // voxels (0,0,0), (1,0,0), (-1,0,0), in the order met
  EXPECT_LT((v[0] - Eigen::Vector3d(0.2, 0.1, 0.1)).norm(), 1e-12);
  EXPECT_LT((v[1] - Eigen::Vector3d(1.3, 0.3, 0.2)).norm(), 1e-12);
  EXPECT_LT((v[2] - Eigen::Vector3d(-0.1, 0, 0)).norm(), 1e-12);
  EXPECT_EQ(VoxelDownsample(pts, 0.0).size(), pts.size());
}

}  // namespace
}  // namespace hull
