// Landmark covariances by the Schur complement (landmark_covariance_schur.h)
// against a dense inverse and against Ceres' sparse-QR covariance.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cmath>
#include <random>
#include <vector>

#include "adjust/bundle_adjuster.h"
#include "adjust/landmark_covariance.h"
#include "adjust/landmark_covariance_schur.h"
#include "base/error.h"
#include "support/test_surveys.h"

namespace hull {
namespace {

// A random sparse SPD matrix: a band, scattered couplings and a dense last
// row and column (like the model pose's), made diagonally dominant.
Eigen::MatrixXd RandomSparseSpd(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> pick(0, n - 1);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - 2); j < i; ++j) a(i, j) = a(j, i) = u(rng);
  }
  for (int k = 0; k < n; ++k) {
    const int i = pick(rng), j = pick(rng);
    if (i != j) a(i, j) = a(j, i) = u(rng);
  }
  for (int j = 0; j < n - 1; ++j) a(n - 1, j) = a(j, n - 1) = 0.3 * u(rng);
  for (int i = 0; i < n; ++i) a(i, i) = a.row(i).cwiseAbs().sum() + 0.5;
  return a;
}

Eigen::SparseMatrix<double> Lower(const Eigen::MatrixXd& a) {
  const Eigen::MatrixXd lower = a.triangularView<Eigen::Lower>();
  return lower.sparseView();
}

TEST(SelectedInverse, MatchesTheDenseInverseOnTheFactorsPattern) {
  const int n = 80;
  const Eigen::MatrixXd a = RandomSparseSpd(n, 3);
  const Eigen::MatrixXd inv = a.inverse();
  adjust::SelectedInverse z;
  std::string why;
  ASSERT_TRUE(z.Compute(Lower(a), &why)) << why;
  EXPECT_EQ(z.size(), n);
  int on_pattern = 0;
  for (int c = 0; c < n; ++c) {
    for (int r = 0; r < n; ++r) {
      double v = 0;
      if (!z.Get(r, c, &v)) {
        EXPECT_EQ(a(r, c), 0.0) << "a nonzero of A is off the factor's pattern: " << r << ", " << c;
        continue;
      }
      ++on_pattern;
      EXPECT_NEAR(v, inv(r, c), 1e-12 * inv.cwiseAbs().maxCoeff()) << r << ", " << c;
    }
  }
  // Beyond A's own nonzeros (the fill), but not the whole inverse.
  EXPECT_GT(on_pattern, (a.array() != 0).count());
  EXPECT_LT(on_pattern, n * n);
  // A run of rows of one column: rows 1 and 2 of column 0 (the band), and
  // the dense last row in every column; none past the last row.
  double run[2];
  ASSERT_TRUE(z.GetColumnRun(1, 2, 0, run));
  EXPECT_NEAR(run[0], inv(1, 0), 1e-12 * inv.cwiseAbs().maxCoeff());
  EXPECT_NEAR(run[1], inv(2, 0), 1e-12 * inv.cwiseAbs().maxCoeff());
  for (int c = 0; c < n - 1; ++c) {
    ASSERT_TRUE(z.GetColumnRun(n - 1, 1, c, run)) << c;
    EXPECT_NEAR(run[0], inv(n - 1, c), 1e-12 * inv.cwiseAbs().maxCoeff());
  }
  EXPECT_FALSE(z.GetColumnRun(n - 1, 2, 0, run));
}

TEST(SelectedInverse, RefusesASingularMatrix) {
  Eigen::MatrixXd a = RandomSparseSpd(30, 5);
  // Make row 29 a copy of row 28 (and the columns likewise): rank 29.
  a.row(29) = a.row(28);
  a.col(29) = a.col(28);
  adjust::SelectedInverse z;
  std::string why;
  EXPECT_FALSE(z.Compute(Lower(a), &why));
  EXPECT_NE(why.find("singular"), std::string::npos) << why;
}

// The largest difference between two covariances relative to the largest
// entry.
double RelativeDifference(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(a.cwiseAbs().maxCoeff(), 1e-300);
}

// The small simulated survey adjusted twice on one thread (so the solutions
// are identical), its covariances by the Schur complement and by sparse QR.
void ExpectSchurMatchesSparseQr(const AdjustmentOptions& base) {
  const SimulatedSurvey& sim = test::SmallSurvey();
  const Pose guess = Pose::FromVector(*sim.bundle.manifest.model_pose_guess);
  NullProgress p;
  AdjustmentOptions o = base;
  o.num_threads = 1;
  o.covariance = CovarianceMethod::kFull;
  const AdjustmentResult schur = RunAdjustment(sim.bundle, sim.cad, guess, o, p);
  o.covariance = CovarianceMethod::kFullSparseQr;
  const AdjustmentResult qr = RunAdjustment(sim.bundle, sim.cad, guess, o, p);
  EXPECT_EQ(schur.covariance_method, CovarianceMethod::kFull) << schur.covariance_note;
  EXPECT_EQ(qr.covariance_method, CovarianceMethod::kFullSparseQr) << qr.covariance_note;
  ASSERT_EQ(schur.landmarks.size(), qr.landmarks.size());
  ASSERT_GT(schur.landmarks.size(), 100u);
  double worst = 0, worst_sigma = 0;
  for (std::size_t i = 0; i < schur.landmarks.size(); ++i) {
    const LandmarkEstimate &a = schur.landmarks[i], &b = qr.landmarks[i];
    ASSERT_EQ(a.p, b.p) << "the two adjustments differ";
    ASSERT_TRUE(a.covariance.allFinite()) << i;
    worst = std::max(worst, RelativeDifference(a.covariance, b.covariance));
    ASSERT_TRUE(std::isfinite(a.sigma_h)) << i;
    worst_sigma = std::max(worst_sigma, std::abs(a.sigma_h - b.sigma_h) / b.sigma_h);
  }
  std::printf("%zu landmarks: covariances within %.2e, sigma_h within %.2e (relative); %.3f s against %.3f s\n",
              schur.landmarks.size(), worst, worst_sigma, schur.covariance_seconds, qr.covariance_seconds);
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(worst_sigma, 1e-6);
}

