// The 3-D photomosaic (core/mosaic):
// - the atlas: every UV in [0, 1], and the texture sampled back at a point
//   of a face equals the source image at the point's projection (raw
//   values, hard seams, so the atlas holds the image itself);
// - visibility: a plate between the nearest camera and part of a plane
//   hides that part from it, and no face is ever textured from a camera
//   whose line of sight the plate blocks (checked analytically here); the
//   visibility stage's culled search (centroid grid, frustum) finds exactly
//   what the candidate rule applied to every (view, face) pair finds, on a
//   stereo rig with mount, servo, extrinsic and model pose;
// - colour: on a small rendered survey (the underwater renderer, true poses,
//   the true surface as the model) the per-face error against the true
//   albedo stays below the bound justified at the test, and the photometric
//   normalisation is what makes it small (raw pixels are far off);
// - the written folder: OBJ, MTL, atlas, PLY, JSON and CSV.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "base/file_io.h"
#include "image/image_file.h"
#include "mosaic/mosaic_camera.h"
#include "mosaic/mosaic_io.h"
#include "mosaic/photomosaic.h"
#include "mosaic/photomosaic_internal.h"
#include "results/mosaic_files.h"
#include "simulate/survey_imaging.h"
#include "support/test_files.h"

namespace hull {
namespace {

constexpr int kW = 160, kH = 120;
constexpr double kF = 120;

// A monocular rig whose camera is the vehicle: no mount, no extrinsic.
SurveyManifest PlainManifest() {
  SurveyManifest m;
  m.camera.type = CameraType::kMono;
  m.camera.width = kW;
  m.camera.height = kH;
  m.camera.top = {kF, kF, (kW - 1) / 2.0, (kH - 1) / 2.0};
  m.camera.servo_to_top = Vector6d::Zero();
  m.servo_mount = Vector6d::Zero();
  return m;
}

// A camera at (x, y, z) looking straight down (-z of M).
Vector6d LookingDown(double x, double y, double z) {
  Vector6d v;
  v << x, y, z, M_PI, 0, 0;
  return v;
}

// The square [-1, 1]^2 at z = 0, normals +z, `n` cells a side.
void AddPlane(TriangleMesh& m, int n, double half, double z) {
  const int base = static_cast<int>(m.vertices.size());
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(-half + 2 * half * i / n, -half + 2 * half * j / n, z);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  }
}

// An axis-aligned rectangle [x0, x1] x [y0, y1] at height z, facing +z.
void AddRect(TriangleMesh& m, double x0, double x1, double y0, double y1, double z) {
  const int b = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(x0, y0, z);
  m.vertices.emplace_back(x1, y0, z);
  m.vertices.emplace_back(x1, y1, z);
  m.vertices.emplace_back(x0, y1, z);
  m.faces.push_back({b, b + 1, b + 2});
  m.faces.push_back({b, b + 2, b + 3});
}

MosaicInput PlaneInput(const std::vector<Vector6d>& cams, std::vector<cv::Mat> images, TriangleMesh model) {
  MosaicInput in;
  in.manifest = PlainManifest();
  for (std::size_t k = 0; k < cams.size(); ++k) {
    in.keyframes.push_back(static_cast<std::int64_t>(k) + 1);
    in.poses.push_back(cams[k]);
    in.servo.push_back(0);
  }
  in.model = std::move(model);
  in.has_image = [](std::size_t, bool bottom) { return !bottom; };
  in.read_image = [images](std::size_t k, bool) { return images[k]; };
  return in;
}

// Smooth random texture (grey levels 30..225).
cv::Mat SmoothImage(int seed) {
  cv::Mat noise(kH, kW, CV_32F);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 3.0);
  double lo, hi;
  cv::minMaxLoc(noise, &lo, &hi);
  cv::Mat out;
  noise.convertTo(out, CV_8U, 195.0 / (hi - lo), 30 - 195.0 * lo / (hi - lo));
  return out;
}

