// The simulator's truth is consistent with what it observed: projecting true
// landmarks with true poses gives the observed pixels within the noise, true
// DVL ranges equal ray casts, no observed landmark is occluded or outside the
// image; every preset passes the independent contract checker.
#include "simulate/survey_simulator.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "geometry/mesh_index.h"
#include "survey/survey_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

const SimulatedSurvey& Demo(const std::string& preset) {
  static std::unordered_map<std::string, SimulatedSurvey> cache;
  auto it = cache.find(preset);
  if (it == cache.end()) {
    NullProgress p;
    it = cache.emplace(preset, SimulateSurvey(SurveyPreset(preset), p)).first;
  }
  return it->second;
}

class Simulator : public ::testing::TestWithParam<std::string> {};

TEST_P(Simulator, ProjectionsOfTruthMatchObservationsWithinNoise) {
  const SimulatedSurvey& s = Demo(GetParam());
  const SurveyBundle& b = s.bundle;
  const auto kf = b.KeyframeIndex();
  std::unordered_map<std::int64_t, Eigen::Vector3d> truth;
  for (const auto& l : b.truth->landmarks) truth[l.landmark] = l.p;
  std::unordered_set<std::uint64_t> wrong;
  for (const auto& [k, l] : s.wrong_matches) wrong.insert(static_cast<std::uint64_t>(k) << 32 | l);
  const Pose x_s_cT = Pose::FromVector(b.truth->x_s_cT);
  const Pose x_cT_cB = Pose::FromVector(b.manifest.camera.top_to_bottom);
  double sum2 = 0;
  std::size_t n = 0, wrong_seen = 0;
  const double sigma = b.manifest.noise.pixel_sigma;
  for (const auto& f : b.features) {
    const auto& tp = b.truth->poses[static_cast<std::size_t>(kf.at(f.keyframe))];
    const Pose g_cT = Pose::FromVector(tp.x_gv) * b.manifest.VehicleToServo(tp.servo) * x_s_cT;
    const Eigen::Vector3d pc = g_cT.Inverse() * truth.at(f.landmark);
    ASSERT_GT(pc.z(), 0.0);
    const Eigen::Vector2d uv = b.manifest.camera.top.Project(pc);
    ASSERT_TRUE(b.manifest.camera.InImage(f.top));
    ASSERT_TRUE(b.manifest.camera.InImage(uv));
    const double err = (uv - f.top).norm();
    if (wrong.count(static_cast<std::uint64_t>(f.keyframe) << 32 | f.landmark)) {
      EXPECT_GT(err, 25.0);
      ++wrong_seen;
      continue;
    }
    EXPECT_LT(err, 3.5 * sigma * std::sqrt(2.0) + 1e-9);
    sum2 += (uv - f.top).squaredNorm();
    n += 2;
    if (f.has_bottom) {
      const Eigen::Vector2d ub = b.manifest.camera.bottom.Project((g_cT * x_cT_cB).Inverse() * truth.at(f.landmark));
      EXPECT_LT((ub - f.bottom).norm(), 3.5 * sigma * std::sqrt(2.0) + 1e-9);
    }
  }
  const double rms = std::sqrt(sum2 / static_cast<double>(n));
  EXPECT_NEAR(rms, sigma, 0.1 * sigma);
  if (b.manifest.camera.stereo()) {
    EXPECT_EQ(wrong_seen, 0u);
  } else {
    const double frac = static_cast<double>(wrong_seen) / static_cast<double>(b.features.size());
    EXPECT_GT(frac, 0.02);
    EXPECT_LT(frac, 0.04);
  }
}

TEST_P(Simulator, ObservedLandmarksAreVisibleAndSeenTwice) {
  const SimulatedSurvey& s = Demo(GetParam());
  const SurveyBundle& b = s.bundle;
  TriangleMesh surface = s.cad;
  for (const auto& m : s.object_meshes) surface.Append(m);
  const MeshIndex index(surface);
  const Pose x_Mg = Pose::FromVector(b.truth->x_gM).Inverse();
  const Pose x_s_cT = Pose::FromVector(b.truth->x_s_cT);
  const auto kf = b.KeyframeIndex();
  std::unordered_map<std::int64_t, Eigen::Vector3d> truth;
  for (const auto& l : b.truth->landmarks) truth[l.landmark] = l.p;
  std::unordered_map<std::int64_t, int> views;
  int occluded = 0;
  for (std::size_t i = 0; i < b.features.size(); i += 3) {  // every third observation keeps the test quick
    const auto& f = b.features[i];
    const auto& tp = b.truth->poses[static_cast<std::size_t>(kf.at(f.keyframe))];
    const Pose g_cT = Pose::FromVector(tp.x_gv) * b.manifest.VehicleToServo(tp.servo) * x_s_cT;
    const Eigen::Vector3d c = x_Mg * g_cT.translation(), p = x_Mg * truth.at(f.landmark);
    const double d = (p - c).norm();
    occluded += index.Raycast(c, (p - c) / d, d - 1e-3).hit;
  }
  for (const auto& f : b.features) ++views[f.landmark];
  EXPECT_EQ(occluded, 0);
  EXPECT_EQ(views.size(), b.truth->landmarks.size());
  for (const auto& [id, v] : views) EXPECT_GE(v, 2) << "landmark " << id;
}

