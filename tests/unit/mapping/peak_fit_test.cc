// The peak fit (peak_fit.h; issue 12, part 1) on planted lumps with known
// apexes: a flat 4 m x 4 m patch of hull bottom (outward normal down) seen
// from below by a 3 x 3 lattice of cameras at 1.5 m, as in fusion_test.cc.
// A Gaussian lump sampled sparsely (no feature within 4.5 cm of its top, so
// the highest feature stands more than 1 cm below the apex) must come out
// within a few millimetres of its apex with the fit and not without it; a
// flat-topped cylinder must not be raised; and one wrong feature above a
// lump must not raise the fitted apex.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "geometry/mesh_index.h"
#include "keyframe_grid.h"
#include "mapping/mapper.h"
#include "mapping/peak_fit.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

const Eigen::Vector2d kCentre(2.0, 2.0);
constexpr double kApex = 0.12, kSigma = 0.10;  // the Gaussian lump: height, standard deviation (m)

double Gaussian(double x, double y) {
  return kApex * std::exp(-(Eigen::Vector2d(x, y) - kCentre).squaredNorm() / (2 * kSigma * kSigma));
}

TriangleMesh FlatBottom() {
  TriangleMesh m = test::MakeGrid(20, 20, 0.2);
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  m.ComputeNormals();
  return m;
}

// Features at 300 per m^2 over the lump's square and 60 per m^2 on the rest
// of the patch, at the height `h`, with Gaussian noise; with hole > 0 none
// within hole of the lump's centre and two rings of 6 and 9 features at hole
// and hole + 2.5 cm (the random ones keep 2 cm beyond); `extra` (x, y,
// deviation) added as given; then the cameras and what each observed.
MappingInput MakeInput(const std::function<double(double, double)>& h, double hole, double noise,
                       const std::vector<Eigen::Vector3d>& extra = {}) {
  MappingInput in;
  in.source = "test scene";
  in.x_gM = Pose();
  in.model_axes = ModelAxes{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  auto add = [&](double x, double y, double d) {
    in.landmarks.push_back({static_cast<std::int64_t>(in.landmarks.size()), Eigen::Vector3d(x, y, -d), d});
  };
  for (int i = 0; i < 60 * 16; ++i) {
    const double x = 4 * u(rng), y = 4 * u(rng);
    if ((Eigen::Vector2d(x, y) - kCentre).cwiseAbs().maxCoeff() < 0.3) continue;
    add(x, y, h(x, y) + noise * g(rng));
  }
  for (int i = 0; i < 300 * 0.36; ++i) {
    const double x = kCentre.x() - 0.3 + 0.6 * u(rng), y = kCentre.y() - 0.3 + 0.6 * u(rng);
    if ((Eigen::Vector2d(x, y) - kCentre).norm() < hole + 0.045) continue;
    add(x, y, h(x, y) + noise * g(rng));
  }
  // Around the hole, two rings of features (the first 4.5 cm from the top:
  // 1.1 cm below it on the Gaussian lump).
  if (hole > 0) {
    for (const auto& [r, n] : {std::pair<double, int>{hole, 6}, {hole + 0.025, 9}}) {
      for (int k = 0; k < n; ++k) {
        const double a = 2 * M_PI * (k + 0.3 * r / hole) / n;
        const double x = kCentre.x() + r * std::cos(a), y = kCentre.y() + r * std::sin(a);
        add(x, y, h(x, y) + noise * g(rng));
      }
    }
  }
  for (const auto& e : extra) add(e.x(), e.y(), e.z());
  AddKeyframeGrid(in, 10, Eigen::Vector2d(1.5, 1.6), Eigen::Vector2d(0.5, 0.4));
  return in;
}

// The fused model's highest deviation within 0.3 m of the lump's centre.
double ModelMax(const MappingResult& r) {
  const std::vector<double>& d = *r.model.FindScalar("deviation");
  double best = -1;
  for (std::size_t v = 0; v < d.size(); ++v) {
    if ((r.model.vertices[v].head<2>() - kCentre).norm() < 0.3) best = std::max(best, d[v]);
  }
  return best;
}

double HighestFeature(const MappingInput& in) {
  double best = -1;
  for (const auto& l : in.landmarks) best = std::max(best, l.deviation);
  return best;
}

TEST(PeakFit, QuadricApexOfAKnownParaboloid) {
  // h = 0.1 - 8 ((u - 0.01)^2 + (v + 0.02)^2) sampled around its apex: the
  // isotropic and the full quadric both find it exactly.
  std::vector<Eigen::Vector3d> uvh;
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) {
      const double u = 0.015 * i, v = 0.015 * j;
      uvh.emplace_back(u, v, 0.1 - 8 * ((u - 0.01) * (u - 0.01) + (v + 0.02) * (v + 0.02)));
    }
  }
  for (const bool isotropic : {true, false}) {
    Eigen::Vector2d a;
    double h = 0, rms = 1;
    std::string why;
    ASSERT_TRUE(FitQuadricApex(uvh, isotropic, &a, &h, &rms, &why)) << why;
    EXPECT_NEAR(h, 0.1, 1e-9);
    EXPECT_NEAR(a.x(), 0.01, 1e-9);
    EXPECT_NEAR(a.y(), -0.02, 1e-9);
    EXPECT_LT(rms, 1e-9);
  }
  // A bowl is not concave; an apex beyond the samples is refused.
  std::vector<Eigen::Vector3d> bowl = uvh, beyond;
  for (auto& p : bowl) p.z() = -p.z();
  for (int i = 0; i < 5; ++i) {
    for (int j = -2; j <= 2; ++j) {
      const double u = 0.03 + 0.015 * i, v = 0.015 * j;
      beyond.emplace_back(u, v, 0.1 - 8 * ((u - 0.01) * (u - 0.01) + (v + 0.02) * (v + 0.02)));
    }
  }
  Eigen::Vector2d a;
  double h = 0, rms = 0;
  std::string why;
  EXPECT_FALSE(FitQuadricApex(bowl, true, &a, &h, &rms, &why));
  EXPECT_EQ(why, "not concave");
  EXPECT_FALSE(FitQuadricApex(beyond, true, &a, &h, &rms, &why));
  EXPECT_EQ(why, "apex outside the features");
}