float Bilinear(const cv::Mat& img, double u, double v) {
  const int x0 = std::clamp(static_cast<int>(std::floor(u)), 0, img.cols - 2);
  const int y0 = std::clamp(static_cast<int>(std::floor(v)), 0, img.rows - 2);
  const double fx = u - x0, fy = v - y0;
  auto at = [&](int y, int x) { return static_cast<double>(img.at<std::uint8_t>(y, x)); };
  return static_cast<float>((1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x0 + 1)) +
                            fy * ((1 - fx) * at(y0 + 1, x0) + fx * at(y0 + 1, x0 + 1)));
}

MosaicOptions RawOptions() {
  MosaicOptions o;
  o.normalisation = MosaicNormalisation::kNone;
  o.feather_rings = 0;
  o.texel_size = 0.005;
  o.num_threads = 2;
  return o;
}

TEST(Mosaic, AtlasUvsInRangeAndTextureSampledBackIsTheImage) {
  TriangleMesh plane;
  AddPlane(plane, 10, 0.4, 0.0);
  const Vector6d cam = LookingDown(0.05, -0.03, 1.0);
  const cv::Mat image = SmoothImage(3);
  NullProgress progress;
  const MosaicResult r = BuildMosaic(PlaneInput({cam}, {image}, plane), RawOptions(), progress);
  ASSERT_EQ(r.summary.faces_textured, r.model.num_faces());
  ASSERT_EQ(r.atlas.type(), CV_8UC1);
  // An independent pinhole: camera at (x, y, z) looking down, x right, y down.
  const Pose x_Mc = Pose::FromVector(cam);
  auto project = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d c = x_Mc.Inverse() * p;
    return Eigen::Vector2d(kF * c.x() / c.z() + (kW - 1) / 2.0, kF * c.y() / c.z() + (kH - 1) / 2.0);
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double worst_centre = 0, worst_any = 0;
  int centres = 0;
  for (std::size_t f = 0; f < r.model.num_faces(); ++f) {
    const Face& F = r.model.faces[f];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2f uv = r.Uv(static_cast<int>(f), c);
      ASSERT_GE(uv.x(), 0.0f);
      ASSERT_LE(uv.x(), 1.0f);
      ASSERT_GE(uv.y(), 0.0f);
      ASSERT_LE(uv.y(), 1.0f);
    }
    const auto& k = r.corners[f];
    // Texel centres inside the triangle: the texel is the image there.
    const float x0 = std::min({k[0].x(), k[1].x(), k[2].x()}), x1 = std::max({k[0].x(), k[1].x(), k[2].x()});
    const float y0 = std::min({k[0].y(), k[1].y(), k[2].y()}), y1 = std::max({k[0].y(), k[1].y(), k[2].y()});
    for (int j = static_cast<int>(y0); j <= static_cast<int>(y1); ++j) {
      for (int i = static_cast<int>(x0); i <= static_cast<int>(x1); ++i) {
        const Eigen::Vector2d q(i + 0.5, j + 0.5);
        const Eigen::Vector2d a = k[0].cast<double>(), b = k[1].cast<double>(), c = k[2].cast<double>();
        const double den = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
        const double l1 = ((q - a).x() * (c - a).y() - (q - a).y() * (c - a).x()) / den;
        const double l2 = ((b - a).x() * (q - a).y() - (b - a).y() * (q - a).x()) / den;
        const double l0 = 1 - l1 - l2;
        if (std::min({l0, l1, l2}) < 0) continue;
        const Eigen::Vector3d p = l0 * r.model.vertices[static_cast<std::size_t>(F[0])] +
                                  l1 * r.model.vertices[static_cast<std::size_t>(F[1])] +
                                  l2 * r.model.vertices[static_cast<std::size_t>(F[2])];
        const Eigen::Vector2d px = project(p);
        const double d = std::abs(r.atlas.at<std::uint8_t>(j, i) - Bilinear(image, px.x(), px.y()));
        worst_centre = std::max(worst_centre, d);
        ++centres;
      }
    }
    // Random points of the face, through the OBJ's UVs and bilinear lookup.
    for (int s = 0; s < 5; ++s) {
      double l1 = 0.05 + 0.9 * U(rng), l2 = 0.05 + 0.9 * U(rng);
      if (l1 + l2 > 0.95) l1 = 0.95 - l1 + 0.05, l2 = 0.95 - l2 + 0.05;
      const double l0 = 1 - l1 - l2;
      const Eigen::Vector2f uv = static_cast<float>(l0) * r.Uv(static_cast<int>(f), 0) +
                                 static_cast<float>(l1) * r.Uv(static_cast<int>(f), 1) +
                                 static_cast<float>(l2) * r.Uv(static_cast<int>(f), 2);
      const double ax = uv.x() * r.atlas.cols - 0.5, ay = (1 - uv.y()) * r.atlas.rows - 0.5;
      const Eigen::Vector3d p = l0 * r.model.vertices[static_cast<std::size_t>(F[0])] +
                                l1 * r.model.vertices[static_cast<std::size_t>(F[1])] +
                                l2 * r.model.vertices[static_cast<std::size_t>(F[2])];
      const Eigen::Vector2d px = project(p);
      worst_any = std::max(worst_any,
                           static_cast<double>(std::abs(Bilinear(r.atlas, ax, ay) - Bilinear(image, px.x(), px.y()))));
    }
  }
  EXPECT_GT(centres, 1000);
  // Texel centres: the image's bilinear value, rounded to 8 bits.
  EXPECT_LE(worst_centre, 0.5 + 1e-3);
  // Anywhere: plus the atlas' own linear interpolation of a smooth image
  // (texel 5 mm, pixel 8 mm: the gradients are below 1 level per texel).
  EXPECT_LE(worst_any, 1.5);
}