TEST_P(Simulator, DvlRangesEqualRaycastsOfTheTrueSurface) {
  const SimulatedSurvey& s = Demo(GetParam());
  const SurveyBundle& b = s.bundle;
  TriangleMesh surface = s.cad;
  for (const auto& m : s.object_meshes) surface.Append(m);
  const MeshIndex index(surface);
  const Pose x_Mg = Pose::FromVector(b.truth->x_gM).Inverse();
  const Pose x_s_d = Pose::FromVector(b.manifest.servo_to_dvl);
  double sum2 = 0;
  int n = 0;
  for (std::size_t k = 0; k < b.dvl.size(); ++k) {
    const auto& tp = b.truth->poses[k];
    const Pose g_d = Pose::FromVector(tp.x_gv) * b.manifest.VehicleToServo(tp.servo) * x_s_d;
    for (int beam = 0; beam < 4; ++beam) {
      const RayHit hit =
          index.Raycast(x_Mg * g_d.translation(), x_Mg.Rotate(g_d.Rotate(b.manifest.BeamDirection(beam))), 30.0);
      const double r = b.dvl[k].range[beam];
      if (!DvlRecord::HasReturn(r)) continue;  // drop-outs are allowed where there is a hit
      ASSERT_TRUE(hit.hit);
      EXPECT_LT(std::abs(r - hit.range), 4 * b.manifest.noise.dvl_range_sigma + 1e-9);
      sum2 += (r - hit.range) * (r - hit.range);
      ++n;
    }
  }
  ASSERT_GT(n, 100);
  EXPECT_NEAR(std::sqrt(sum2 / n), b.manifest.noise.dvl_range_sigma, 0.1 * b.manifest.noise.dvl_range_sigma);
}

TEST_P(Simulator, ShapeOfTheDemoSurvey) {
  const SurveyBundle& b = Demo(GetParam()).bundle;
  EXPECT_GE(b.nav.size(), 200u);
  EXPECT_LE(b.nav.size(), 400u);
  EXPECT_GE(b.truth->landmarks.size(), 1000u);
  std::unordered_set<std::string> with_features;
  for (const auto& l : b.truth->landmarks) with_features.insert(l.object);
  for (const auto& o : b.truth->objects) EXPECT_TRUE(with_features.count(o.id)) << o.id << " carries no features";
  // The model-pose guess is wrong by tens of centimetres and a few degrees.
  const Pose truth = Pose::FromVector(b.truth->x_gM), guess = Pose::FromVector(*b.manifest.model_pose_guess);
  const double deg = Pose::AngleBetween(truth, guess) * 180 / M_PI;
  EXPECT_GT(deg, 1.0);
  EXPECT_LT(deg, 4.0);
}

TEST_P(Simulator, DeterministicFromTheSeed) {
  NullProgress p;
  SurveySimulationOptions o = SurveyPreset(GetParam());
  const SimulatedSurvey a = SimulateSurvey(o, p);
  const SurveyBundle& b = Demo(GetParam()).bundle;
  ASSERT_EQ(a.bundle.features.size(), b.features.size());
  for (std::size_t i = 0; i < b.features.size(); ++i) ASSERT_EQ(a.bundle.features[i].top, b.features[i].top);
  EXPECT_EQ(a.bundle.nav.back().x_gv, b.nav.back().x_gv);
  o.seed = 2;
  EXPECT_NE(SimulateSurvey(o, p).bundle.nav.back().x_gv, b.nav.back().x_gv);
}

// The independent reading of the contract: ../shared/tools/check-bundle.py.
TEST_P(Simulator, WrittenBundlePassesTheContractChecker) {
  const std::string script = std::string(HI_SHARED_DATA_DIR) + "/../tools/check-bundle.py";
  if (!fs::exists(script)) GTEST_SKIP() << "contract checker not found at " << script;
  if (std::system("/usr/bin/python3 -c 'import numpy' 2>/dev/null") != 0) {
    GTEST_SKIP() << "python3-numpy is not installed";
  }
  const std::string dir = (fs::path(::testing::TempDir()) / ("hi_sim_" + GetParam())).string();
  fs::remove_all(dir);
  fs::remove_all(dir + ".gen");
  WriteSimulatedSurvey(Demo(GetParam()), dir, true);
  EXPECT_TRUE(ValidateSurveyBundle(dir).empty());
  const std::string cmd = "/usr/bin/python3 " + script + " --contract --quiet " + dir + " > " + dir + ".log 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << "check-bundle.py failed; see " << dir << ".log";
}

INSTANTIATE_TEST_SUITE_P(Presets, Simulator, ::testing::Values("demo", "mono"));

}  // namespace
}  // namespace hull
