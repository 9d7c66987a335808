// The underwater image renderer's physics on a flat plate, through its
// noise-free signal: inverse-square fall-off and Lambert's cosine from the
// strobe, Beer-Lambert attenuation, the backscatter veil, vignetting, and
// shot plus read noise with the right spread. Small images, milliseconds.
#include "simulate/image_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "base/error.h"
#include "simulate/true_scene.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

// A 4 m x 4 m plate in z = 0 centred on the origin, rotated by `tilt_deg`
// about the y axis through the origin. The albedo's up axis is y, so the
// hull texture treats the plate as a side at every tilt (its texture at the
// origin does not depend on the tilt).
std::unique_ptr<TrueScene> Plate(double tilt_deg, double x_offset = 0) {
  TriangleMesh m = test::MakeGrid(8, 8, 0.5);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (auto& v : m.vertices) v = R * (v - Eigen::Vector3d(2, 2, 0)) + Eigen::Vector3d(x_offset, 0, 0);
  return std::make_unique<TrueScene>(m, std::vector<TriangleMesh>{}, std::vector<TrueObject>{},
                                     SurfaceAlbedo(7, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()));
}

// A narrow camera (footprint well under a millimetre at these ranges, so
// every texture octave is resolved at every range and the albedo at the
// plate's origin is the same in every test) with one strobe at its centre
// looking along its axis; no noise, no water unless a test adds it.
struct PlateRig {
  PinholeIntrinsics k;
  int size = 9;
  UnderwaterImagingOptions o;
  PlateRig() {
    k.fx = k.fy = 6000;
    k.cx = k.cy = 4;
    o.attenuation = 0;
    o.backscatter = 0;
    o.strobes = {Strobe{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 40.0, 1.0}};
    o.read_noise = 0;
    o.full_well = 1e12;
    o.exposure_range = 2.0;
    o.exposure_level = 0.05;  // albedo 0.9 at 1 m stays below full scale
  }
  UnderwaterCamera Camera() const { return UnderwaterCamera(k, size, size, o.strobes, o); }
};

// The camera at distance d in front of the plate's origin, looking at it.
Pose Looking(double d) { return Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, -d)); }

float CentreSignal(const UnderwaterCamera& cam, const TrueScene& scene, const Pose& x_Mc, cv::Mat* image = nullptr) {
  cv::Mat signal;
  const cv::Mat im = cam.Render(scene, x_Mc, 1, nullptr, &signal);
  if (image) *image = im;
  return signal.at<float>(4, 4);
}

TEST(UnderwaterRenderer, CentreRayHitsThePlateOrigin) {
  const auto scene = Plate(0);
  const PlateRig s;
  const RayHit h = s.Camera().SurfaceAt(*scene, Looking(1.5), 4, 4);
  ASSERT_TRUE(h.hit);
  EXPECT_LT(h.point.norm(), 1e-9);
  EXPECT_NEAR(h.range, 1.5, 1e-9);
}

TEST(UnderwaterRenderer, InverseSquareFalloffFromTheStrobe) {
  const auto scene = Plate(0);
  const PlateRig s;
  const UnderwaterCamera cam = s.Camera();
  const float near = CentreSignal(cam, *scene, Looking(1.0));
  ASSERT_GT(near, 0.005f);
  for (double d : {1.5, 2.0, 3.0}) EXPECT_NEAR(CentreSignal(cam, *scene, Looking(d)) / near, 1.0 / (d * d), 1e-4) << d;
}

TEST(UnderwaterRenderer, GainSetsTheExposureOfAlbedoOneHalfAtTheExposureRange) {
  // The plate's albedo at its origin, then the signal the gain promises for it.
  const auto scene = Plate(0);
  PlateRig s;
  s.o.attenuation = 0.3;
  const float rho = scene->AlbedoAt(Eigen::Vector3d::Zero());
  ASSERT_GT(rho, 0.03f);
  const float signal = CentreSignal(s.Camera(), *scene, Looking(s.o.exposure_range));
  EXPECT_NEAR(signal, s.o.exposure_level * rho / 0.5, 1e-4 * s.o.exposure_level);
}

TEST(UnderwaterRenderer, LambertCosineOfTheIncidence) {
  const PlateRig s;
  const UnderwaterCamera cam = s.Camera();
  const float facing = CentreSignal(cam, *Plate(0), Looking(1.5));
  for (double tilt : {30.0, 60.0, -45.0}) {
    EXPECT_NEAR(CentreSignal(cam, *Plate(tilt), Looking(1.5)) / facing, std::cos(tilt * M_PI / 180), 1e-4) << tilt;
  }
}

TEST(UnderwaterRenderer, BeerLambertAttenuationOnBothPaths) {
  // The strobe sits at the camera: light travels 2 d through the water. The
  // fixed gain cancels the exposure range's share, so compare two ranges.
  const auto scene = Plate(0);
  PlateRig s;
  s.o.attenuation = 0.4;
  const UnderwaterCamera cam = s.Camera();
  const float a = CentreSignal(cam, *scene, Looking(1.0)), b = CentreSignal(cam, *scene, Looking(2.5));
  EXPECT_NEAR(b / a, std::exp(-2 * 0.4 * 1.5) / (2.5 * 2.5), 1e-4);
}

