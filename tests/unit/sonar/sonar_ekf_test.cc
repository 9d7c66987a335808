// The sonar EKF: its API contract, the covariance it keeps, the two
// initialisations and a large state.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "base/error.h"
#include "simulate/sonar_simulator.h"
#include "sonar/acoustic_camera.h"
#include "sonar/sonar_ekf.h"
#include "sonar/sonar_runner.h"

namespace hull {
namespace {

AcousticSequence Prism(std::uint64_t seed, bool noise = true) {
  SonarSimulationOptions o;
  o.seed = seed;
  o.noise = noise;
  return SimulateSonar(o);
}

double MinEigenvalue(const Eigen::MatrixXd& P) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}

TEST(SonarEkfOptions, CheckNamesTheField) {
  SonarEkfOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.hypotheses = 2;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("hypotheses:", 0), 0u) << why;
  o = SonarEkfOptions();
  o.collapse_probability = 1.0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("collapse_probability:", 0), 0u) << why;
  o = SonarEkfOptions();
  o.paper_elevation_sigma_fraction = 0;
  EXPECT_FALSE(o.Check(&why));
  o = SonarEkfOptions();
  o.update_block = 0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("update_block:", 0), 0u) << why;
  o = SonarEkfOptions();
  o.max_delay_steps = 0;
  EXPECT_FALSE(o.Check());
  const AcousticSequence seq = Prism(1);
  try {
    SonarEkf ekf(seq, o);
    ADD_FAILURE() << "bad options accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "max_delay_steps");
  }
  EXPECT_EQ(ParseSonarInit("paper"), SonarInit::kPaper);
  EXPECT_EQ(ParseSonarInit("hypotheses"), SonarInit::kHypotheses);
  EXPECT_THROW(ParseSonarInit("zero"), OptionError);
}

TEST(SonarEkf, StepRefusesMisuse) {
  const AcousticSequence seq = Prism(1);
  const auto by_step = MeasurementsByStep(seq);
  SonarEkf ekf(seq);
  EXPECT_THROW(ekf.Step(&seq.controls[0], by_step[0]), std::invalid_argument);  // control at step 0
  EXPECT_THROW(ekf.Step(nullptr, by_step[1]), std::invalid_argument);           // measurements of step 1 at step 0
  std::vector<SonarMeasurement> twice = by_step[0];
  twice.push_back(twice.front());
  EXPECT_THROW(ekf.Step(nullptr, twice), std::invalid_argument);
  ekf.Step(nullptr, by_step[0]);
  EXPECT_EQ(ekf.step(), 0);
  EXPECT_THROW(ekf.Step(nullptr, by_step[1]), std::invalid_argument);           // control missing
  EXPECT_THROW(ekf.Step(&seq.controls[1], by_step[1]), std::invalid_argument);  // control of step 2
  ekf.Step(&seq.controls[0], by_step[1]);
  EXPECT_EQ(ekf.step(), 1);
}

TEST(SonarEkf, CovarianceStaysSymmetricPositiveDefinite) {
  for (SonarInit init : {SonarInit::kPaper, SonarInit::kHypotheses}) {
    const AcousticSequence seq = Prism(2);
    const auto by_step = MeasurementsByStep(seq);
    SonarEkfOptions o;
    o.init = init;
    SonarEkf ekf(seq, o);
    for (int k = 0; k < seq.num_steps(); ++k) {
      ekf.Step(k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr, by_step[static_cast<std::size_t>(k)]);
      const Eigen::MatrixXd& P = ekf.covariance();
      ASSERT_EQ(P.rows(), ekf.state().size());
      EXPECT_EQ((P - P.transpose()).cwiseAbs().maxCoeff(), 0.0) << SonarInitName(init) << " step " << k;
      // A pose clone (kHypotheses) is an exact copy of the pose when made, so
      // the whole matrix is only positive semi-definite; the pose and the
      // features' block is positive definite.
      EXPECT_GT(MinEigenvalue(P), -1e-12 * P.diagonal().maxCoeff()) << SonarInitName(init) << " step " << k;
      std::vector<int> idx = {0, 1, 2, 3, 4, 5};
      for (const SonarFeatureEstimate& f : ekf.Features()) {
        if (!f.in_state) continue;
        for (int a = 0; a < 3; ++a) idx.push_back(ekf.FeatureOffset(f.id) + a);
      }
      Eigen::MatrixXd B(idx.size(), idx.size());
      for (std::size_t i = 0; i < idx.size(); ++i) {
        for (std::size_t j = 0; j < idx.size(); ++j) B(i, j) = P(idx[i], idx[j]);
      }
      EXPECT_GT(MinEigenvalue(B), 0.0) << SonarInitName(init) << " step " << k;
    }
    // Every feature entered, every clone released: pose + 8 features.
    EXPECT_EQ(ekf.num_features_in_state(), 8);
    EXPECT_EQ(ekf.num_pending(), 0);
    EXPECT_EQ(ekf.state().size(), 6 + 3 * 8);
  }
}