// Whether the segment from p to the camera centre o crosses the plate.
bool PlateBlocks(const Eigen::Vector3d& p, const Eigen::Vector3d& o, double x0, double x1, double y0, double y1,
                 double z) {
  const double t = (z - p.z()) / (o.z() - p.z());
  if (!(t > 0 && t < 1)) return false;
  const Eigen::Vector3d q = p + t * (o - p);
  return q.x() >= x0 && q.x() <= x1 && q.y() >= y0 && q.y() <= y1;
}

TEST(Mosaic, OccludedViewIsNeverChosen) {
  TriangleMesh model;
  AddPlane(model, 40, 0.8, 0.0);
  const std::size_t plane_faces = model.num_faces();
  const double px0 = -0.3, px1 = -0.1, py0 = -0.2, py1 = 0.2, pz = 0.5;
  AddRect(model, px0, px1, py0, py1, pz);
  // A: near and frontal (the best score everywhere it sees); B: farther.
  const Vector6d a = LookingDown(0, 0, 1.0), b = LookingDown(0.3, 0, 2.0);
  const cv::Mat image_a(kH, kW, CV_8U, cv::Scalar(200)), image_b(kH, kW, CV_8U, cv::Scalar(60));
  MosaicOptions o = RawOptions();
  NullProgress progress;
  const MosaicResult r = BuildMosaic(PlaneInput({a, b}, {image_a, image_b}, model), o, progress);
  const Eigen::Vector3d oa = Pose::FromVector(a).translation();
  int hidden_from_a = 0, hidden_from_a_taken_from_b = 0, seen_by_a = 0;
  for (std::size_t f = 0; f < plane_faces; ++f) {
    const MosaicFace& F = r.faces[f];
    const Eigen::Vector3d g = r.model.FaceCentroid(static_cast<int>(f));
    const bool a_blocked = PlateBlocks(g, oa, px0, px1, py0, py1, pz);
    if (F.view < 0) continue;
    const Eigen::Vector3d o_chosen = r.views[static_cast<std::size_t>(F.view)].x_Mc.translation();
    // Never a camera the plate hides the face's centroid from.
    EXPECT_FALSE(PlateBlocks(g, o_chosen, px0, px1, py0, py1, pz)) << "face " << f;
    if (a_blocked) {
      ++hidden_from_a;
      if (F.view == 1) ++hidden_from_a_taken_from_b;
    } else if (F.view == 0) {
      ++seen_by_a;
    }
    // The atlas holds the chosen camera's (constant) image.
    const auto& k = r.corners[f];
    const Eigen::Vector2f c = (k[0] + k[1] + k[2]) / 3.0f;
    EXPECT_EQ(r.atlas.at<std::uint8_t>(static_cast<int>(c.y()), static_cast<int>(c.x())), F.view == 0 ? 200 : 60);
  }
  EXPECT_GT(hidden_from_a, 20);                          // the plate does hide part of the plane from A ...
  EXPECT_EQ(hidden_from_a_taken_from_b, hidden_from_a);  // ... and B textures all of that part
  EXPECT_GT(seen_by_a, 500);                             // elsewhere A, the better view, wins
  EXPECT_GT(r.summary.seam_edges, 0u);
}

