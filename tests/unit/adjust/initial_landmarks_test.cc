// Landmarks triangulated from the initial poses far off the prior mesh
// (AdjustmentOptions::max_initial_deviation): a monocular track of two views
// whose second match lies on the epipolar line at the wrong depth
// triangulates exactly, metres off the hull, and no reprojection error
// reveals it. On the rendered mono survey about 200 such points turned the
// adjusted model 95 degrees about the surveyed stretch of flat bottom
// (docs/benchmarks.md, "From images end to end").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "adjust/adjust_result.h"
#include "adjust/bundle_adjuster.h"
#include "base/progress.h"
#include "results/adjustment_files.h"
#include "simulate/survey_simulator.h"
#include "support/test_surveys.h"

namespace hull {
namespace {

struct Planted {
  SimulatedSurvey survey;
  std::set<std::int64_t> wrong;  // ids of the planted tracks
  SurveyBundle clean;            // the bundle before planting
};

// The small survey seen by one camera, without initial landmark positions
// (the adjustment triangulates them from the navigation prior, as for the
// front end's tracks), and a wrong two-view track planted for every
// `every`-th landmark: its first view's pixel, and in the next keyframe that
// sees the landmark the projection of the point `depth` m along that pixel's
// ray (beyond the hull), both through the initial camera poses.
Planted PlantWrongTracks(int every, double depth) {
  SurveySimulationOptions so = test::SmallSurveyOptions();
  so.camera = CameraType::kMono;
  so.wrong_match_fraction = 0;
  NullProgress quiet;
  Planted out;
  out.survey = SimulateSurvey(so, quiet);
  SurveyBundle& b = out.survey.bundle;
  b.landmarks.reset();
  out.clean = b;
  const auto kf = b.KeyframeIndex();
  const Pose x_s_cT = Pose::FromVector(b.manifest.camera.servo_to_top);
  auto camera = [&](std::int64_t keyframe) {
    const NavRecord& n = b.nav[static_cast<std::size_t>(kf.at(keyframe))];
    return Pose::FromVector(n.x_gv) * b.manifest.VehicleToServo(n.servo) * x_s_cT;
  };
  std::unordered_map<std::int64_t, std::vector<const FeatureObservation*>> views;
  for (const FeatureObservation& f : b.features) views[f.landmark].push_back(&f);
  std::int64_t next_id = 0;
  for (const auto& [id, list] : views) next_id = std::max(next_id, id + 1);
  std::vector<std::int64_t> ids;
  for (const auto& [id, list] : views) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  const PinholeIntrinsics& k = b.manifest.camera.top;
  std::vector<FeatureObservation> added;
  for (std::size_t i = 0; i < ids.size(); i += static_cast<std::size_t>(every)) {
    const auto& list = views[ids[i]];
    if (list.size() < 2) continue;
    const FeatureObservation& a = *list[0];
    const FeatureObservation& c = *list[1];
    const Eigen::Vector3d q = camera(a.keyframe) * (k.Unproject(a.top) * depth);
    const Eigen::Vector3d in_c = camera(c.keyframe).Inverse() * q;
    if (in_c.z() < 0.5) continue;
    const Eigen::Vector2d uv = k.Project(in_c);
    if (uv.x() < 0 || uv.y() < 0 || uv.x() > b.manifest.camera.width || uv.y() > b.manifest.camera.height) continue;
    FeatureObservation fa = a, fc = c;
    fa.landmark = fc.landmark = next_id;
    fc.top = uv;
    added.push_back(fa);
    added.push_back(fc);
    out.wrong.insert(next_id++);
  }
  b.features.insert(b.features.end(), added.begin(), added.end());
  return out;
}

TEST(InitialLandmarks, TracksTriangulatedFarOffTheMeshAreLeftOut) {
  const Planted p = PlantWrongTracks(8, 4.0);
  ASSERT_GE(p.wrong.size(), 20u);
  const Pose guess = Pose::FromVector(*p.survey.bundle.manifest.model_pose_guess);
  NullProgress quiet;
  AdjustmentOptions o;
  o.covariance = CovarianceMethod::kNone;
  o.num_threads = 2;
  ASSERT_GT(o.max_initial_deviation, 0);
  const AdjustmentResult limited = RunAdjustment(p.survey.bundle, p.survey.cad, guess, o, quiet);
  AdjustmentOptions off = o;
  off.max_initial_deviation = 0;
  const AdjustmentResult unlimited = RunAdjustment(p.survey.bundle, p.survey.cad, guess, off, quiet);
  const AdjustmentResult clean = RunAdjustment(p.clean, p.survey.cad, guess, o, quiet);

  auto planted_kept = [&](const AdjustmentResult& r) {
    int n = 0;
    for (const LandmarkEstimate& l : r.landmarks) n += static_cast<int>(p.wrong.count(l.id));
    return n;
  };
  auto moved = [&](const AdjustmentResult& r) {
    return Pose::DistanceBetween(Pose::FromVector(r.x_gM), Pose::FromVector(clean.x_gM));
  };
  std::printf(
      "planted %zu; kept with the limit %d (left out %d), without %d; model pose %.2e vs %.2e m from the "
      "clean survey's\n",
      p.wrong.size(), planted_kept(limited), limited.num_landmarks_off_model, planted_kept(unlimited), moved(limited),
      moved(unlimited));
  // Every planted track is left out, and nothing else: the true tracks start
  // within centimetres of the mesh.
  EXPECT_EQ(planted_kept(limited), 0);
  EXPECT_EQ(limited.num_landmarks_off_model, static_cast<int>(p.wrong.size()));
  EXPECT_EQ(clean.num_landmarks_off_model, 0);
  EXPECT_EQ(limited.landmarks.size(), clean.landmarks.size());
  // So the adjustment is the clean survey's; left in, they move the model pose.
  EXPECT_LT(moved(limited), 1e-5);
  EXPECT_EQ(unlimited.num_landmarks_off_model, 0);
  EXPECT_GT(planted_kept(unlimited), 0);
  EXPECT_GT(moved(unlimited), 1e-3);
  // adjustment.json keeps the count and the limit.
  const std::string dir = (std::filesystem::path(::testing::TempDir()) / "hi_initial_landmarks").string();
  WriteAdjustmentResult(limited, dir);
  const AdjustmentResult back = ReadAdjustmentResult(dir);
  EXPECT_EQ(back.num_landmarks_off_model, limited.num_landmarks_off_model);
  EXPECT_EQ(back.options.max_initial_deviation, o.max_initial_deviation);
}

TEST(InitialLandmarks, MaxInitialDeviationMustBeFiniteAndNotNegative) {
  AdjustmentOptions o;
  o.max_initial_deviation = -1;
  EXPECT_THROW(o.Check(), OptionError);
  o.max_initial_deviation = std::nan("");
  EXPECT_THROW(o.Check(), OptionError);
  o.max_initial_deviation = 0;
  EXPECT_NO_THROW(o.Check());
}

}  // namespace
}  // namespace hull
