// Data association: chi-square quantiles against tables, the optimal
// assignment against exhaustive search, and JCBB where the joint test sees
// what individual gating cannot (predictions correlated through the pose).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "sonar/sonar_association.h"

namespace hull {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Association, ChiSquareQuantilesMatchTables) {
  // Table values: probability, degrees of freedom, quantile.
  const struct {
    double p;
    int dof;
    double q;
  } table[] = {{0.99, 2, 9.2103},    {0.999, 2, 13.8155}, {0.99, 4, 13.2767},  {0.99, 10, 23.2093},
               {0.999, 10, 29.5883}, {0.95, 20, 31.4104}, {0.99, 40, 63.6907}, {0.99, 1, 6.6349},
               {0.999, 3, 16.2662},  {0.95, 21, 32.6706}, {0.6, 7, 7.2832},    {0.99, 400, 468.7245}};
  for (const auto& t : table) EXPECT_NEAR(ChiSquareQuantile(t.p, t.dof), t.q, 1e-4 * std::max(1.0, t.q / 100)) << t.dof;
  EXPECT_THROW(ChiSquareQuantile(1.0, 2), std::invalid_argument);
  EXPECT_THROW(ChiSquareQuantile(0.9, 0), std::invalid_argument);
}

// Exhaustive minimum of the assignment cost (unpaired rows cost `unpaired`).
double BruteForce(const Eigen::MatrixXd& c, double unpaired) {
  const int n = static_cast<int>(c.rows()), m = static_cast<int>(c.cols());
  std::vector<bool> used(static_cast<std::size_t>(m), false);
  std::function<double(int)> best = [&](int i) -> double {
    if (i == n) return 0.0;
    double b = unpaired + best(i + 1);
    for (int j = 0; j < m; ++j) {
      if (used[static_cast<std::size_t>(j)] || !std::isfinite(c(i, j))) continue;
      used[static_cast<std::size_t>(j)] = true;
      b = std::min(b, c(i, j) + best(i + 1));
      used[static_cast<std::size_t>(j)] = false;
    }
    return b;
  };
  return best(0);
}

TEST(Association, OptimalAssignmentIsOptimal) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 10);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 5, m = 1 + (trial / 5) % 6;
    Eigen::MatrixXd c(n, m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) c(i, j) = u(rng) < 3 ? kInf : u(rng);
    }
    const double unpaired = 6.0;
    const std::vector<int> a = OptimalAssignment(c, unpaired);
    ASSERT_EQ(static_cast<int>(a.size()), n);
    double total = 0;
    std::vector<int> count(static_cast<std::size_t>(m), 0);
    for (int i = 0; i < n; ++i) {
      if (a[static_cast<std::size_t>(i)] < 0) {
        total += unpaired;
        continue;
      }
      ASSERT_TRUE(std::isfinite(c(i, a[static_cast<std::size_t>(i)])));
      total += c(i, a[static_cast<std::size_t>(i)]);
      EXPECT_EQ(++count[static_cast<std::size_t>(a[static_cast<std::size_t>(i)])], 1) << "a column used twice";
    }
    EXPECT_NEAR(total, BruteForce(c, unpaired), 1e-9) << "trial " << trial;
  }
}

// Two features side by side in azimuth whose predictions share a pose error
// (correlated), seen shifted by +6 mrad; a clutter detection lies closer to
// the first prediction than its true detection.
AssociationInput SharedShift() {
  AssociationInput in;
  in.predicted = Eigen::Vector4d(2.0, 0.0, 2.0, 0.01);
  const double common = 0.006, own = 0.0003;
  in.covariance = Eigen::Matrix4d::Zero();
  in.covariance.diagonal() << 1e-6, own * own, 1e-6, own * own;
  in.covariance(1, 1) += common * common;
  in.covariance(3, 3) += common * common;
  in.covariance(1, 3) = in.covariance(3, 1) = common * common;
  const Eigen::Matrix2d R = Eigen::Vector2d(1e-6, own * own).asDiagonal();
  in.detected = {{2.0, 0.006}, {2.0, 0.016}, {2.0, 0.003}};  // true, true, clutter
  in.noise = {R, R, R};
  return in;
}

TEST(Association, JointCompatibilitySeesTheSharedShift) {
  const AssociationInput in = SharedShift();
  // Individually the clutter is the nearer one for the first feature, and
  // the optimal assignment of individual distances takes it.
  const Eigen::MatrixXd d = IndividualDistances(in, 0.99);
  EXPECT_LT(d(0, 2), d(0, 0));
  const std::vector<int> greedy = OptimalAssignment(d, ChiSquareQuantile(0.99, 2));
  EXPECT_EQ(greedy[0], 2);
  EXPECT_NE(greedy[1], 1);
  // Jointly, shifts of +3 and +6 mrad cannot both come from one pose error.
  const Association a = JointCompatibility(in, 0.99, 1000);
  EXPECT_TRUE(a.jcbb);
  EXPECT_EQ(a.pairs, 2);
  EXPECT_EQ(a.detection[0], 0);
  EXPECT_EQ(a.detection[1], 1);
  EXPECT_GT(a.nodes, 0);
}

TEST(Association, JcbbGivesUpToTheOptimalAssignment) {
  const AssociationInput in = SharedShift();
  const Association a = JointCompatibility(in, 0.99, 2);
  EXPECT_FALSE(a.jcbb);
  EXPECT_EQ(a.detection, OptimalAssignment(IndividualDistances(in, 0.99), ChiSquareQuantile(0.99, 2)));
  // Nothing in the gate: nothing paired.
  AssociationInput far = in;
  for (Eigen::Vector2d& z : far.detected) z[1] += 1.0;
  const Association none = JointCompatibility(far, 0.99, 1000);
  EXPECT_EQ(none.pairs, 0);
  EXPECT_EQ(none.detection, std::vector<int>({-1, -1}));
}

TEST(Association, JcbbAgreesWithTheOptimalAssignmentOnIndependentPredictions) {
  // Independent predictions: JCBB and the optimal assignment agree.
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 30; ++trial) {
    AssociationInput in;
    const int n = 6;
    in.predicted.resize(2 * n);
    in.covariance = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    for (int i = 0; i < n; ++i) {
      in.predicted.segment<2>(2 * i) = Eigen::Vector2d(1 + 0.05 * i, 0.02 * (i % 3));
      in.covariance.block<2, 2>(2 * i, 2 * i) = Eigen::Vector2d(1e-5, 1e-6).asDiagonal();
      if (i == trial % n) continue;  // one feature not detected
      in.detected.push_back(in.predicted.segment<2>(2 * i) + Eigen::Vector2d(0.003 * g(rng), 0.001 * g(rng)));
      in.noise.push_back(Eigen::Vector2d(1e-5, 1e-6).asDiagonal());
    }
    const Association a = JointCompatibility(in, 0.99, 100000);
    ASSERT_TRUE(a.jcbb);
    const std::vector<int> h = OptimalAssignment(IndividualDistances(in, 0.99), ChiSquareQuantile(0.99, 2));
    // Independent predictions: the joint distance is the sum of the
    // individual ones, so the two agree.
    EXPECT_EQ(a.detection, h) << "trial " << trial;
    EXPECT_EQ(a.detection[static_cast<std::size_t>(trial % n)], -1);
    int j = 0;
    for (int i = 0; i < n; ++i) {
      if (i == trial % n) continue;
      if (a.detection[static_cast<std::size_t>(i)] >= 0) {
        EXPECT_EQ(a.detection[static_cast<std::size_t>(i)], j);
      }
      ++j;
    }
  }
}

}  // namespace
}  // namespace hull
