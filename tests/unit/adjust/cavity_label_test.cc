// The max-mixture's E-step by the cavity estimate (adjust/cavity_label.h):
// a landmark whose observations put it above the decision boundary, pulled
// below it by its own on-model component, is recognised as off the model.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "adjust/adjust_options.h"
#include "adjust/cavity_label.h"
#include "base/error.h"

namespace hull {
namespace {

// What a landmark's observations say: a Gaussian on its position with
// standard deviations sx, sy, sz along g's axes (z: the hull's normal here).
struct PositionPrior {
  Eigen::Vector3d mean, sigma;
  template <typename T>
  bool operator()(const T* l, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = (l[i] - T(mean[i])) / T(sigma[i]);
    return true;
  }
};

// A surface factor on the plane z = 0 (h = l_z), its component chosen by
// h as the max-mixture chooses it, or forced off.
struct PlaneSurface {
  double sigma0, sigma1;
  const bool* off;
  template <typename T>
  bool operator()(const T* l, T* r) const {
    const T h = l[2];
    double hv;
    if constexpr (std::is_same_v<T, double>) {
      hv = h;
    } else {
      hv = h.a;
    }
    const bool on = !*off && MaxMixtureLabel(hv, sigma0, sigma1) == 1;
    r[0] = h / T(on ? sigma1 : sigma0);
    r[1] = T(on ? 0.0 : std::sqrt(2.0 * std::log(sigma0 / sigma1)));
    return true;
  }
};

// Only x and y of a landmark observed.
struct XY {
  template <typename T>
  bool operator()(const T* p, T* r) const {
    r[0] = p[0] / T(0.01);
    r[1] = p[1] / T(0.01);
    return true;
  }
};

struct OneLandmark {
  double l[3];
  bool off = false;
  ceres::Problem problem;
  ceres::ResidualBlockId surface = nullptr;

  OneLandmark(const Eigen::Vector3d& measured, const Eigen::Vector3d& sigma, double start_h) {
    l[0] = measured.x();
    l[1] = measured.y();
    l[2] = start_h;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PositionPrior, 3, 3>(new PositionPrior{measured, sigma}),
                             nullptr, l);
    surface = problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<PlaneSurface, 2, 3>(new PlaneSurface{1.0, 0.02, &off}), nullptr, l);
  }
  void Solve() {
    ceres::Solver::Options so;
    so.max_num_iterations = 50;
    so.function_tolerance = 1e-14;
    so.gradient_tolerance = 1e-14;
    so.parameter_tolerance = 1e-14;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
  }
};

TEST(CavityLabel, AFeatureOfALowObjectPulledBelowTheBoundaryIsOffTheModel) {
  // Observed 6.2 cm above the hull with 3 cm of depth noise (the rendered
  // demo's patch-2), starting on the model: its on-model component pulls it
  // to 6.2 * 2^2 / (2^2 + 3^2) = 1.9 cm, where the estimate's label is "on".
  OneLandmark a(Eigen::Vector3d(0.1, 0.2, 0.062), Eigen::Vector3d(0.004, 0.004, 0.03), 0.0);
  a.Solve();
  const double h = a.l[2];
  EXPECT_NEAR(h, 0.062 * 4.0 / 13.0, 1e-6);
  EXPECT_EQ(MaxMixtureLabel(h, 1.0, 0.02), 1);
  const adjust::CavityEstimate c = adjust::Cavity(a.problem, a.l, a.surface, h, 0.02);
  EXPECT_NEAR(c.sigma, 0.03, 1e-9);
  EXPECT_NEAR(c.h, 0.062, 1e-6);  // what its observations say
  EXPECT_TRUE(adjust::CavityOffModel(c, 1.0, 0.02));
  // Labelled off, it goes back to where it was observed, and its cavity
  // estimate there (under the off component) stays off.
  a.off = true;
  a.Solve();
  EXPECT_NEAR(a.l[2], 0.062 / (1.0 + 0.03 * 0.03), 1e-6);
  EXPECT_TRUE(adjust::CavityOffModel(adjust::Cavity(a.problem, a.l, a.surface, a.l[2], 1.0), 1.0, 0.02));
}

TEST(CavityLabel, HullNoiseStaysOnTheModel) {
  // 3 cm of depth noise, observed 4 cm off the hull: below the boundary
  // (5.6 cm) with or without its own factor.
  for (const double measured : {0.04, -0.04, 0.0, 0.05}) {
    OneLandmark a(Eigen::Vector3d(0, 0, measured), Eigen::Vector3d(0.004, 0.004, 0.03), measured);
    a.Solve();
    const adjust::CavityEstimate c = adjust::Cavity(a.problem, a.l, a.surface, a.l[2], 0.02);
    EXPECT_NEAR(c.h, measured, 1e-6) << measured;
    EXPECT_FALSE(adjust::CavityOffModel(c, 1.0, 0.02)) << measured;
  }
  // Precisely observed (1 mm), the factor hardly moves it: the cavity
  // estimate is the estimate.
  OneLandmark b(Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(0.001, 0.001, 0.001), 0.05);
  b.Solve();
  const adjust::CavityEstimate c = adjust::Cavity(b.problem, b.l, b.surface, b.l[2], 0.02);
  EXPECT_NEAR(c.h, 0.05, 1e-6);
  EXPECT_NEAR(b.l[2], 0.05 / (1 + 0.0025), 1e-6);
  EXPECT_FALSE(adjust::CavityOffModel(c, 1.0, 0.02));
}

TEST(CavityLabel, ObservationsThatFixNoHeightGiveNoCavity) {
  // Only x and y observed (a degenerate information matrix): no sigma, and
  // the estimate's own label stands.
  double l[3] = {0, 0, 0.07};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<XY, 2, 3>(new XY), nullptr, l);
  bool off = false;
  const ceres::ResidualBlockId s = problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<PlaneSurface, 2, 3>(new PlaneSurface{1.0, 0.02, &off}), nullptr, l);
  const adjust::CavityEstimate c = adjust::Cavity(problem, l, s, 0.07, 0.02);
  EXPECT_TRUE(std::isnan(c.sigma));
  EXPECT_EQ(c.h, 0.07);
}

TEST(CavityLabel, RuleNames) {
  EXPECT_EQ(ParseLabelRule("cavity"), LabelRule::kCavity);
  EXPECT_EQ(ParseLabelRule("estimate"), LabelRule::kEstimate);
  EXPECT_STREQ(LabelRuleName(LabelRule::kCavity), "cavity");
  EXPECT_THROW(ParseLabelRule("posterior"), OptionError);
  AdjustmentOptions o;
  EXPECT_EQ(o.labels, LabelRule::kCavity);
  o.label_rounds = -1;
  EXPECT_THROW(o.Check(), OptionError);
}

}  // namespace
}  // namespace hull