TEST(PeakFit, SparselySampledGaussianLumpReachesItsApex) {
  const MappingInput in = MakeInput(Gaussian, 0.045, 0.001);
  const double top = HighestFeature(in);
  ASSERT_LT(top, kApex - 0.01);  // the features miss the top centimetre
  MappingOptions o;
  NullProgress p;
  Mapper mapper(in, FlatBottom());
  o.peak_fit = false;
  const double without = ModelMax(mapper.Run(o, p));
  o.peak_fit = true;
  const MappingResult with = mapper.Run(o, p);
  const double fitted = ModelMax(with);
  EXPECT_LT(without, kApex - 0.01) << "the fusion alone stops at the features";
  EXPECT_NEAR(fitted, kApex, 0.005) << "highest feature " << top << ", without the fit " << without;
  EXPECT_LE(fitted, kApex + 0.002);
  EXPECT_EQ(with.summary.peaks_placed, 1u);
  for (const FittedPeak& f : with.peaks) {
    std::printf("peak: top %.4f apex %.4f (all %.4f) rise %.4f features %d rms %.4f %s%s\n", f.top, f.height,
                f.full_height, f.rise, f.features, f.rms, f.reason.c_str(), f.placement.c_str());
  }
}

TEST(PeakFit, FlatToppedCylinderIsNotRaised) {
  constexpr double kHeight = 0.10, kRadius = 0.15;
  auto cylinder = [](double x, double y) {
    return (Eigen::Vector2d(x, y) - kCentre).norm() <= kRadius ? kHeight : 0.0;
  };
  const MappingInput in = MakeInput(cylinder, 0.0, 0.002);
  MappingOptions o;
  o.peak_fit = true;
  NullProgress p;
  const MappingResult r = Mapper(in, FlatBottom()).Run(o, p);
  EXPECT_LE(ModelMax(r), std::max(kHeight, HighestFeature(in)) + 0.001);
}

TEST(PeakFit, OneWrongFeatureCannotRaiseTheApex) {
  // The sparsely sampled lump, and the same with one wrong feature 1.2 cm
  // above the surface 5 cm from the apex: the plain fit over every feature
  // rises, the apex taken (the lowest leave-one-out fit) does not.
  const MappingInput clean = MakeInput(Gaussian, 0.045, 0.001);
  const double x = kCentre.x() + 0.05, y = kCentre.y() + 0.01;
  const MappingInput bad = MakeInput(Gaussian, 0.045, 0.001, {{x, y, Gaussian(x, y) + 0.012}});
  const TriangleMesh bottom = FlatBottom();
  const MeshIndex cad(bottom);
  MappingOptions o;
  NullProgress p;
  const PeakFitOptions po = PeakFitOptionsFor(o);
  auto best = [&](const MappingInput& in) {
    FittedPeak out;
    for (const FittedPeak& f : FitPeaks(in, cad, DetectAllShapes(in, o, p), po)) {
      if (f.top > out.top) out = f;
    }
    return out;
  };
  const FittedPeak a = best(clean), b = best(bad);
  ASSERT_TRUE(a.accepted) << a.reason;
  ASSERT_TRUE(b.accepted) << b.reason;
  EXPECT_GT(b.full_height, a.full_height + 0.001) << "the wrong feature pulls the plain fit up";
  EXPECT_LE(b.height, kApex + 0.001);
  std::printf("clean %.4f (all %.4f), wrong %.4f (all %.4f)\n", a.height, a.full_height, b.height, b.full_height);
}

}  // namespace
}  // namespace hull
