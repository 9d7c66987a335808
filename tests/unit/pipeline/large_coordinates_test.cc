// Issue 23.4: a survey in UTM-scale coordinates (the demo moved 400 km east
// and 5,000 km north, as real navigation arrives) gives the same
// alignment, landmarks and objects as the same survey near g's origin: the
// estimators and the mapping work in the survey's local frame
// (survey/survey_origin.h) and answer in the user's.
#include <gtest/gtest.h>

#include <string>
#include <unordered_map>

#include "base/progress.h"
#include "pipeline/pipeline.h"
#include "simulate/survey_simulator.h"
#include "survey/survey_origin.h"

namespace hull {
namespace {

const Eigen::Vector3d kShift(4e5, 5e6, 0.0);

TEST(SurveyOrigin, LocalOriginIsTheFirstKeyframeOnAKilometreGrid) {
  SurveyBundle b;
  EXPECT_TRUE(LocalOrigin(b).isZero());
  NavRecord n;
  n.x_gv << 399993.1, 5000000.4, 10.6, 0, 0, 0.35;
  b.nav.push_back(n);
  EXPECT_EQ(LocalOrigin(b), Eigen::Vector3d(4e5, 5e6, 0));
  b.nav[0].x_gv.head<3>() << -3.9, 499.0, 10.0;
  EXPECT_TRUE(LocalOrigin(b).isZero()) << "a survey near g's origin is left as it is";
}

TEST(SurveyOrigin, ShiftSurveyMovesEveryPositionInG) {
  NullProgress np;
  SurveySimulationOptions o = SurveyPreset("demo");
  o.write_landmarks = true;
  const SurveyBundle a = SimulateSurvey(o, np).bundle;
  o.shift = kShift;
  const SurveyBundle b = SimulateSurvey(o, np).bundle;  // the simulator's --shift
  ASSERT_EQ(a.nav.size(), b.nav.size());
  EXPECT_NEAR((b.nav[7].x_gv.head<3>() - a.nav[7].x_gv.head<3>() - kShift).norm(), 0, 1e-8);
  EXPECT_EQ(b.nav[7].x_gv.tail<3>(), a.nav[7].x_gv.tail<3>());
  EXPECT_NEAR(((*b.landmarks)[3].p - (*a.landmarks)[3].p - kShift).norm(), 0, 1e-8);
  EXPECT_NEAR((b.truth->landmarks[3].p - a.truth->landmarks[3].p - kShift).norm(), 0, 1e-8);
  EXPECT_NEAR((b.truth->x_gM.head<3>() - a.truth->x_gM.head<3>() - kShift).norm(), 0, 1e-8);
  ASSERT_TRUE(a.manifest.model_pose_guess && b.manifest.model_pose_guess);
  EXPECT_NEAR((b.manifest.model_pose_guess->head<3>() - a.manifest.model_pose_guess->head<3>() - kShift).norm(), 0,
              1e-8);
  EXPECT_EQ(b.features.size(), a.features.size());
}

TEST(LargeCoordinates, TheShiftedDemoGivesTheSameLandmarksAndObjects) {
  NullProgress np;
  const SimulatedSurvey s = SimulateSurvey(SurveyPreset("demo"), np);
  PipelineInputs near, far;
  near.bundle = s.bundle;
  near.mesh = s.cad;
  far = near;
  ShiftSurvey(far.bundle, kShift);
  PipelineOptions o;
  o.adjustment.num_threads = 2;
  const PipelineResult a = RunPipeline(near, o, np);
  const PipelineResult b = RunPipeline(far, o, np);

  const Pose back(Eigen::Quaterniond::Identity(), -kShift);
  // GICP works in float on centred clouds and stops at 0.1 mm steps: nav
  // values read back 1e-9 m apart land within a millimetre (the prior of the
  // adjustment, whose sigma is a metre).
  EXPECT_LT(((back * b.alignment.x_gM).translation() - a.alignment.x_gM.translation()).norm(), 1e-3)
      << "the aligned model pose";
  ASSERT_EQ(a.adjustment.landmarks.size(), b.adjustment.landmarks.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.adjustment.landmarks.size(); ++i) {
    ASSERT_EQ(a.adjustment.landmarks[i].id, b.adjustment.landmarks[i].id);
    worst = std::max(worst, (b.adjustment.landmarks[i].p - kShift - a.adjustment.landmarks[i].p).norm());
    worst = std::max(worst, std::abs(b.adjustment.landmarks[i].deviation - a.adjustment.landmarks[i].deviation));
  }
  EXPECT_LT(worst, 1e-4) << "landmarks (m) of the shifted demo against the unshifted";
  EXPECT_LT((b.adjustment.x_s_cT - a.adjustment.x_s_cT).norm(), 1e-6) << "the camera extrinsic";

  ASSERT_TRUE(a.mapping && b.mapping);
  ASSERT_EQ(a.mapping->objects.size(), b.mapping->objects.size());
  ASSERT_GT(a.mapping->objects.size(), 5u);
  for (std::size_t i = 0; i < a.mapping->objects.size(); ++i) {
    const DetectedObject &p = a.mapping->objects[i], &q = b.mapping->objects[i];
    EXPECT_EQ(p.id, q.id);
    EXPECT_LT((p.centroid_m - q.centroid_m).norm(), 1e-4) << p.id;
    EXPECT_NEAR(p.max_height, q.max_height, 1e-4) << p.id;
    EXPECT_NEAR(p.mean_height, q.mean_height, 1e-4) << p.id;
    EXPECT_NEAR(p.area, q.area, 1e-4) << p.id;
  }
}

}  // namespace
}  // namespace hull
