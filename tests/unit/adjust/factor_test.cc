// Every factor's Jacobian against numerical differentiation (ceres::GradientChecker,
// on the SO(3) x R^3 manifold of the pose blocks), at random states.
#include <ceres/ceres.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <gtest/gtest.h>

#include <random>

#include "adjust/factors/dvl_raycast_factor.h"
#include "adjust/factors/odometry_factor.h"
#include "adjust/factors/pose_prior_factor.h"
#include "adjust/factors/reprojection_factor.h"
#include "adjust/factors/surface_factor.h"
#include "adjust/factors/zpr_factor.h"
#include "geometry/mesh_index.h"
#include "support/test_meshes.h"

namespace hull::adjust {
namespace {

using SE3 = ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>>;

struct Block {
  std::vector<double> v;
  const ceres::Manifold* manifold = nullptr;
};

// Checks the cost function's Jacobians at the given blocks: the analytic
// (autodiff) Jacobian in each block's tangent space against central
// differences of the residual along the manifold, compared as matrices
// (Frobenius norm relative to the Jacobian's size, so near-zero entries do
// not produce meaningless relative errors).
void ExpectGradientsMatch(const ceres::CostFunction* cf, std::vector<Block> blocks, double tolerance = 1e-6) {
  const int nr = cf->num_residuals();
  const std::size_t nb = blocks.size();
  std::vector<const double*> params;
  for (auto& b : blocks) params.push_back(b.v.data());
  std::vector<std::vector<double>> jac(nb);
  std::vector<double*> jac_ptr(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    jac[i].resize(static_cast<std::size_t>(nr) * blocks[i].v.size());
    jac_ptr[i] = jac[i].data();
  }
  std::vector<double> r0(static_cast<std::size_t>(nr));
  ASSERT_TRUE(cf->Evaluate(params.data(), r0.data(), jac_ptr.data()));
  for (std::size_t i = 0; i < nb; ++i) {
    const int amb = static_cast<int>(blocks[i].v.size());
    const int tan = blocks[i].manifold ? blocks[i].manifold->TangentSize() : amb;
    Eigen::MatrixXd plus = Eigen::MatrixXd::Identity(amb, tan);
    if (blocks[i].manifold) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> pj(amb, tan);
      blocks[i].manifold->PlusJacobian(blocks[i].v.data(), pj.data());
      plus = pj;
    }
    const Eigen::MatrixXd J =
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jac[i].data(), nr, amb) *
        plus;
    Eigen::MatrixXd N(nr, tan);
    const double h = 1e-6;
    for (int k = 0; k < tan; ++k) {
      std::vector<double> delta(static_cast<std::size_t>(tan), 0.0), xp(static_cast<std::size_t>(amb)),
          xm(static_cast<std::size_t>(amb));
      std::vector<double> rp(static_cast<std::size_t>(nr)), rm(static_cast<std::size_t>(nr));
      delta[static_cast<std::size_t>(k)] = h;
      auto step = [&](std::vector<double>& out) {
        if (blocks[i].manifold) {
          blocks[i].manifold->Plus(blocks[i].v.data(), delta.data(), out.data());
        } else {
          for (int a = 0; a < amb; ++a)
            out[static_cast<std::size_t>(a)] =
                blocks[i].v[static_cast<std::size_t>(a)] + delta[static_cast<std::size_t>(a)];
        }
      };
      step(xp);
      delta[static_cast<std::size_t>(k)] = -h;
      step(xm);
      std::vector<const double*> pp = params, pm = params;
      pp[i] = xp.data();
      pm[i] = xm.data();
      ASSERT_TRUE(cf->Evaluate(pp.data(), rp.data(), nullptr));
      ASSERT_TRUE(cf->Evaluate(pm.data(), rm.data(), nullptr));
      for (int r = 0; r < nr; ++r)
        N(r, k) = (rp[static_cast<std::size_t>(r)] - rm[static_cast<std::size_t>(r)]) / (2 * h);
    }
    const double err = (J - N).norm();
    EXPECT_LE(err, tolerance * std::max(1.0, J.norm())) << "block " << i << "\nanalytic\n" << J << "\nnumeric\n" << N;
  }
}

std::vector<double> PoseBlock(const Pose& p) {
  std::vector<double> b(kPoseSize);
  PoseToBlock(p, b.data());
  return b;
}

Pose RandomPose(std::mt19937& rng, double t_scale, double angle) {
  std::normal_distribution<double> n(0, 1);
  Vector6d x;
  x << t_scale * n(rng), t_scale * n(rng), t_scale * n(rng), angle * n(rng), angle * n(rng), angle * n(rng);
  return Pose::FromVector(x);
}

class Factors : public ::testing::Test {
 protected:
  std::mt19937 rng{42};
  SE3 se3;
};