// ---- Visibility: the culled search against the rule on every pair.

// The candidate rule applied to every (view, face) pair, one ray at a time:
// what SeenFaces must return.
std::vector<std::vector<std::pair<int, float>>> SeenByEveryPair(const TriangleMesh& m, const MeshIndex& index,
                                                                const std::vector<MosaicCamera>& cams,
                                                                const MosaicOptions& o, int* rejected) {
  const double cos_max = std::cos(o.max_incidence_deg * M_PI / 180.0);
  std::vector<std::vector<std::pair<int, float>>> seen(cams.size());
  for (std::size_t v = 0; v < cams.size(); ++v) {
    const Eigen::Vector3d c = cams[v].centre();
    for (std::size_t f = 0; f < m.num_faces(); ++f) {
      const Eigen::Vector3d to = c - m.FaceCentroid(static_cast<int>(f));
      const double d = to.norm();
      if (!(d > 1e-6 && d <= o.max_range)) {
        ++rejected[0];
        continue;
      }
      const double cosi = m.face_normals[f].dot(to) / d;
      if (cosi < cos_max) {
        ++rejected[1];
        continue;
      }
      bool in_image = true;
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector2d uv;
        in_image = in_image && cams[v].Project(m.vertices[static_cast<std::size_t>(m.faces[f][i])], &uv) &&
                   uv.x() >= o.image_margin && uv.y() >= o.image_margin && uv.x() <= kW - 1 - o.image_margin &&
                   uv.y() <= kH - 1 - o.image_margin;
      }
      if (!in_image) {
        ++rejected[2];
        continue;
      }
      bool free = true;
      for (const Eigen::Vector3d& p : mosaic_internal::FaceSamples(m, static_cast<int>(f))) {
        bool blocked = false;
        index.OccludedToward(&p, 1, c, 1e-3, &blocked);
        free = free && !blocked;
      }
      if (!free) {
        ++rejected[3];
        continue;
      }
      seen[v].emplace_back(static_cast<int>(f), static_cast<float>(cosi / (d * d)));
    }
  }
  return seen;
}