TEST(SonarEkf, JosephAndShortFormAgree) {
  const AcousticSequence seq = Prism(3);
  SonarRunOptions a, b;
  a.ekf.joseph = true;
  b.ekf.joseph = false;
  for (SonarInit init : {SonarInit::kPaper, SonarInit::kHypotheses}) {
    a.ekf.init = b.ekf.init = init;
    const SonarRunResult ra = RunSonarSequence(seq, a), rb = RunSonarSequence(seq, b);
    ASSERT_EQ(ra.final_features.size(), rb.final_features.size());
    for (std::size_t i = 0; i < ra.final_features.size(); ++i) {
      EXPECT_LT((ra.final_features[i].position - rb.final_features[i].position).norm(), 1e-9);
      EXPECT_LT((ra.final_features[i].covariance - rb.final_features[i].covariance).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

TEST(SonarEkf, UpdateBlocksGiveTheBatchUpdate) {
  // The block size only splits the same linearised update: 1, 3 and all
  // measurements at once agree to rounding.
  SonarSimulationOptions so;
  so.seed = 9;
  so.extra_features = 40;
  const AcousticSequence seq = SimulateSonar(so);
  std::vector<SonarRunResult> runs;
  for (int block : {1, 3, 1000}) {
    SonarRunOptions o;
    o.ekf.init = SonarInit::kPaper;
    o.ekf.update_block = block;
    runs.push_back(RunSonarSequence(seq, o));
  }
  for (std::size_t r = 1; r < runs.size(); ++r) {
    ASSERT_EQ(runs[r].final_features.size(), runs[0].final_features.size());
    EXPECT_LT((runs[r].steps.back().estimate.pose - runs[0].steps.back().estimate.pose).norm(), 1e-9);
    EXPECT_NEAR(runs[r].steps.back().estimate.nis, runs[0].steps.back().estimate.nis, 1e-6);
    for (std::size_t i = 0; i < runs[0].final_features.size(); ++i) {
      EXPECT_LT((runs[r].final_features[i].position - runs[0].final_features[i].position).norm(), 1e-9);
      EXPECT_LT((runs[r].final_features[i].covariance - runs[0].final_features[i].covariance).cwiseAbs().maxCoeff(),
                1e-12);
    }
  }
}

TEST(SonarEkf, PaperInitialisationIsElevationZeroSpanningTheFan) {
  const AcousticSequence seq = Prism(4);
  const auto by_step = MeasurementsByStep(seq);
  SonarEkfOptions o;
  o.init = SonarInit::kPaper;
  SonarEkf ekf(seq, o);
  ekf.Step(nullptr, by_step[0]);
  ASSERT_EQ(ekf.num_features_in_state(), static_cast<int>(by_step[0].size()));
  const SonarSensor& s = seq.sensor;
  for (const SonarMeasurement& m : by_step[0]) {
    const auto f = ekf.Feature(m.feature);
    ASSERT_TRUE(f.has_value());
    EXPECT_TRUE(f->in_state);
    // At elevation 0 on the measured range and azimuth.
    const Eigen::Vector3d polar = SonarPolarOf(ekf.pose(), f->position);
    EXPECT_NEAR(polar[0], m.range, 1e-12);
    EXPECT_NEAR(polar[1], m.azimuth, 1e-12);
    EXPECT_NEAR(polar[2], 0.0, 1e-12);
    // Its standard deviation along the elevation direction is r sigma_phi
    // (sigma_phi = elevation_fov / 4) plus a little from the pose prior.
    // At elevation 0 the elevation direction is the sonar's z axis.
    const Eigen::Vector3d up = RotationFromEuler(ekf.pose()[3], ekf.pose()[4], ekf.pose()[5]).col(2);
    const double sd = std::sqrt(up.dot(f->covariance * up));
    EXPECT_NEAR(sd, m.range * s.elevation_fov / 4, 0.003);
  }
}

TEST(SonarEkf, HypothesesWaitForTheElevationThenEnterWithTheirViews) {
  const AcousticSequence seq = Prism(5);
  const auto by_step = MeasurementsByStep(seq);
  SonarEkf ekf(seq);  // kHypotheses is the default
  ASSERT_EQ(ekf.options().init, SonarInit::kHypotheses);
  const SonarStepEstimate first = ekf.Step(nullptr, by_step[0]);
  EXPECT_EQ(first.initialised, 0);
  EXPECT_EQ(first.pending, 8);
  EXPECT_EQ(ekf.num_features_in_state(), 0);
  EXPECT_EQ(ekf.state().size(), 6 + 6);  // the pose and one clone
  for (const SonarFeatureEstimate& f : ekf.Features()) {
    EXPECT_FALSE(f.in_state);
    // The mixture over the fan: metres of spread across the elevation, at the measured range.
    EXPECT_GT(f.covariance.trace(), 0.01);
  }
  int entered_at = -1;
  for (int k = 1; k < seq.num_steps() && ekf.num_pending() > 0; ++k) {
    const SonarStepEstimate e =
        ekf.Step(&seq.controls[static_cast<std::size_t>(k - 1)], by_step[static_cast<std::size_t>(k)]);
    if (e.initialised > 0 && entered_at < 0) {
      entered_at = k;
      // The replayed views update the new features (2 rows per view).
      EXPECT_GE(e.nis_dof, 2 * e.initialised * k);
    }
  }
  EXPECT_GT(entered_at, 0);
  EXPECT_LE(entered_at, SonarEkfOptions().max_delay_steps);
  EXPECT_EQ(ekf.num_pending(), 0);
  EXPECT_EQ(ekf.state().size(), 6 + 3 * 8);
  for (const SonarFeatureEstimate& f : ekf.Features()) {
    EXPECT_TRUE(f.in_state);
    EXPECT_EQ(f.first_step, 0);
    EXPECT_LT((f.position - seq.truth->features[static_cast<std::size_t>(f.id)]).norm(), 0.1);
  }
}

TEST(SonarEkf, WithoutNoiseTheFeaturesConverge) {
  for (SonarInit init : {SonarInit::kPaper, SonarInit::kHypotheses}) {
    SonarRunOptions o;
    o.ekf.init = init;
    const AcousticSequence seq = Prism(6, /*noise=*/false);
    const SonarRunResult r = RunSonarSequence(seq, o);
    ASSERT_TRUE(r.has_truth);
    EXPECT_LT(r.steps.back().errors->mean_feature_error, 0.004) << SonarInitName(init);
    EXPECT_LT(r.steps.back().errors->position, 0.003) << SonarInitName(init);
  }
}

TEST(SonarEkf, FiveHundredFeatures) {
  // 500 features over a 2 x 3 m field, a part in view at each step (timing:
  // bench_sonar and docs/benchmarks.md).
  SonarSimulationOptions so;
  so.seed = 8;
  so.num_steps = 6;
  so.extra_features = 492;
  so.extra_box = Eigen::Vector3d(2.0, 3.0, 0.5);
  const AcousticSequence seq = SimulateSonar(so);
  const auto by_step = MeasurementsByStep(seq);
  SonarEkfOptions o;
  o.init = SonarInit::kPaper;
  SonarEkf ekf(seq, o);
  int measured = 0;
  for (int k = 0; k < seq.num_steps(); ++k) {
    const SonarStepEstimate e =
        ekf.Step(k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr, by_step[static_cast<std::size_t>(k)]);
    measured += e.updated;
  }
  EXPECT_GT(measured, 500);
  EXPECT_GT(ekf.num_features_in_state(), 250);
  const Eigen::MatrixXd& P = ekf.covariance();
  EXPECT_EQ(P.rows(), 6 + 3 * ekf.num_features_in_state());
  EXPECT_EQ((P - P.transpose()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(MinEigenvalue(P), 0.0);
  double mean = 0;
  int n = 0;
  for (const SonarFeatureEstimate& f : ekf.Features()) {
    mean += (f.position - seq.truth->features[static_cast<std::size_t>(f.id)]).norm();
    ++n;
  }
  EXPECT_LT(mean / n, 0.2);
}

}  // namespace
}  // namespace hull
