// The acoustic image simulator: visibility and shadows from the scene,
// returns where the geometry puts them, surfaces continuous in range,
// speckle with the right mean, determinism, and the sequences it writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <set>

#include "base/error.h"
#include "simulate/sonar_image_simulator.h"
#include "sonar/acoustic_camera.h"

namespace hull {
namespace {

struct SceneSetup {
  SonarLayout layout;
  SonarScene scene;
  SonarImageFormat format;
};

SceneSetup Make(SonarPreset preset) {
  SonarSimulationOptions o;
  o.preset = preset;
  SceneSetup s{MakeSonarLayout(o), {}, {}};
  s.scene = MakeSonarScene(s.layout, preset);
  return s;
}

// No speckle, no fluctuation, no noise: the deterministic part of the model.
SonarRenderOptions Clean() {
  SonarRenderOptions r;
  r.speckle_looks = 1000;
  r.point_looks = 1000;
  r.noise_level = 0;
  return r;
}

TEST(SonarRenderer, OptionsCheckNamesTheField) {
  SonarRenderOptions r;
  std::string why;
  EXPECT_TRUE(r.Check(&why));
  r.elevation_rays = 1;
  EXPECT_FALSE(r.Check(&why));
  EXPECT_EQ(why.rfind("elevation_rays:", 0), 0u) << why;
  r = SonarRenderOptions();
  r.speckle_looks = 0;
  EXPECT_FALSE(r.Check(&why));
  EXPECT_EQ(why.rfind("speckle_looks:", 0), 0u) << why;
  SonarSceneOptions so;
  so.vertex_strength = -1;
  EXPECT_FALSE(so.Check(&why));
  EXPECT_EQ(why.rfind("vertex_strength:", 0), 0u) << why;
  const SceneSetup s = Make(SonarPreset::kPrism);
  r = SonarRenderOptions();
  r.dynamic_range_db = 0;
  EXPECT_THROW(SonarRenderer(s.scene, SonarSensor(), s.format, r), OptionError);
}

TEST(SonarRenderer, TheObjectHidesItsFarVertices) {
  // The paper's layout, first view: level, the prism's front face square to
  // the boresight, the sonar at mid height: the four front vertices show,
  // the four behind the front face do not.
  SceneSetup s = Make(SonarPreset::kPrism);
  const SonarRenderer r(s.scene, SonarSensor(), s.format);
  const Vector6d& pose = s.layout.poses[0];
  for (const Eigen::Vector3d& v : s.layout.object_vertices) {
    EXPECT_EQ(r.Sees(pose, v), v.x() < s.layout.centre.x()) << v.transpose();
  }
  // From above the object the top face and the near bottom edge show.
  s = Make(SonarPreset::kAbove);
  const SonarRenderer above(s.scene, SonarSensor(), s.format);
  int seen = 0;
  for (const Eigen::Vector3d& v : s.layout.object_vertices) {
    const bool far_bottom = v.x() > s.layout.centre.x() && v.z() > s.layout.centre.z();
    EXPECT_EQ(above.Sees(s.layout.poses[0], v), !far_bottom) << v.transpose();
    seen += above.Sees(s.layout.poses[0], v);
  }
  EXPECT_EQ(seen, 6);
  // Outside the field of view nothing is seen.
  EXPECT_FALSE(above.Sees(s.layout.poses[0], Eigen::Vector3d(0, 3, 0)));
}

TEST(SonarRenderer, VerticesShineAndTheObjectCastsAShadow) {
  const SceneSetup s = Make(SonarPreset::kTank);
  const SonarSensor sensor;
  const SonarRenderer r(s.scene, sensor, s.format, Clean());
  const Vector6d& pose = s.layout.poses[0];
  const cv::Mat I = r.RenderIntensity(pose, 1);
  ASSERT_EQ(I.rows, 512);
  ASSERT_EQ(I.cols, 128);
  std::vector<float> all(I.begin<float>(), I.end<float>());
  std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
  const double median = all[all.size() / 2];
  int visible = 0;
  for (const Eigen::Vector3d& v : s.layout.object_vertices) {
    if (!r.Sees(pose, v)) continue;
    ++visible;
    const Eigen::Vector3d polar = SonarPolarOf(pose, v);
    const int row = static_cast<int>(std::lround(s.format.RangeToRow(sensor, polar[0])));
    const int col = static_cast<int>(std::lround(s.format.AzimuthToColumn(sensor, polar[1])));
    double peak = 0;
    for (int a = row - 1; a <= row + 1; ++a) {
      for (int b = col - 1; b <= col + 1; ++b) peak = std::max(peak, static_cast<double>(I.at<float>(a, b)));
    }
    EXPECT_GT(peak, 1000 * median) << "vertex " << v.transpose();
  }
  EXPECT_EQ(visible, 6);  // the front face's four and the top face's far two
  // Behind the prism (its azimuth, 0.6 m beyond it) the floor is in shadow;
  // beside it, at the same range, it returns.
  const double behind = s.format.RangeToRow(sensor, SonarPolarOf(pose, s.layout.centre)[0] + 0.6);
  const int row = static_cast<int>(behind), centre = static_cast<int>(s.format.AzimuthToColumn(sensor, 0.0));
  double shadow = 0, lit = 0;
  for (int a = row - 5; a <= row + 5; ++a) {
    shadow += I.at<float>(a, centre);
    lit += I.at<float>(a, centre + 30) + I.at<float>(a, centre - 30);
  }
  EXPECT_LT(shadow, 0.01 * lit / 2);
}

TEST(SonarRenderer, SurfacesAreContinuousInRange) {
  // A beam away from the prism sees the floor from where the fan's lower
  // edge meets it to the far limit, in every bin between (no gaps between
  // the elevation rays' hits).
  const SceneSetup s = Make(SonarPreset::kTank);
  const SonarSensor sensor;
  SonarRenderOptions o = Clean();
  o.elevation_rays = 12;  // coarse: the gaps would show
  const SonarRenderer r(s.scene, sensor, s.format, o);
  const cv::Mat I = r.RenderIntensity(s.layout.poses[0], 1);
  const int col = 10;
  int first = -1, last = -1;
  for (int i = 0; i < I.rows; ++i) {
    if (I.at<float>(i, col) > 0) {
      if (first < 0) first = i;
      last = i;
    }
  }
  ASSERT_GE(first, 0);
  EXPECT_GT(last - first, 100);
  for (int i = first; i <= last; ++i) EXPECT_GT(I.at<float>(i, col), 0) << "row " << i;
}

TEST(SonarRenderer, SpeckleKeepsTheMeanAndSeedsRepeat) {
  const SceneSetup s = Make(SonarPreset::kTank);
  const SonarSensor sensor;
  SonarRenderOptions speckled = Clean();
  speckled.speckle_looks = 2;
  const SonarRenderer clean(s.scene, sensor, s.format, Clean());
  const SonarRenderer noisy(s.scene, sensor, s.format, speckled);
  const Vector6d& pose = s.layout.poses[0];
  const cv::Mat a = clean.RenderIntensity(pose, 1), b = noisy.RenderIntensity(pose, 1);
  // Gamma(2) speckle: mean 1 (sum within 2 %), relative variance 1/2.
  EXPECT_NEAR(cv::sum(b)[0] / cv::sum(a)[0], 1.0, 0.02);
  cv::Mat ratio;
  cv::divide(b, a, ratio);
  double n = 0, s1 = 0, s2 = 0;
  for (int i = 0; i < a.rows; ++i) {
    for (int j = 0; j < a.cols; ++j) {
      if (a.at<float>(i, j) <= 0) continue;
      const double x = ratio.at<float>(i, j);
      n += 1;
      s1 += x;
      s2 += x * x;
    }
  }
  ASSERT_GT(n, 1000);
  const double mean = s1 / n;
  EXPECT_NEAR(s2 / n - mean * mean, 0.5, 0.05);
  // The same seed gives the same image, another seed another.
  EXPECT_EQ(cv::norm(noisy.Render(pose, 7), noisy.Render(pose, 7), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(noisy.Render(pose, 7), noisy.Render(pose, 8), cv::NORM_L1), 0.0);
}

TEST(SonarRenderer, AbsorptionDimsTheFarField) {
  const SceneSetup s = Make(SonarPreset::kTank);
  const SonarSensor sensor;
  SonarRenderOptions lossy = Clean();
  lossy.absorption_db_per_m = 3;
  const SonarRenderer a(s.scene, sensor, s.format, Clean()), b(s.scene, sensor, s.format, lossy);
  const cv::Mat Ia = a.RenderIntensity(s.layout.poses[0], 1), Ib = b.RenderIntensity(s.layout.poses[0], 1);
  // Per row (range) the ratio is 10^(-2 (3 - 0.4) r / 10).
  for (int row : {150, 300, 450}) {
    const double r = s.format.RowToRange(sensor, row);
    const double sa = cv::sum(Ia.row(row))[0], sb = cv::sum(Ib.row(row))[0];
    if (sa <= 0) continue;
    EXPECT_NEAR(sb / sa, std::pow(10.0, -2 * (3 - 0.4) * r / 10), 0.1 * sb / sa) << "row " << row;
  }
}

TEST(SonarImageSimulation, MeasurementsAreTheVerticesEachImageShows) {
  for (const char* preset : {"prism", "tank", "above"}) {
    SonarImageSimulationOptions o = SonarImagePreset(preset, 4);
    o.sequence.num_steps = o.sequence.preset == SonarPreset::kTank ? 8 : 9;
    const SonarImageSimulation sim = SimulateSonarImages(o);
    const AcousticSequence& seq = sim.sequence;
    ASSERT_TRUE(seq.image.has_value());
    ASSERT_EQ(static_cast<int>(sim.images.size()), seq.num_steps());
    EXPECT_EQ(sim.images[0].type(), CV_8UC1);
    EXPECT_EQ(sim.images[0].rows, 512);
    ASSERT_EQ(seq.truth->features.size(), 8u) << preset;
    const SonarLayout layout = MakeSonarLayout(o.sequence);
    for (std::size_t i = 0; i < layout.features.size(); ++i) {
      EXPECT_EQ(seq.truth->features[i], layout.features[i]) << preset << ": the preset's features keep their ids";
    }
    const SonarRenderer r(sim.scene, seq.sensor, *seq.image);
    std::set<std::pair<std::int64_t, std::int64_t>> measured;
    for (const SonarMeasurement& m : seq.measurements) measured.insert({m.step, m.feature});
    int shown = 0;
    for (int k = 0; k < seq.num_steps(); ++k) {
      for (std::size_t i = 0; i < 8; ++i) {
        const bool sees = r.Sees(seq.truth->poses[static_cast<std::size_t>(k)], seq.truth->features[i]);
        shown += sees;
        // A noisy measurement may fall outside the limits and be dropped.
        if (!sees) {
          EXPECT_EQ(measured.count({k, static_cast<std::int64_t>(i)}), 0u) << preset << " step " << k;
        }
      }
    }
    EXPECT_GE(static_cast<int>(measured.size()), shown - 2) << preset;
    EXPECT_LT(shown, 8 * seq.num_steps()) << preset << ": some vertex is hidden somewhere";
  }
}

}  // namespace
}  // namespace hull