TEST(Mosaic, SeenFacesEqualsTheRuleOnEveryPair) {
  // A wavy 10 m x 6 m surface (0.2 m cells), a plate floating over it and one
  // facing away from the cameras; a stereo rig on a servo with a mount,
  // extrinsic and model pose of their own, 40 keyframes 0.8-3 m above it,
  // tilted up to 0.4 rad: every part of the rule rejects some pairs.
  TriangleMesh m;
  const int nx = 50, ny = 30;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = -5 + 0.2 * i, y = -3 + 0.2 * j;
      m.vertices.emplace_back(x, y, 0.25 * std::sin(1.3 * x) * std::cos(0.9 * y));
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  }
  AddRect(m, -1, 1, -0.5, 0.5, 0.8);
  const std::size_t down = m.num_faces();
  AddRect(m, 2, 3, -1, 0, 0.6);
  for (std::size_t f = down; f < m.num_faces(); ++f) std::swap(m.faces[f][1], m.faces[f][2]);  // facing -z
  m.ComputeNormals();
  SurveyManifest rig = PlainManifest();
  rig.camera.type = CameraType::kStereo;
  rig.camera.bottom = {kF * 1.02, kF * 0.99, kW / 2.0 + 1.5, kH / 2.0 - 2};
  rig.camera.top_to_bottom << 0.02, 0.12, 0.01, 0.01, -0.02, 0.005;
  rig.servo_mount << 0.4, 0.05, 0.2, 0.02, 0, -0.01;
  Vector6d x_s_cT, x_gM;
  x_s_cT << 0.05, 0.02, 0.1, 0.02, -0.03, 0.01;
  x_gM << 0.1, -0.2, 0.05, 0.01, 0.02, -0.03;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-5.5, 5.5), uy(-3.5, 3.5), uz(0.8, 3.0), tilt(-0.4, 0.4), yaw(-M_PI, M_PI);
  std::vector<MosaicCamera> cams;
  for (int k = 0; k < 40; ++k) {
    Vector6d x_gv;
    x_gv << ux(rng), uy(rng), uz(rng), M_PI + tilt(rng), tilt(rng), yaw(rng);
    const double servo = tilt(rng);
    for (bool bottom : {false, true}) cams.emplace_back(rig, x_gv, servo, x_s_cT, x_gM, bottom);
  }
  MosaicOptions o;
  o.max_range = 2.5;  // cells of 0.625 m: the surface spans 16 x 10 of them
  o.max_incidence_deg = 60;
  const MeshIndex index(m);
  int rejected[4] = {0, 0, 0, 0};  // range, incidence, image, occluded
  const auto expected = SeenByEveryPair(m, index, cams, o, rejected);
  NullProgress progress;
  const mosaic_internal::Visibility vis = mosaic_internal::SeenFaces(m, index, cams, kW, kH, o, progress);
  ASSERT_EQ(vis.seen.size(), cams.size());
  std::size_t candidates = 0;
  for (std::size_t v = 0; v < cams.size(); ++v) {
    EXPECT_EQ(vis.seen[v], expected[v]) << "view " << v;  // the same faces, bit for bit the same scores
    candidates += expected[v].size();
  }
  for (int r = 0; r < 4; ++r) EXPECT_GT(rejected[r], 0) << "rule " << r << " never rejects";
  EXPECT_GT(candidates, 2000u);
  // The culls do cull: fewer pairs looked at than all, fewer projected than near.
  EXPECT_LT(vis.near, cams.size() * m.num_faces() / 2);
  EXPECT_LT(vis.projected, vis.near / 2);
  // Rays only for the pairs with their corners in the image: the candidates and the occluded.
  EXPECT_EQ(vis.rays, 4 * (candidates + static_cast<std::size_t>(rejected[3])));
}

// ---- A small rendered survey.

struct RenderedSurvey {
  SimulatedSurvey survey;
  std::unique_ptr<TrueScene> scene;
  std::unique_ptr<UnderwaterCamera> top, bottom;
};

const RenderedSurvey& Rendered() {
  static RenderedSurvey* s = [] {
    auto* r = new RenderedSurvey;
    SurveySimulationOptions o = SurveyPreset("demo");
    o.camera_scale = 0.25;         // 340 x 256
    o.plan.keyframe_spacing *= 3;  // a third of the keyframes
    o.images = true;
    NullProgress p;
    r->survey = SimulateSurvey(o, p);
    r->scene = MakeTrueScene(r->survey);
    r->top = MakeSurveyCamera(r->survey.bundle.manifest, *r->survey.imaging, false);
    r->bottom = MakeSurveyCamera(r->survey.bundle.manifest, *r->survey.imaging, true);
    return r;
  }();
  return *s;
}