TEST_F(Factors, PosePriorAndGauge) {
  for (int i = 0; i < 10; ++i) {
    const Pose prior = RandomPose(rng, 5, 1.0), x = prior * RandomPose(rng, 0.3, 0.1);
    std::unique_ptr<ceres::CostFunction> cf(
        PosePriorFactor::Create(prior, (Vector6d() << 1, 2, 3, 0.1, 0.2, 0.3).finished()));
    ExpectGradientsMatch(cf.get(), {{PoseBlock(x), &se3}});
    std::unique_ptr<ceres::CostFunction> g(GaugePriorFactor::Create(prior.ToVector(), 1e-3, 1e-4));
    ExpectGradientsMatch(g.get(), {{PoseBlock(x), &se3}}, 1e-5);
  }
}

TEST_F(Factors, ZprAndServo) {
  for (int i = 0; i < 10; ++i) {
    const Pose x = RandomPose(rng, 5, 0.3);
    std::unique_ptr<ceres::CostFunction> cf(ZprFactor::Create(10.0, 0.01, -0.02, 0.1, 0.0017));
    ExpectGradientsMatch(cf.get(), {{PoseBlock(x), &se3}});
  }
  std::unique_ptr<ceres::CostFunction> s(ServoPriorFactor::Create(1.5, 0.0873));
  ExpectGradientsMatch(s.get(), {{{1.52}, nullptr}});
}

TEST_F(Factors, Odometry) {
  for (int i = 0; i < 10; ++i) {
    const Pose a = RandomPose(rng, 5, 0.5), b = a * RandomPose(rng, 0.5, 0.05);
    const Vector6d z = (a.Inverse() * b * RandomPose(rng, 0.01, 0.002)).ToVector();
    std::unique_ptr<ceres::CostFunction> cf(
        OdometryFactor::Create(z, (Vector6d() << 0.006, 0.006, 0.006, 5e-4, 5e-4, 5e-4).finished()));
    ExpectGradientsMatch(cf.get(), {{PoseBlock(a), &se3}, {PoseBlock(b), &se3}}, 1e-5);
  }
}

TEST_F(Factors, StereoAndMonoReprojection) {
  SurveyManifest man;
  CameraModel cam;
  cam.mount = Pose::FromVector(man.servo_mount);
  cam.top_to_bottom = Pose::FromVector(man.camera.top_to_bottom);
  cam.top = man.camera.top;
  cam.bottom = man.camera.bottom;
  const Pose ext = Pose::FromVector(man.camera.servo_to_top);
  for (int i = 0; i < 10; ++i) {
    const Pose v = RandomPose(rng, 3, 0.05);
    const double theta = M_PI / 2 + 0.05 * i;
    const Pose g_c = v * man.VehicleToServo(theta) * ext;
    const Eigen::Vector3d l = g_c * Eigen::Vector3d(0.2 * i - 1, 0.1 * i - 0.4, 1.5);
    const Eigen::Vector2d top(600, 500), bottom(610, 420);
    std::unique_ptr<ceres::CostFunction> st(StereoReprojectionFactor::Create(&cam, top, bottom, 2.0));
    ExpectGradientsMatch(
        st.get(), {{PoseBlock(v), &se3}, {{theta}, nullptr}, {PoseBlock(ext), &se3}, {{l.x(), l.y(), l.z()}, nullptr}},
        1e-5);
    std::unique_ptr<ceres::CostFunction> mo(MonoReprojectionFactor::Create(&cam, top, 2.0));
    ExpectGradientsMatch(
        mo.get(), {{PoseBlock(v), &se3}, {{theta}, nullptr}, {PoseBlock(ext), &se3}, {{l.x(), l.y(), l.z()}, nullptr}},
        1e-5);
  }
}

TEST_F(Factors, ReprojectionOfTheTruthIsZero) {
  SurveyManifest man;
  CameraModel cam;
  cam.mount = Pose::FromVector(man.servo_mount);
  cam.top_to_bottom = Pose::FromVector(man.camera.top_to_bottom);
  cam.top = man.camera.top;
  cam.bottom = man.camera.bottom;
  const Pose ext = Pose::FromVector(man.camera.servo_to_top), v = RandomPose(rng, 3, 0.1);
  const double theta = 1.4;
  const Pose g_c = v * man.VehicleToServo(theta) * ext;
  const Eigen::Vector3d l = g_c * Eigen::Vector3d(0.3, -0.2, 1.7);
  const Eigen::Vector2d top = cam.top.Project(g_c.Inverse() * l);
  const Eigen::Vector2d bottom = cam.bottom.Project((g_c * cam.top_to_bottom).Inverse() * l);
  std::unique_ptr<ceres::CostFunction> st(StereoReprojectionFactor::Create(&cam, top, bottom, 2.0));
  auto pv = PoseBlock(v), pe = PoseBlock(ext);
  double th = theta, lm[3] = {l.x(), l.y(), l.z()}, r[4];
  const double* params[4] = {pv.data(), &th, pe.data(), lm};
  ASSERT_TRUE(st->Evaluate(params, r, nullptr));
  for (double x : r) EXPECT_NEAR(x, 0.0, 1e-9);
}