TEST(SchurCovariance, MatchesSparseQrOnASmallSurvey) {
  AdjustmentOptions o;
  o.max_iterations = 30;
  ExpectSchurMatchesSparseQr(o);
}

// Held blocks (servo angles, extrinsic) are not variables of either.
TEST(SchurCovariance, MatchesSparseQrWithHeldServoAndExtrinsic) {
  AdjustmentOptions o;
  o.max_iterations = 30;
  o.estimate_servo = false;
  o.estimate_extrinsic = false;
  ExpectSchurMatchesSparseQr(o);
}

// Without surface factors (naive): the landmark marginals only, sigma_h
// from them.
TEST(SchurCovariance, MatchesSparseQrWithoutSurfaceFactors) {
  AdjustmentOptions o;
  o.max_iterations = 30;
  o.model = SurfaceModel::kNaive;
  ExpectSchurMatchesSparseQr(o);
}

// Several threads (the landmarks' parts are computed in parallel, their
// residual blocks evaluated on one thread): the same covariances as on one,
// to the agreement of the two adjustments themselves.
TEST(SchurCovariance, ThreeThreadsAgreeWithOne) {
  const SimulatedSurvey& sim = test::SmallSurvey();
  const Pose guess = Pose::FromVector(*sim.bundle.manifest.model_pose_guess);
  NullProgress p;
  AdjustmentOptions o;
  o.max_iterations = 30;
  o.num_threads = 1;
  const AdjustmentResult one = RunAdjustment(sim.bundle, sim.cad, guess, o, p);
  o.num_threads = 3;
  const AdjustmentResult three = RunAdjustment(sim.bundle, sim.cad, guess, o, p);
  ASSERT_EQ(three.covariance_method, CovarianceMethod::kFull) << three.covariance_note;
  ASSERT_EQ(one.landmarks.size(), three.landmarks.size());
  for (std::size_t i = 0; i < one.landmarks.size(); ++i) {
    EXPECT_LT(RelativeDifference(three.landmarks[i].covariance, one.landmarks[i].covariance), 1e-4) << i;
    EXPECT_NEAR(three.landmarks[i].sigma_h, one.landmarks[i].sigma_h, 1e-4 * one.landmarks[i].sigma_h) << i;
  }
}

// r = x - target over the first `rows` coordinates of a 3-vector.
class Partial final : public ceres::CostFunction {
 public:
  explicit Partial(int rows) : rows_(rows) {
    set_num_residuals(rows);
    mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    for (int i = 0; i < rows_; ++i) r[i] = x[0][i] - 1.0;
    if (jac && jac[0]) {
      for (int i = 0; i < rows_ * 3; ++i) jac[0][i] = 0;
      for (int i = 0; i < rows_; ++i) jac[0][i * 3 + i] = 1;
    }
    return true;
  }

 private:
  int rows_;
};

// A landmark its residuals do not fix (one coordinate only): no full
// covariance; the fallback is reported.
TEST(SchurCovariance, ASingularLandmarkFallsBackToConditionalAndSaysWhy) {
  double good[3] = {1, 1, 1}, bad[3] = {1, 1, 1};
  ceres::Problem problem;
  problem.AddResidualBlock(new Partial(3), nullptr, good);
  problem.AddResidualBlock(new Partial(1), nullptr, bad);
  const LandmarkCovariances c = ComputeLandmarkCovariances(problem, {good, bad}, CovarianceMethod::kFull, 1);
  EXPECT_EQ(c.method, CovarianceMethod::kConditional);
  EXPECT_NE(c.note.find("landmark 1"), std::string::npos) << c.note;
  EXPECT_TRUE(c.covariance[0].isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_FALSE(c.covariance[1].allFinite());
}

// Landmarks alone (no reduced system): the inverse of each H_ll.
TEST(SchurCovariance, LandmarksAloneGiveTheirOwnInverse) {
  double a[3] = {0, 0, 0}, b[3] = {2, 2, 2};
  ceres::Problem problem;
  problem.AddResidualBlock(new Partial(3), nullptr, a);
  problem.AddResidualBlock(new Partial(3), nullptr, a);
  problem.AddResidualBlock(new Partial(3), nullptr, b);
  const LandmarkCovariances c = ComputeLandmarkCovariances(problem, {a, b}, CovarianceMethod::kFull, 2);
  ASSERT_EQ(c.method, CovarianceMethod::kFull) << c.note;
  EXPECT_TRUE(c.covariance[0].isApprox(0.5 * Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(c.covariance[1].isApprox(Eigen::Matrix3d::Identity()));
}

TEST(CovarianceMethod, NamesRoundTrip) {
  for (const CovarianceMethod m : {CovarianceMethod::kNone, CovarianceMethod::kConditional, CovarianceMethod::kFull,
                                   CovarianceMethod::kFullSparseQr}) {
    EXPECT_EQ(ParseCovarianceMethod(CovarianceMethodName(m)), m);
  }
  EXPECT_THROW(ParseCovarianceMethod("schur"), OptionError);
}

}  // namespace
}  // namespace hull