// The truth as the "adjusted" estimates and the true surface as the model:
// what remains is the photometric inversion, resampling and sensor noise.
MosaicInput RenderedInput(const RenderedSurvey& s, std::size_t max_keyframes) {
  const SurveyBundle& b = s.survey.bundle;
  MosaicInput in;
  in.manifest = b.manifest;
  const std::size_t n = std::min(max_keyframes, b.truth->poses.size());
  for (std::size_t k = 0; k < n; ++k) {
    in.keyframes.push_back(b.truth->poses[k].keyframe);
    in.poses.push_back(b.truth->poses[k].x_gv);
    in.servo.push_back(b.truth->poses[k].servo);
  }
  in.x_gM = b.truth->x_gM;
  in.x_s_cT = b.truth->x_s_cT;
  in.model = s.scene->mesh();
  const SimulatedSurvey* sv = &s.survey;
  const RenderedSurvey* rs = &s;
  in.has_image = [](std::size_t, bool) { return true; };
  in.read_image = [sv, rs](std::size_t k, bool bottom) {
    const UnderwaterCamera& cam = bottom ? *rs->bottom : *rs->top;
    return cam.Render(*rs->scene, TrueCameraPose(*sv, k, bottom), 1000 + 2 * k + (bottom ? 1 : 0));
  };
  return in;
}

TEST(Mosaic, ColourErrorOnARenderedSurveyIsSmallAndNeedsTheNormalisation) {
  const RenderedSurvey& s = Rendered();
  const MosaicInput in = RenderedInput(s, 16);
  MosaicOptions o;
  o.texel_size = 0.01;
  o.num_threads = 2;
  NullProgress progress;
  const MosaicResult r = BuildMosaic(in, o, progress, s.scene.get());
  ASSERT_GT(r.summary.faces_scored, 200u);
  std::printf(
      "model+gains: %zu faces, |error| median %.4f p95 %.4f, face means median %.4f p95 %.4f, gains %.3f..%.3f, "
      "%.2f s\n",
      r.summary.faces_scored, r.summary.error_median, r.summary.error_p95, r.summary.mean_error_median,
      r.summary.mean_error_p95, r.summary.gain_min, r.summary.gain_max, r.summary.seconds.total);
  // Measured on this survey (docs/mosaic.md, "Colour error"): face means
  // median 0.008, p95 0.05; texels median 0.017 (albedo units; the hull's
  // paint is 0.2..0.4). What remains: sensor noise, facet normals against
  // the renderer's smoothed shading normals, strobe shadows beside objects
  // (not modelled). Bounds with a margin of about 1.5..2.
  EXPECT_LT(r.summary.mean_error_median, 0.015);
  EXPECT_LT(r.summary.mean_error_p95, 0.08);
  EXPECT_LT(r.summary.error_median, 0.03);
  EXPECT_LT(r.summary.error_p95, 0.09);

  // Raw pixels (share of full scale) against the albedo: the strobe, water
  // and vignetting left in are far larger errors.
  MosaicOptions raw = o;
  raw.normalisation = MosaicNormalisation::kNone;
  const MosaicResult q = BuildMosaic(in, raw, progress, s.scene.get());
  std::printf("raw: |error| median %.4f, face means median %.4f\n", q.summary.error_median,
              q.summary.mean_error_median);
  EXPECT_GT(q.summary.mean_error_median, 3 * r.summary.mean_error_median);
}

