// The binary Gaussian max-mixture of eq. 7: the decision boundary, the label,
// and a cost that is the true negative log of the larger density.
#include <gtest/gtest.h>

#include <cmath>

#include "adjust/adjust_options.h"
#include "base/error.h"

namespace hull {
namespace {

TEST(MaxMixture, DecisionBoundaryOfThePaper) {
  AdjustmentOptions o;  // sigma0 = 1 m, sigma1 = 0.02 m
  EXPECT_NEAR(o.DecisionBoundary(), 0.05595, 1e-4);
  EXPECT_EQ(MaxMixtureLabel(0.0559, 1.0, 0.02), 1);
  EXPECT_EQ(MaxMixtureLabel(-0.0559, 1.0, 0.02), 1);
  EXPECT_EQ(MaxMixtureLabel(0.0560, 1.0, 0.02), 0);
  EXPECT_EQ(MaxMixtureLabel(-0.0560, 1.0, 0.02), 0);
}

TEST(MaxMixture, LabelIsTheLargerDensity) {
  for (double s1 : {0.01, 0.02, 0.05}) {
    for (double h = -0.3; h <= 0.3; h += 0.001) {
      auto density = [h](double s) { return std::exp(-0.5 * h * h / (s * s)) / s; };
      EXPECT_EQ(MaxMixtureLabel(h, 1.0, s1), density(s1) >= density(1.0) ? 1 : 0) << h;
    }
  }
}

TEST(MaxMixture, BoundaryMovesWithSigma) {
  AdjustmentOptions o;
  o.sigma1 = 0.01;
  const double b1 = o.DecisionBoundary();
  o.sigma1 = 0.05;
  EXPECT_GT(o.DecisionBoundary(), b1);
  // At the boundary both components are equally likely.
  const double b = o.DecisionBoundary();
  EXPECT_NEAR(0.5 * b * b / (o.sigma1 * o.sigma1) + std::log(o.sigma1), 0.5 * b * b + std::log(1.0), 1e-9);
}

TEST(MaxMixture, OptionsAreChecked) {
  AdjustmentOptions o;
  EXPECT_NO_THROW(o.Check());
  o.sigma0 = 0.01;  // not above sigma1
  EXPECT_THROW(o.Check(), OptionError);
  o = AdjustmentOptions();
  o.sigma1 = 0;
  EXPECT_THROW(o.Check(), OptionError);
  o = AdjustmentOptions();
  o.max_iterations = 0;
  EXPECT_THROW(o.Check(), OptionError);
  EXPECT_THROW(ParseSurfaceModel("squashed"), OptionError);
  EXPECT_EQ(ParseSurfaceModel("all-on-surface"), SurfaceModel::kAllOnSurface);
}

}  // namespace
}  // namespace hull