TEST(UnderwaterRenderer, VignettingIsCosineToTheFourth) {
  const auto scene = Plate(0);
  PlateRig s;
  s.k.fx = s.k.fy = 8;  // wide: the corner pixel is 29 degrees off the axis
  s.o.strobes[0].half_power_angle_deg = 80;
  cv::Mat with, without;
  s.Camera().Render(*scene, Looking(1.5), 1, nullptr, &with);
  s.o.vignetting = 0;
  s.Camera().Render(*scene, Looking(1.5), 1, nullptr, &without);
  for (int v : {0, 4, 8}) {
    for (int u : {0, 2, 4, 8}) {
      const double x = (u - 4) / 8.0, y = (v - 4) / 8.0, cos2 = 1 / (1 + x * x + y * y);
      ASSERT_GT(without.at<float>(v, u), 0.0f);
      EXPECT_NEAR(with.at<float>(v, u) / without.at<float>(v, u), cos2 * cos2, 1e-5) << u << "," << v;
    }
  }
}

TEST(UnderwaterRenderer, BackscatterVeilAddsLightThatGrowsWithRange) {
  // Nothing but water in view (the plate is beyond max_range): the veil alone.
  const auto scene = Plate(0);
  PlateRig s;
  s.o.attenuation = 0.3;
  s.o.backscatter = 0.002;
  const float open_water = CentreSignal(s.Camera(), *scene, Looking(s.o.max_range + 1));
  EXPECT_GT(open_water, 0.0f);
  s.o.backscatter = 0.004;
  EXPECT_NEAR(CentreSignal(s.Camera(), *scene, Looking(s.o.max_range + 1)), 2 * open_water, 1e-3 * open_water);
  // In front of the plate, the veil of the water up to the plate adds to
  // the plate's light; a nearer plate has less water in front of it.
  s.o.backscatter = 0.002;
  const UnderwaterCamera veiled = s.Camera();
  s.o.backscatter = 0;
  const UnderwaterCamera clear = s.Camera();
  const float veil_near = CentreSignal(veiled, *scene, Looking(1.0)) - CentreSignal(clear, *scene, Looking(1.0));
  const float veil_far = CentreSignal(veiled, *scene, Looking(3.0)) - CentreSignal(clear, *scene, Looking(3.0));
  EXPECT_GT(veil_near, 0.0f);
  EXPECT_GT(veil_far, veil_near);
  EXPECT_LT(veil_far, open_water);
}

TEST(UnderwaterRenderer, ShotAndReadNoiseHaveThePhotonSpread) {
  // A wide view of the plate: each pixel's deviation from its noise-free
  // signal, in electrons, over sqrt(signal electrons + read^2) is N(0, 1).
  const auto scene = Plate(0);
  PlateRig s;
  s.size = 64;
  s.k.fx = s.k.fy = 60;
  s.k.cx = s.k.cy = 31.5;
  s.o.full_well = 2000;
  s.o.read_noise = 12;
  s.o.exposure_level = 0.3;
  s.o.strobes[0].half_power_angle_deg = 80;
  const UnderwaterCamera cam = UnderwaterCamera(s.k, s.size, s.size, s.o.strobes, s.o);
  cv::Mat signal;
  const cv::Mat image = cam.Render(*scene, Looking(1.5), 42, nullptr, &signal);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int v = 0; v < s.size; ++v) {
    for (int u = 0; u < s.size; ++u) {
      const double e = signal.at<float>(v, u) * s.o.full_well;
      if (e < 50 || e > 0.9 * s.o.full_well) continue;  // clipped at 0 or 255
      const double z = (image.at<std::uint8_t>(v, u) / 255.0 * s.o.full_well - e) / std::sqrt(e + 144.0);
      sum += z;
      sum2 += z * z;
      ++n;
    }
  }
  ASSERT_GT(n, 2000);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.08);
  EXPECT_NEAR(sd, 1.0, 0.06);  // 8-bit quantisation adds under 1 % at these levels
  // Same seed, same image; another seed, other noise.
  EXPECT_EQ(cv::norm(image, cam.Render(*scene, Looking(1.5), 42), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(image, cam.Render(*scene, Looking(1.5), 43), cv::NORM_L1), 0.0);
}

TEST(UnderwaterRenderer, OptionsAreChecked) {
  UnderwaterImagingOptions o;
  EXPECT_NO_THROW(o.Check());
  o.attenuation = -1;
  EXPECT_THROW(o.Check(), OptionError);
  o = UnderwaterImagingOptions();
  o.strobes.clear();
  EXPECT_THROW(o.Check(), OptionError);
  o = UnderwaterImagingOptions();
  o.max_range = 1.0;
  EXPECT_THROW(o.Check(), OptionError);
}