TEST(Mosaic, WritesTheFolderTheGltfExporterReads) {
  TriangleMesh plane;
  AddPlane(plane, 4, 0.3, 0.0);
  NullProgress progress;
  MosaicResult r = BuildMosaic(PlaneInput({LookingDown(0, 0, 1)}, {SmoothImage(1)}, plane), RawOptions(), progress);
  const testing::ScratchDir tmp("mosaic_write");
  const std::string dir = tmp / "mosaic";
  WriteMosaic(r, dir);
  namespace fs = std::filesystem;
  for (const char* f : {kMosaicObj, kMosaicMtl, kMosaicAtlas, kMosaicPly, kMosaicJson, kMosaicFacesCsv}) {
    EXPECT_TRUE(fs::exists(fs::path(dir) / f)) << f;
  }
  const std::string obj = ReadFileToString(dir + "/" + kMosaicObj);
  EXPECT_NE(obj.find("mtllib mosaic.mtl"), std::string::npos);
  EXPECT_NE(obj.find("f 1/"), std::string::npos);
  EXPECT_NE(ReadFileToString(dir + "/" + kMosaicMtl).find("map_Kd mosaic_atlas.png"), std::string::npos);
  const cv::Mat atlas = ReadImageFile(dir + "/" + kMosaicAtlas);
  EXPECT_EQ(cv::norm(atlas, r.atlas, cv::NORM_INF), 0.0);
  const std::string ply = ReadFileToString(dir + "/" + kMosaicPly);
  EXPECT_NE(ply.find("property uchar red"), std::string::npos);
  EXPECT_NE(ply.find("element face " + std::to_string(r.model.num_faces()) + "\n"), std::string::npos);
  const std::string json = ReadFileToString(dir + "/" + kMosaicJson);
  EXPECT_NE(json.find("\"format\": \"hull-mosaic\""), std::string::npos);
}

TEST(Mosaic, CancelledBeforeWorkThrowsCancelledAndReportsProgress) {
  TriangleMesh plane;
  AddPlane(plane, 4, 0.3, 0.0);
  const MosaicInput in = PlaneInput({LookingDown(0, 0, 1)}, {SmoothImage(1)}, plane);
  double last = -1;
  CallbackProgress progress([&](double f, const std::string&) { last = f; });
  const MosaicResult done = BuildMosaic(in, RawOptions(), progress);
  EXPECT_EQ(last, 1.0);
  progress.RequestCancel();
  EXPECT_THROW(BuildMosaic(in, RawOptions(), progress), Cancelled);
}

// Images that do not match the camera or each other are named, both of
// them, as bad input (it was "the images mix channel counts", naming none).
TEST(Mosaic, MixedImagesNameTheirFiles) {
  TriangleMesh plane;
  AddPlane(plane, 4, 0.3, 0.0);
  cv::Mat colour;
  cv::cvtColor(SmoothImage(2), colour, cv::COLOR_GRAY2BGR);
  MosaicInput in = PlaneInput({LookingDown(0, 0, 1), LookingDown(0.05, 0, 1)}, {SmoothImage(1), colour}, plane);
  in.image_name = [](std::size_t k, bool) { return "images/" + std::to_string(k + 1) + "_top.png"; };
  NullProgress progress;
  try {
    BuildMosaic(in, RawOptions(), progress);
    FAIL() << "mixed channel counts accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "images/2_top.png");
    EXPECT_THAT(e.what(), ::testing::HasSubstr("3 channels, where images/1_top.png has 1"));
  }
  in = PlaneInput({LookingDown(0, 0, 1)}, {cv::Mat(kH / 2, kW, CV_8U, cv::Scalar(90))}, plane);
  EXPECT_THROW(
      {
        try {
          BuildMosaic(in, RawOptions(), progress);
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), ::testing::HasSubstr("the top image of keyframe 1"));
          throw;
        }
      },
      InputError);
}

TEST(Mosaic, ResultsFolderWithoutModelIsNamed) {
  const testing::ScratchDir tmp("mosaic_sources");
  EXPECT_THROW(LocateMosaicSources(tmp / "nothing"), InputError);
  testing::WriteText(tmp / "adjustment.json", "{}");
  try {
    LocateMosaicSources(tmp.path());
    FAIL() << "no mapping/model.ply accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mapping/model.ply"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hull
