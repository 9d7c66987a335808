// The EKF's interface for data association (predict and correct apart,
// predicted measurements and their covariances checked numerically,
// per-measurement noise, dropping, confirmation) and the tracker on
// detections made from the truth with clutter.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <tuple>

#include "simulate/sonar_simulator.h"
#include "sonar/acoustic_camera.h"
#include "sonar/sonar_ekf.h"
#include "sonar/sonar_runner.h"
#include "sonar/sonar_tracker.h"

namespace hull {
namespace {

AcousticSequence Prism(std::uint64_t seed) {
  SonarSimulationOptions o;
  o.seed = seed;
  return SimulateSonar(o);
}

// Runs steps 0..k-1 with Step().
void RunTo(SonarEkf& ekf, const AcousticSequence& seq, int k) {
  const auto by_step = MeasurementsByStep(seq);
  for (int i = 0; i < k; ++i) {
    ekf.Step(i ? &seq.controls[static_cast<std::size_t>(i - 1)] : nullptr, by_step[static_cast<std::size_t>(i)]);
  }
}

TEST(SonarEkfInterface, PredictThenCorrectIsStep) {
  const AcousticSequence seq = Prism(2);
  const auto by_step = MeasurementsByStep(seq);
  for (SonarInit init : {SonarInit::kPaper, SonarInit::kHypotheses}) {
    SonarEkfOptions o;
    o.init = init;
    SonarEkf a(seq, o), b(seq, o);
    for (int k = 0; k < seq.num_steps(); ++k) {
      const SonarControl* u = k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr;
      a.Step(u, by_step[static_cast<std::size_t>(k)]);
      b.Predict(u);
      b.Correct(by_step[static_cast<std::size_t>(k)]);
    }
    EXPECT_EQ(a.state(), b.state());
    EXPECT_EQ(a.covariance(), b.covariance());
    EXPECT_THROW(b.Correct({}), std::invalid_argument);                // not predicted
    EXPECT_THROW(b.Predict(&seq.controls[0]), std::invalid_argument);  // the control of another step
  }
}

TEST(SonarEkfInterface, PredictAndCorrectMustAlternate) {
  const AcousticSequence seq = Prism(2);
  SonarEkf ekf(seq);
  EXPECT_THROW(ekf.Correct({}), std::invalid_argument);
  ekf.Predict(nullptr);
  EXPECT_THROW(ekf.Predict(&seq.controls[0]), std::invalid_argument);
  ekf.Correct({});
  EXPECT_EQ(ekf.step(), 0);
}

TEST(SonarEkfInterface, MeasurementNoiseOfItsOwn) {
  const AcousticSequence seq = Prism(3);
  auto by_step = MeasurementsByStep(seq);
  SonarEkfOptions o;
  o.init = SonarInit::kPaper;
  SonarEkf a(seq, o), b(seq, o), c(seq, o);
  for (int k = 0; k < 6; ++k) {
    const SonarControl* u = k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr;
    std::vector<SonarMeasurement> same = by_step[static_cast<std::size_t>(k)], wide = same;
    for (SonarMeasurement& m : same) {
      m.range_sigma = seq.sensor.range_sigma;
      m.azimuth_sigma = seq.sensor.azimuth_sigma;
    }
    for (SonarMeasurement& m : wide) {
      m.range_sigma = 4 * seq.sensor.range_sigma;
      m.azimuth_sigma = 4 * seq.sensor.azimuth_sigma;
    }
    a.Step(u, by_step[static_cast<std::size_t>(k)]);
    b.Step(u, same);
    c.Step(u, wide);
  }
  EXPECT_LT((a.state() - b.state()).norm(), 1e-12);
  EXPECT_LT((a.covariance() - b.covariance()).norm(), 1e-15);
  // Noisier measurements leave every feature less certain.
  for (std::int64_t id : a.FeatureIds()) {
    EXPECT_GT(c.Feature(id)->covariance.trace(), 2 * a.Feature(id)->covariance.trace()) << "feature " << id;
  }
  std::vector<SonarMeasurement> bad = by_step[6];
  bad[0].range_sigma = -1;
  EXPECT_THROW(c.Step(&seq.controls[5], bad), std::invalid_argument);
}

TEST(SonarEkfInterface, PredictedMeasurementsMatchNumericalDerivatives) {
  const AcousticSequence seq = Prism(4);
  SonarEkfOptions o;
  o.init = SonarInit::kPaper;
  SonarEkf ekf(seq, o);
  RunTo(ekf, seq, 5);
  ekf.Predict(&seq.controls[4]);
  const std::vector<std::int64_t> ids = {1, 4, 6};
  Eigen::VectorXd z;
  Eigen::MatrixXd C;
  ekf.PredictMeasurements(ids, &z, &C);
  // H by central differences of h over the whole state, then H P H^T.
  const Eigen::VectorXd x = ekf.state();
  const auto h = [&](const Eigen::VectorXd& s) {
    Eigen::VectorXd out(2 * static_cast<int>(ids.size()));
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const int off = ekf.FeatureOffset(ids[i]);
      out.segment<2>(2 * static_cast<int>(i)) = SonarMeasure<double>(s.head<6>(), Eigen::Vector3d(s.segment<3>(off)));
    }
    return out;
  };
  Eigen::MatrixXd H(z.size(), x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += 1e-6;
    xm[j] -= 1e-6;
    H.col(j) = (h(xp) - h(xm)) / 2e-6;
  }
  EXPECT_LT((z - h(x)).norm(), 1e-12);
  const Eigen::MatrixXd C_num = H * ekf.covariance() * H.transpose();
  EXPECT_LT((C - C_num).cwiseAbs().maxCoeff(), 1e-6 * C_num.cwiseAbs().maxCoeff());
  EXPECT_THROW(ekf.PredictMeasurements({99}, &z, &C), std::invalid_argument);
}

TEST(SonarEkfInterface, WaitingFeaturesPredictOneGaussianPerHypothesis) {
  const AcousticSequence seq = Prism(5);
  const auto by_step = MeasurementsByStep(seq);
  SonarEkf ekf(seq);  // hypotheses
  ekf.Step(nullptr, by_step[0]);
  ekf.Predict(&seq.controls[0]);
  ASSERT_FALSE(ekf.PendingIds().empty());
  const std::int64_t id = ekf.PendingIds().front();
  const std::vector<SonarEkf::HypothesisPrediction> hyp = ekf.PredictPending(id);
  ASSERT_EQ(static_cast<int>(hyp.size()), ekf.options().hypotheses);
  const SonarMeasurement* first = nullptr;
  for (const SonarMeasurement& m : by_step[0]) first = m.feature == id ? &m : first;
  ASSERT_NE(first, nullptr);
  // The anchor is the state's clone (after the pose): [pose 6 | clone 6].
  const Eigen::VectorXd x = ekf.state();
  ASSERT_EQ(x.size(), 12);
  const SonarSensor& s = seq.sensor;
  double wsum = 0;
  for (std::size_t k = 0; k < hyp.size(); ++k) {
    const double phi = -s.elevation_fov / 2 + (k + 0.5) * s.elevation_fov / hyp.size();
    // f(pose, clone, r0, theta0, phi): the predicted measurement; S = J Sigma J^T.
    const auto f = [&](const Eigen::Matrix<double, 15, 1>& v) {
      const Vector6d pose = v.head<6>(), anchor = v.segment<6>(6);
      return SonarMeasure<double>(pose, SonarBackProject<double>(anchor, v[12], v[13], v[14]));
    };
    Eigen::Matrix<double, 15, 1> v;
    v << x.head<12>(), first->range, first->azimuth, phi;
    Eigen::Matrix<double, 2, 15> J;
    for (int j = 0; j < 15; ++j) {
      Eigen::Matrix<double, 15, 1> vp = v, vm = v;
      vp[j] += 1e-7;
      vm[j] -= 1e-7;
      J.col(j) = (f(vp) - f(vm)) / 2e-7;
    }
    Eigen::Matrix<double, 15, 15> Sigma = Eigen::Matrix<double, 15, 15>::Zero();
    Sigma.topLeftCorner<12, 12>() = ekf.covariance();
    const double sh = s.elevation_fov / hyp.size() / 2;
    Sigma.bottomRightCorner<3, 3>().diagonal() << s.range_sigma * s.range_sigma, s.azimuth_sigma * s.azimuth_sigma,
        sh * sh;
    EXPECT_LT((hyp[k].z - f(v)).norm(), 1e-12) << "hypothesis " << k;
    const Eigen::Matrix2d S_num = J * Sigma * J.transpose();
    EXPECT_LT((hyp[k].S - S_num).cwiseAbs().maxCoeff(), 1e-6 * S_num.cwiseAbs().maxCoeff()) << "hypothesis " << k;
    wsum += hyp[k].weight;
  }
  EXPECT_NEAR(wsum, 1.0, 1e-12);
  EXPECT_THROW(ekf.PredictPending(12345), std::invalid_argument);
}

TEST(SonarEkfInterface, DroppingMarginalisesTheFeature) {
  const AcousticSequence seq = Prism(6);
  SonarEkfOptions o;
  o.init = SonarInit::kPaper;
  SonarEkf ekf(seq, o);
  RunTo(ekf, seq, 4);
  const Eigen::VectorXd x = ekf.state();
  const Eigen::MatrixXd P = ekf.covariance();
  const int off = ekf.FeatureOffset(3);
  ASSERT_GE(off, 0);
  std::vector<int> keep;
  for (int i = 0; i < x.size(); ++i) {
    if (i < off || i >= off + 3) keep.push_back(i);
  }
  ASSERT_TRUE(ekf.DropFeature(3));
  EXPECT_FALSE(ekf.DropFeature(3));
  EXPECT_FALSE(ekf.Feature(3).has_value());
  ASSERT_EQ(ekf.state().size(), x.size() - 3);
  for (std::size_t i = 0; i < keep.size(); ++i) {
    EXPECT_EQ(ekf.state()[static_cast<Eigen::Index>(i)], x[keep[i]]);
    for (std::size_t j = 0; j < keep.size(); ++j) {
      EXPECT_EQ(ekf.covariance()(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), P(keep[i], keep[j]));
    }
  }
  // A waiting feature's drop releases its clone: the state shrinks to what it was.
  SonarEkf hyp(seq);
  const auto by_step = MeasurementsByStep(seq);
  hyp.Step(nullptr, {});
  std::vector<SonarMeasurement> one = {by_step[1].front()};
  hyp.Step(&seq.controls[0], one);
  EXPECT_EQ(hyp.state().size(), 12);  // pose and the clone of step 1
  EXPECT_TRUE(hyp.DropFeature(one[0].feature));
  EXPECT_EQ(hyp.state().size(), 6);
  EXPECT_EQ(hyp.num_pending(), 0);
}

TEST(SonarEkfInterface, ConfirmViewsHoldsTentativeFeaturesBack) {
  const AcousticSequence seq = Prism(7);
  const auto by_step = MeasurementsByStep(seq);
  for (SonarInit init : {SonarInit::kPaper, SonarInit::kHypotheses}) {
    SonarEkfOptions o;
    o.init = init;
    o.confirm_views = 3;
    SonarEkf ekf(seq, o);
    ekf.Step(nullptr, by_step[0]);
    ekf.Step(&seq.controls[0], by_step[1]);
    EXPECT_EQ(ekf.num_features_in_state(), 0) << SonarInitName(init);
    for (int k = 2; k < seq.num_steps(); ++k) {
      ekf.Step(&seq.controls[static_cast<std::size_t>(k - 1)], by_step[static_cast<std::size_t>(k)]);
    }
    EXPECT_EQ(ekf.num_features_in_state(), 8) << SonarInitName(init);
    if (init == SonarInit::kPaper) {
      // The paper's start, delayed: every view replayed, so the features are
      // those of the immediate start to within the linearisation.
      SonarEkfOptions now = o;
      now.confirm_views = 1;
      SonarEkf direct(seq, now);
      RunTo(direct, seq, seq.num_steps());
      for (std::int64_t id : direct.FeatureIds()) {
        EXPECT_LT((direct.Feature(id)->position - ekf.Feature(id)->position).norm(), 0.01) << "feature " << id;
      }
    }
  }
}

// Detections made from the true measurements: their noise, plus clutter
// spread over the image.
std::vector<SonarDetection> Detections(const std::vector<SonarMeasurement>& ms, const SonarSensor& s,
                                       const SonarImageFormat& f, int clutter, std::mt19937& rng) {
  std::vector<SonarDetection> out;
  std::uniform_real_distribution<double> u(0, 1);
  const auto add = [&](double range, double azimuth) {
    SonarDetection d;
    d.range = range;
    d.azimuth = azimuth;
    d.row = f.RangeToRow(s, range);
    d.col = f.AzimuthToColumn(s, azimuth);
    d.covariance = Eigen::Vector2d(s.range_sigma * s.range_sigma, s.azimuth_sigma * s.azimuth_sigma).asDiagonal();
    out.push_back(d);
  };
  for (const SonarMeasurement& m : ms) add(m.range, m.azimuth);
  for (int c = 0; c < clutter; ++c) {
    add(s.range_min + u(rng) * (s.range_max - s.range_min), (u(rng) - 0.5) * s.azimuth_fov);
  }
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

TEST(SonarTracker, AssociatesConfirmsAndDrops) {
  const AcousticSequence seq = Prism(8);
  auto by_step = MeasurementsByStep(seq);
  // Feature 2 disappears after step 12 while it stays in view.
  for (int k = 13; k < seq.num_steps(); ++k) {
    auto& ms = by_step[static_cast<std::size_t>(k)];
    ms.erase(std::remove_if(ms.begin(), ms.end(), [](const SonarMeasurement& m) { return m.feature == 2; }), ms.end());
  }
  const SonarImageFormat f;
  SonarEkfOptions eo;
  eo.confirm_views = 3;
  SonarEkf ekf(seq, eo);
  SonarTrackerOptions to;
  to.drop_misses = 4;
  to.first_id = 100;
  SonarTracker tracker(to);
  std::mt19937 rng(1);
  // (feature, detection, step, in the state) of each association
  std::vector<std::tuple<std::int64_t, Eigen::Vector2d, int, bool>> pairs;
  std::map<std::int64_t, std::map<std::int64_t, int>> votes;  // feature -> true feature -> detections
  std::vector<std::int64_t> dropped;
  for (int k = 0; k < seq.num_steps(); ++k) {
    const auto& truth = by_step[static_cast<std::size_t>(k)];
    std::vector<SonarDetection> dets = Detections(truth, seq.sensor, f, 2, rng);
    const SonarControl* u = k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr;
    const SonarTrackStep t = tracker.Step(ekf, u, dets, f);
    ASSERT_EQ(t.feature.size(), dets.size());
    for (std::size_t j = 0; j < dets.size(); ++j) {
      std::int64_t label = -1;
      for (const SonarMeasurement& m : truth) {
        if (m.range == dets[j].range && m.azimuth == dets[j].azimuth) label = m.feature;
      }
      EXPECT_GE(t.feature[j], 100);
      ++votes[t.feature[j]][label];
      if (t.pairing[j] != SonarPairing::kNew) {
        pairs.emplace_back(t.feature[j], Eigen::Vector2d(dets[j].range, dets[j].azimuth), k,
                           t.pairing[j] == SonarPairing::kInState);
      }
    }
    for (std::int64_t id : t.dropped) {
      if (!ekf.Feature(id)) dropped.push_back(id);
    }
  }
  // Each feature stands for the true feature most of its detections are of.
  std::map<std::int64_t, std::int64_t> truth_of;
  for (const auto& [id, v] : votes) {
    int best = 0;
    for (const auto& [label, n] : v) {
      if (n > best) {
        best = n;
        truth_of[id] = label;
      }
    }
  }
  int wrong = 0, wrong_in_state = 0;
  // Wrong: the detection is not where the feature's true vertex projects
  // (two vertices may project to one place, e.g. an edge's ends without roll).
  for (const auto& [id, z, k, in_state] : pairs) {
    const std::int64_t t = truth_of.at(id);
    if (t < 0) continue;
    const Eigen::Vector2d h = SonarMeasure<double>(seq.truth->poses[static_cast<std::size_t>(k)],
                                                   seq.truth->features[static_cast<std::size_t>(t)]);
    const bool w =
        std::abs(h[0] - z[0]) > 4 * seq.sensor.range_sigma || std::abs(h[1] - z[1]) > 4 * seq.sensor.azimuth_sigma;
    wrong += w;
    wrong_in_state += w && in_state;
  }
  const int paired = static_cast<int>(pairs.size());
  std::int64_t dropped_truth = -1;
  for (std::int64_t id : dropped) dropped_truth = truth_of.at(id) >= 0 ? truth_of.at(id) : dropped_truth;
  EXPECT_GT(paired, 100);
  // Tentative features born where two vertices coincide (an edge's ends
  // before any roll) may take either one when they part; once in the state
  // every association is right.
  EXPECT_EQ(wrong_in_state, 0);
  EXPECT_LE(wrong, paired / 25) << "of " << paired;
  EXPECT_EQ(dropped_truth, 2) << "the feature that vanished in view is dropped";
  // The true features are in the state (the vanished one not), the clutter not.
  int in_state_true = 0;
  for (std::int64_t id : ekf.FeatureIds()) {
    EXPECT_GE(truth_of.at(id), 0) << "clutter entered the state as feature " << id;
    EXPECT_NE(truth_of.at(id), 2);
    in_state_true += truth_of.at(id) >= 0;
  }
  EXPECT_EQ(in_state_true, 7);
  EXPECT_LE(ekf.num_pending(), 4) << "tentative clutter is dropped";
}

// The step keeps what the EKF predicted before the correction (the fan
// view draws it): every in-state candidate with h(X) and H P H^T as the
// filter computes them after the prediction, the detection JCBB paired with
// it; waiting features with their most likely hypothesis.
TEST(SonarTracker, KeepsThePredictionsAndTheirPairings) {
  const AcousticSequence seq = Prism(3);
  const auto by_step = MeasurementsByStep(seq);
  const SonarImageFormat f;
  SonarEkfOptions eo;
  eo.confirm_views = 3;
  SonarEkf ekf(seq, eo);
  SonarTracker tracker;
  std::mt19937 rng(4);
  int in_state = 0, waiting = 0, paired = 0;
  for (int k = 0; k < seq.num_steps(); ++k) {
    const std::vector<SonarDetection> dets = Detections(by_step[static_cast<std::size_t>(k)], seq.sensor, f, 1, rng);
    const SonarControl* u = k ? &seq.controls[static_cast<std::size_t>(k - 1)] : nullptr;
    SonarEkf before = ekf;
    before.Predict(u);
    const std::vector<std::int64_t> pending = before.PendingIds();
    const SonarTrackStep t = tracker.Step(ekf, u, dets, f);
    int candidates = 0;
    std::vector<int> claimed(dets.size(), 0);
    for (const SonarPrediction& p : t.predictions) {
      if (p.detection >= 0) {
        ASSERT_LT(p.detection, static_cast<int>(dets.size()));
        ++claimed[static_cast<std::size_t>(p.detection)];
        EXPECT_EQ(t.feature[static_cast<std::size_t>(p.detection)], p.id);
        EXPECT_EQ(t.pairing[static_cast<std::size_t>(p.detection)],
                  p.waiting ? SonarPairing::kWaiting : SonarPairing::kInState);
        ++paired;
      }
      if (p.waiting) {
        ++waiting;
        EXPECT_TRUE(std::binary_search(pending.begin(), pending.end(), p.id));
        double best = -1;
        Eigen::Vector2d z = Eigen::Vector2d::Zero();
        for (const auto& h : before.PredictPending(p.id)) {
          if (h.weight > best) {
            best = h.weight;
            z = h.z;
          }
        }
        EXPECT_NEAR((p.z - z).norm(), 0.0, 1e-12);
        continue;
      }
      ++candidates;
      ++in_state;
      Eigen::VectorXd z;
      Eigen::MatrixXd C;
      before.PredictMeasurements({p.id}, &z, &C);
      EXPECT_NEAR((p.z - z).norm(), 0.0, 1e-12);
      EXPECT_NEAR((p.covariance - C).norm(), 0.0, 1e-9 * C.norm());
      EXPECT_GT(p.covariance.determinant(), 0.0);
    }
    EXPECT_EQ(candidates, t.candidates) << "step " << k;
    for (std::size_t j = 0; j < dets.size(); ++j) {
      // Every detection paired with an in-state feature is some prediction's, once.
      if (t.pairing[j] == SonarPairing::kInState) {
        EXPECT_EQ(claimed[j], 1) << "step " << k;
      }
      EXPECT_LE(claimed[j], 1);
    }
  }
  EXPECT_GT(in_state, 100);
  EXPECT_GT(waiting, 0);
  EXPECT_GT(paired, 100);
}

TEST(SonarTracker, OptionsCheckNamesTheField) {
  SonarTrackerOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  o.gate_probability = 1;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("gate_probability:", 0), 0u) << why;
  o = SonarTrackerOptions();
  o.drop_misses = 0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why.rfind("drop_misses:", 0), 0u) << why;
}

}  // namespace
}  // namespace hull