TEST_F(Factors, DvlRaycastAgainstAPlane) {
  // A large slab whose bottom face is the plane z = 0 (in M), seen from below.
  const TriangleMesh slab = test::MakeBox({-50, -50, 0}, {50, 50, 5});
  const MeshIndex index(slab);
  SurveyManifest man;
  DvlModel m;
  m.mesh = &index;
  m.mount = Pose::FromVector(man.servo_mount);
  m.servo_to_dvl = Pose::FromVector(man.servo_to_dvl);
  m.model_offset = Pose::FromXyzRpy(0.5, -0.3, 0.1, 0, 0, 0);
  for (int i = 0; i < 8; ++i) {
    // Vehicle 1.5 m below the plane in g (z down), model placed upside down (roll pi).
    const Pose x_gC = Pose::FromXyzRpy(0.1 * i, -0.2, -0.1, M_PI + 0.01 * i, 0.02, 0.3);
    const Pose v = Pose::FromXyzRpy(0.3 * i, 0.2, 1.5, 0.02, -0.01, 0.1 * i);
    const double theta = M_PI / 2 - 0.03 * i;
    const Eigen::Vector3d beam = man.BeamDirection(i % 4);
    auto pv = PoseBlock(v), pm = PoseBlock(x_gC);
    int face = -1;
    const double r = DvlRaycastFactor::PredictRange(m, pv.data(), &theta, pm.data(), beam, &face);
    ASSERT_GE(face, 0);
    std::unique_ptr<ceres::CostFunction> cf(DvlRaycastFactor::Create(&m, beam, r + 0.004, 0.003));
    ExpectGradientsMatch(cf.get(), {{pv, &se3}, {{theta}, nullptr}, {pm, &se3}}, 1e-5);
    double res = 0, th = theta;
    const double* params[3] = {pv.data(), &th, pm.data()};
    ASSERT_TRUE(cf->Evaluate(params, &res, nullptr));
    EXPECT_NEAR(res, -0.004 / 0.003, 1e-7);  // (predicted - measured) / sigma
  }
}

TEST_F(Factors, SurfaceConstraintBothModels) {
  const TriangleMesh sphere = test::MakeIcosphere(5.0, 3);
  const MeshIndex index(sphere);
  const Pose offset = Pose::FromXyzRpy(0.2, 0.1, -0.3, 0, 0, 0);
  for (SurfaceModel model : {SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture}) {
    for (int i = 0; i < 10; ++i) {
      const Pose x_gC = RandomPose(rng, 2, 0.3);
      // A point near the middle of a face, at a height h off it (in M).
      const int f = 37 * i + 11;
      const Eigen::Vector3d c = sphere.FaceCentroid(f);
      const double h = (i % 2 ? 0.01 : 0.2) * (i % 3 ? 1 : -1);
      const Eigen::Vector3d lM = c + h * sphere.face_normals[static_cast<std::size_t>(f)];
      const Eigen::Vector3d l = (x_gC * offset) * lM;
      std::unique_ptr<ceres::CostFunction> cf(
          SurfaceFactor::Create(&index, &offset, SurfaceLookup::kClosestFace, model, 1.0, 0.02));
      ExpectGradientsMatch(cf.get(), {{PoseBlock(x_gC), &se3}, {{l.x(), l.y(), l.z()}, nullptr}}, 1e-5);
      auto pm = PoseBlock(x_gC);
      double lm[3] = {l.x(), l.y(), l.z()}, r[2];
      const double* params[2] = {pm.data(), lm};
      ASSERT_TRUE(cf->Evaluate(params, r, nullptr));
      const bool on = model == SurfaceModel::kAllOnSurface || std::abs(h) < 0.05595;
      EXPECT_NEAR(r[0], h / (on ? 0.02 : 1.0), 1e-7);
      EXPECT_NEAR(r[1], on ? 0.0 : std::sqrt(2 * std::log(50.0)), 1e-12);
    }
  }
}

TEST_F(Factors, SurfaceDeviationIsContinuousAroundEdges) {
  // A point circling a box's edge at 3 cm: h stays 3 cm (eq. 5 with one
  // face's plane would jump where the closest face changes).
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 1, 1});
  const MeshIndex index(box);
  double prev = std::nan("");
  for (int k = 0; k <= 90; ++k) {
    const double a = (-10 + 1.2 * k) * M_PI / 180.0;  // from under the top face over the edge to beside the side face
    const Eigen::Vector3d q(1 + 0.03 * std::sin(a), 0.5, 1 + 0.03 * std::cos(a));
    const double h = SurfaceDeviation(index, Pose(), q, SurfaceLookup::kClosestFace);
    if (q.x() > 1 && q.z() > 1) {
      EXPECT_NEAR(h, 0.03, 1e-9);
    }
    if (!std::isnan(prev)) {
      EXPECT_LT(std::abs(h - prev), 2e-3);
    }
    prev = h;
  }
  // Inside, near the edge: negative.
  EXPECT_LT(SurfaceDeviation(index, Pose(), {0.99, 0.5, 0.98}, SurfaceLookup::kClosestFace), 0.0);
}

}  // namespace
}  // namespace hull::adjust