// The albedo along an image row (SurfaceAlbedo::HullRow, the coarse texture
// interpolated between every 6th point) against the exact batch: equal at
// the anchors, within 0.01 everywhere (mean under 0.001) on a row of 1.5 mm
// steps across a curved hull side and a flat bottom with a jump between;
// exactly equal where the steps are too long to interpolate (1 cm).
TEST(SurfaceAlbedoRow, InterpolatedCoarseTextureStaysCloseToTheExactAlbedo) {
  const SurfaceAlbedo albedo(11, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  for (const double step : {0.0015, 0.01}) {
    std::vector<float> px, py, pz, nx, ny, nz, fp;
    for (int i = 0; i < 1360; ++i) {
      Eigen::Vector3d p, n;
      if (i < 700) {  // a side curving away: radius 3 m about the x axis
        const double a = i * step / 3.0;
        p = Eigen::Vector3d(5.0 + 0.3 * i * step, 3.0 * std::sin(a), -3.0 * std::cos(a));
        n = Eigen::Vector3d(0, std::sin(a), -std::cos(a));
      } else {  // a flat bottom 40 cm away
        p = Eigen::Vector3d(5.4 + i * step, 0.2 * i * step, -3.4);
        n = -Eigen::Vector3d::UnitZ();
      }
      px.push_back(static_cast<float>(p.x()));
      py.push_back(static_cast<float>(p.y()));
      pz.push_back(static_cast<float>(p.z()));
      nx.push_back(static_cast<float>(n.x()));
      ny.push_back(static_cast<float>(n.y()));
      nz.push_back(static_cast<float>(n.z()));
      fp.push_back(static_cast<float>(step));
    }
    const int n = static_cast<int>(px.size());
    std::vector<float> exact(px.size()), row(px.size());
    albedo.HullBatch(px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), fp.data(), n, exact.data());
    albedo.HullRow(px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), fp.data(), n, row.data());
    double max_diff = 0, sum_diff = 0;
    int differing = 0;
    for (int i = 0; i < n; ++i) {
      const double d = std::abs(row[static_cast<std::size_t>(i)] - exact[static_cast<std::size_t>(i)]);
      if (i % 6 == 0 || i == n - 1) {
        EXPECT_EQ(d, 0.0) << "anchor " << i;
      }
      max_diff = std::max(max_diff, d);
      sum_diff += d;
      differing += d > 0;
    }
    if (step > 0.005) {
      EXPECT_EQ(max_diff, 0.0) << "steps too long to interpolate";
    } else {                        // measured: max 0.0043, mean 0.00006, 1077 of 1360 points differ
      EXPECT_GT(differing, n / 2);  // interpolated
      EXPECT_LT(max_diff, 0.01);
      EXPECT_LT(sum_diff / n, 0.001);
    }
  }
}

// The object albedo in batches (as the renderer shades object pixels) is
// exactly the one-point albedo, for every material, at several footprints.
TEST(SurfaceAlbedoRow, ObjectBatchIsTheOnePointAlbedo) {
  const SurfaceAlbedo albedo(5, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  std::vector<TrueObject> kinds(3);
  kinds[0].kind = ObjectKind::kPatch;
  kinds[1].kind = ObjectKind::kCylinder;
  kinds[2].kind = ObjectKind::kBox;
  for (TrueObject& o : kinds) {
    o.center = Eigen::Vector3d(1, 2, 3);
    o.radius = 0.1;
    o.height = 0.05;
    o.size = Eigen::Vector3d(0.2, 0.1, 0.05);
  }
  std::vector<const TrueObject*> objects;
  std::vector<float> px, py, pz, nx, ny, nz, fp;
  for (int i = 0; i < 37; ++i) {  // more than two batches of 16
    objects.push_back(&kinds[static_cast<std::size_t>(i % 3)]);
    px.push_back(1.0f + 0.003f * static_cast<float>(i));
    py.push_back(2.0f - 0.002f * static_cast<float>(i));
    pz.push_back(3.0f + 0.001f * static_cast<float>(i % 5) * 0.03f);
    const bool top = i % 2 == 0;
    nx.push_back(top ? 0.0f : 1.0f);
    ny.push_back(0.0f);
    nz.push_back(top ? 1.0f : 0.0f);
    fp.push_back(i % 4 == 0 ? 0.0f : 0.0005f * static_cast<float>(i % 7));
  }
  const int n = static_cast<int>(px.size());
  std::vector<float> out(px.size());
  albedo.ObjectBatch(objects.data(), px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), fp.data(), n,
                     out.data());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const float one =
        albedo.OnObject(*objects[i], Eigen::Vector3f(px[i], py[i], pz[i]), Eigen::Vector3f(nx[i], ny[i], nz[i]), fp[i]);
    EXPECT_EQ(out[i], one) << i;
  }
}

}  // namespace
}  // namespace hull
