// Unit tests of the mapping building blocks on data with known answers:
// options, DBSCAN against a brute-force DBSCAN, Algorithm 1's hysteresis,
// alpha shapes of known point sets, rays against shapes, the moving average of eq. 15, hull zones and
// ratings, exact clipping and refinement regions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "base/error.h"
#include "mapping/alpha_shape.h"
#include "mapping/dbscan.h"
#include "mapping/fouling.h"
#include "mapping/hull_zones.h"
#include "mapping/mapping_options.h"
#include "mapping/point_cone_tree.h"
#include "mapping/refinement_region.h"
#include "mapping/shape_detection.h"
#include "mapping/shape_fusion.h"
#include "mapping/shape_raycast.h"
#include "mapping/surface_clip.h"

namespace hull {
namespace {

// ---- options -------------------------------------------------------------------

TEST(MappingOptions, DefaultsPassAndEachBadFieldIsNamed) {
  MappingOptions ok;
  EXPECT_NO_THROW(ok.Check());
  EXPECT_DOUBLE_EQ(ok.CgalAlpha(), 0.12 * 0.12);
  const struct {
    const char* field;
    void (*spoil)(MappingOptions&);
  } cases[] = {
      {"tau", [](MappingOptions& o) { o.tau = -0.01; }},
      {"shape_grow_height", [](MappingOptions& o) { o.shape_grow_height = -0.01; }},
      {"alpha", [](MappingOptions& o) { o.alpha = 0; }},
      {"dbscan_eps", [](MappingOptions& o) { o.dbscan_eps = -1; }},
      {"dbscan_min_points", [](MappingOptions& o) { o.dbscan_min_points = 0; }},
      {"fusion_radius", [](MappingOptions& o) { o.fusion_radius = 0; }},
      {"fusion_support", [](MappingOptions& o) { o.fusion_support = 0; }},
      {"fusion_peak_band", [](MappingOptions& o) { o.fusion_peak_band = -0.001; }},
      {"refine_edge", [](MappingOptions& o) { o.refine_edge = 0.001; }},
      {"refine_threshold", [](MappingOptions& o) { o.refine_threshold = -1; }},
      {"refine_margin", [](MappingOptions& o) { o.refine_margin = 5; }},
      {"significance_k", [](MappingOptions& o) { o.significance_k = 0; }},
      {"object_min_height", [](MappingOptions& o) { o.object_min_height = 0; }},
      {"object_min_area", [](MappingOptions& o) { o.object_min_area = -1; }},
      {"object_min_features", [](MappingOptions& o) { o.object_min_features = -1; }},
      {"object_min_views", [](MappingOptions& o) { o.object_min_views = 0; }},
      {"stations", [](MappingOptions& o) { o.stations = 0; }},
      {"bottom_angle_deg", [](MappingOptions& o) { o.bottom_angle_deg = 90; }},
      {"inspection_spacing", [](MappingOptions& o) { o.inspection_spacing = 0; }},
      {"inspection_range", [](MappingOptions& o) { o.inspection_range = -2; }},
      {"num_threads", [](MappingOptions& o) { o.num_threads = -1; }},
      {"tau", [](MappingOptions& o) { o.tau = std::nan(""); }},
  };
  for (const auto& c : cases) {
    MappingOptions o;
    c.spoil(o);
    try {
      o.Check();
      ADD_FAILURE() << c.field << " was accepted";
    } catch (const OptionError& e) {
      EXPECT_EQ(e.field(), c.field);
    }
  }
}

// ---- DBSCAN --------------------------------------------------------------------

// The textbook algorithm with O(n^2) neighbourhoods, visiting in index order.
std::vector<int> BruteDbscan(const std::vector<Eigen::Vector3d>& p, double eps, int min_points) {
  const int n = static_cast<int>(p.size());
  auto neighbours = [&](int i) {
    std::vector<int> out;
    for (int j = 0; j < n; ++j) {
      if ((p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(j)]).norm() <= eps) out.push_back(j);
    }
    return out;
  };
  std::vector<int> label(static_cast<std::size_t>(n), -2);
  int clusters = 0;
  for (int i = 0; i < n; ++i) {
    if (label[static_cast<std::size_t>(i)] != -2) continue;
    std::vector<int> seeds = neighbours(i);
    if (static_cast<int>(seeds.size()) < min_points) {
      label[static_cast<std::size_t>(i)] = -1;
      continue;
    }
    const int c = clusters++;
    label[static_cast<std::size_t>(i)] = c;
    for (std::size_t k = 0; k < seeds.size(); ++k) {
      const int j = seeds[k];
      if (label[static_cast<std::size_t>(j)] == -1) label[static_cast<std::size_t>(j)] = c;
      if (label[static_cast<std::size_t>(j)] != -2) continue;
      label[static_cast<std::size_t>(j)] = c;
      const std::vector<int> more = neighbours(j);
      if (static_cast<int>(more.size()) >= min_points) seeds.insert(seeds.end(), more.begin(), more.end());
    }
  }
  return label;
}

TEST(Dbscan, AgreesWithBruteForceOnRandomData) {
  std::mt19937 rng(7);
  int clustered = 0, noise = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Eigen::Vector3d> pts;
    // A few blobs and uniform clutter, in a box shaped like the (x, y, d) data.
    const int blobs = 1 + trial % 4;
    for (int b = 0; b < blobs; ++b) {
      const Eigen::Vector3d c(u(rng) * 2, u(rng) * 1.5, u(rng) * 0.2);
      std::normal_distribution<double> g(0, 0.04 + 0.02 * (trial % 3));
      for (int i = 0; i < 20 + trial; ++i) pts.push_back(c + Eigen::Vector3d(g(rng), g(rng), 0.3 * g(rng)));
    }
    for (int i = 0; i < 60; ++i) pts.emplace_back(u(rng) * 2, u(rng) * 1.5, u(rng) * 0.2);
    const double eps = 0.05 + 0.05 * (trial % 4);
    const int min_points = 1 + trial % 5;
    const DbscanResult r = Dbscan(pts, eps, min_points);
    const std::vector<int> brute = BruteDbscan(pts, eps, min_points);
    ASSERT_EQ(r.labels, brute) << "trial " << trial;
    EXPECT_EQ(r.num_clusters, *std::max_element(brute.begin(), brute.end()) + 1);
    for (const int l : r.labels) (l >= 0 ? clustered : noise) += 1;
  }
  EXPECT_GT(clustered, 1000);  // the cases are not all noise ...
  EXPECT_GT(noise, 100);       // ... nor all clusters
}

TEST(Dbscan, KnownCases) {
  EXPECT_TRUE(Dbscan({}, 0.1, 3).labels.empty());
  // Three points in a row 0.09 apart: the middle one is a core point (itself
  // and two neighbours within 0.1), the ends are its border points.
  const std::vector<Eigen::Vector3d> row = {{0, 0, 0}, {0.09, 0, 0}, {0.18, 0, 0}, {5, 5, 5}};
  const DbscanResult r = Dbscan(row, 0.1, 3);
  EXPECT_EQ(r.num_clusters, 1);
  EXPECT_EQ(r.labels, (std::vector<int>{0, 0, 0, DbscanResult::kNoise}));
  // Four points need four.
  EXPECT_EQ(Dbscan(row, 0.1, 4).num_clusters, 0);
  // min_points 1: every point is its own core.
  EXPECT_EQ(Dbscan(row, 0.01, 1).num_clusters, 4);
}

// ---- Algorithm 1's hysteresis ---------------------------------------------------

TEST(ShapeDetection, KeepSeededClustersDropsClustersWithoutASeed) {
  DbscanResult db;
  db.labels = {0, 0, 1, 1, 2, DbscanResult::kNoise};
  db.num_clusters = 3;
  KeepSeededClusters({0, 1, 0, 0, 1, 1}, 1, db);
  EXPECT_EQ(db.num_clusters, 2);
  EXPECT_EQ(db.labels, (std::vector<int>{0, 0, DbscanResult::kNoise, DbscanResult::kNoise, 1, DbscanResult::kNoise}));
}

// One keyframe's camera (at the origin of g, looking along +z) over a grid
// of features 1 m away, 3 cm apart: a narrow lump 0.10 m high (Gaussian,
// sigma 3.5 cm; above tau = 0.06 m over its five middle features) and a low
// one 0.05 m high (sigma 5 cm; nothing above tau), 0.6 m apart; the rest
// lies on the CAD surface (deviation 0).
MappingInput TwoLumps() {
  MappingInput in;
  MappingKeyframe kf;
  kf.id = 1;
  for (int j = -20; j <= 20; ++j) {
    for (int i = -20; i <= 20; ++i) {
      const Eigen::Vector2d xy(0.03 * i, 0.03 * j);
      const double r1 = (xy - Eigen::Vector2d(-0.3, 0)).squaredNorm(),
                   r2 = (xy - Eigen::Vector2d(0.3, 0)).squaredNorm();
      double d = 0.10 * std::exp(-r1 / (2 * 0.035 * 0.035)) + 0.05 * std::exp(-r2 / (2 * 0.05 * 0.05));
      if (d < 0.002) d = 0;
      MappingLandmark l;
      l.id = static_cast<std::int64_t>(in.landmarks.size());
      l.p_g = Eigen::Vector3d(xy.x(), xy.y(), 1.0 - d);
      l.deviation = d;
      kf.landmarks.push_back(static_cast<int>(in.landmarks.size()));
      in.landmarks.push_back(l);
    }
  }
  in.keyframes.push_back(kf);
  return in;
}

TEST(ShapeDetection, HysteresisShapesANarrowLumpOverItsFootprintAndALowOneNot) {
  const MappingInput in = TwoLumps();
  MappingOptions off;
  off.tau = 0.06;
  off.shape_grow_height = off.tau;  // the paper's Algorithm 1: each feature cut at tau
  MappingOptions on = off;
  on.shape_grow_height = MappingOptions().shape_grow_height;  // the default, 1.5 cm
  ASSERT_LT(on.shape_grow_height, on.tau);
  const KeyframeShapes cut = DetectShapes(in, 0, off), grown = DetectShapes(in, 0, on);
  ASSERT_EQ(cut.shapes.size(), 1u);
  ASSERT_EQ(grown.shapes.size(), 1u);
  // Cut at tau, the narrow lump's shape is its top: every vertex above tau.
  for (const double d : cut.shapes[0].deviation) EXPECT_GT(d, off.tau);
  // Grown, it spans the lump's flanks down to the level: vertices below 2
  // cm, none below the level, 4 times the area and more, all on the narrow
  // lump.
  const DetectedShape& s = grown.shapes[0];
  EXPECT_LT(*std::min_element(s.deviation.begin(), s.deviation.end()), 0.02);
  EXPECT_GT(*std::min_element(s.deviation.begin(), s.deviation.end()), on.shape_grow_height);
  EXPECT_GT(s.area, 4 * cut.shapes[0].area);
  for (const Eigen::Vector3d& v : s.vertices_g) EXPECT_LT((v.head<2>() - Eigen::Vector2d(-0.3, 0)).norm(), 0.1);
  // The low lump has no feature above tau: no shape, and its features are
  // not clustered (kBelowTau), as without the hysteresis.
  for (const ShapePoint& p : grown.points) {
    const Eigen::Vector2d xy = in.landmarks[static_cast<std::size_t>(p.landmark)].p_g.head<2>();
    if ((xy - Eigen::Vector2d(0.3, 0)).norm() < 0.2) {
      EXPECT_EQ(p.cluster, ShapePoint::kBelowTau);
    }
  }
  // At tau = 0 the level has no effect: both lumps are shaped either way.
  off.tau = on.tau = 0;
  EXPECT_EQ(DetectShapes(in, 0, off).shapes.size(), 2u);
  EXPECT_EQ(DetectShapes(in, 0, on).shapes.size(), 2u);
}

TEST(ShapeDetection, ASeedSeenInOneViewKeepsTheLumpsClusterInAnother) {
  // A second keyframe at the same place sees the narrow lump's flanks but
  // not its features above tau (the seeds): on its own, its cluster there
  // has no seed and forms no shape.
  MappingInput in = TwoLumps();
  MappingOptions o;
  o.tau = 0.06;
  ASSERT_LT(o.shape_grow_height, o.tau);
  MappingKeyframe second = in.keyframes[0];
  second.id = 2;
  second.landmarks.clear();
  int seeds = 0;
  for (const int li : in.keyframes[0].landmarks) {
    if (in.landmarks[static_cast<std::size_t>(li)].deviation > o.tau) {
      ++seeds;
      continue;
    }
    second.landmarks.push_back(li);
  }
  ASSERT_GT(seeds, 0);
  in.keyframes.push_back(second);
  const auto near = [&](const Eigen::Vector3d& p, double x) {
    return std::abs(p.x() - x) < 0.15 && std::abs(p.y()) < 0.15;
  };

  const std::vector<char> seeded = SeededLandmarks(in, o);
  // The seeded landmarks: the narrow lump's cluster in the first view, not
  // the low lump's nor the hull's.
  int on_narrow = 0;
  for (std::size_t li = 0; li < seeded.size(); ++li) {
    if (!seeded[li]) continue;
    EXPECT_TRUE(near(in.landmarks[li].p_g, -0.3)) << li;
    on_narrow += in.landmarks[li].deviation <= o.tau;
  }
  EXPECT_GT(on_narrow, 4);  // its flanks below tau, which the second view sees

  EXPECT_TRUE(DetectShapes(in, 1, o).shapes.empty());  // the view alone
  const KeyframeShapes with = DetectShapes(in, 1, o, &seeded);
  ASSERT_EQ(with.shapes.size(), 1u);
  for (const Eigen::Vector3d& v : with.shapes[0].vertices_g) {
    EXPECT_TRUE(near(v, -0.3));
  }
  // The low lump has no seed in any view: no shape, either keyframe.
  for (const int k : {0, 1}) {
    for (const DetectedShape& s : DetectShapes(in, k, o, &seeded).shapes) {
      for (const Eigen::Vector3d& v : s.vertices_g) EXPECT_FALSE(near(v, 0.3)) << k;
    }
  }
  // DetectAllShapes applies it by default, and not when turned off.
  NullProgress quiet;
  EXPECT_EQ(DetectAllShapes(in, o, quiet)[1].shapes.size(), 1u);
  o.shape_seed_across_views = false;
  EXPECT_TRUE(DetectAllShapes(in, o, quiet)[1].shapes.empty());
  // Without hysteresis nothing is seeded.
  o.shape_grow_height = o.tau;
  for (const char c : SeededLandmarks(in, o)) EXPECT_EQ(c, 0);
}

// ---- alpha shapes -----------------------------------------------------------------

double Area(const std::vector<Eigen::Vector2d>& p, const std::vector<Face>& tris) {
  double a = 0;
  for (const Face& f : tris) {
    const Eigen::Vector2d u = p[static_cast<std::size_t>(f[1])] - p[static_cast<std::size_t>(f[0])];
    const Eigen::Vector2d v = p[static_cast<std::size_t>(f[2])] - p[static_cast<std::size_t>(f[0])];
    a += 0.5 * (u.x() * v.y() - u.y() * v.x());  // counter-clockwise: positive
  }
  return a;
}

Eigen::Vector2d Centroid(const std::vector<Eigen::Vector2d>& p, const Face& f) {
  return (p[static_cast<std::size_t>(f[0])] + p[static_cast<std::size_t>(f[1])] + p[static_cast<std::size_t>(f[2])]) /
         3.0;
}

TEST(AlphaShape, GridWithAHoleLargerThanAlphaKeepsTheHole) {
  // A 1 m square grid at 5 cm without the points within 0.3 m of its centre.
  std::vector<Eigen::Vector2d> p;
  const Eigen::Vector2d c(0.5, 0.5);
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const Eigen::Vector2d q(0.05 * i, 0.05 * j);
      if ((q - c).norm() > 0.3) p.push_back(q);
    }
  }
  const std::vector<Face> tris = AlphaShapeTriangles(p, 0.12);
  ASSERT_FALSE(tris.empty());
  for (const Face& f : tris) {
    EXPECT_GT((Centroid(p, f) - c).norm(), 0.25) << "a triangle spans the hole";
  }
  // Every triangle is counter-clockwise, and the area is the square less the
  // hole (the hole's rim is a polygon through the grid, a little larger).
  const double area = Area(p, tris);
  EXPECT_GT(area, 1.0 - M_PI * 0.33 * 0.33);
  EXPECT_LT(area, 1.0 - M_PI * 0.27 * 0.27);
  // With alpha larger than the hole, it closes: the whole square.
  EXPECT_NEAR(Area(p, AlphaShapeTriangles(p, 1.0)), 1.0, 1e-9);
}

TEST(AlphaShape, RingGivesAnAnnulus) {
  std::vector<Eigen::Vector2d> p;
  for (int r = 0; r < 3; ++r) {
    const double radius = 0.5 + 0.04 * r;
    for (int k = 0; k < 90; ++k) {
      const double a = 2 * M_PI * (k + 0.5 * r) / 90;
      p.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
  }
  const std::vector<Face> tris = AlphaShapeTriangles(p, 0.06);
  ASSERT_FALSE(tris.empty());
  for (const Face& f : tris) {
    const double r = Centroid(p, f).norm();
    EXPECT_GT(r, 0.49);
    EXPECT_LT(r, 0.59);
  }
  EXPECT_NEAR(Area(p, tris), M_PI * (0.58 * 0.58 - 0.5 * 0.5), 0.02);
}

TEST(AlphaShape, AlphaIsARadius) {
  // A right triangle with legs 0.2: circumradius = half the hypotenuse.
  const std::vector<Eigen::Vector2d> p = {{0, 0}, {0.2, 0}, {0, 0.2}};
  const double r = 0.5 * std::hypot(0.2, 0.2);
  EXPECT_EQ(AlphaShapeTriangles(p, r * 1.001).size(), 1u);
  EXPECT_TRUE(AlphaShapeTriangles(p, r * 0.999).empty());
}

TEST(AlphaShape, DegenerateInput) {
  EXPECT_TRUE(AlphaShapeTriangles({}, 0.1).empty());
  EXPECT_TRUE(AlphaShapeTriangles({{0, 0}, {1, 0}}, 10).empty());
  EXPECT_TRUE(AlphaShapeTriangles({{0, 0}, {0.1, 0}, {0.2, 0}, {0.3, 0}}, 10).empty());  // collinear
  // A repeated point stands for itself once, under its first index.
  const std::vector<Eigen::Vector2d> p = {{0, 0}, {0.1, 0}, {0, 0.1}, {0.1, 0}};
  const std::vector<Face> tris = AlphaShapeTriangles(p, 1.0);
  ASSERT_EQ(tris.size(), 1u);
  std::set<int> used(tris[0].begin(), tris[0].end());
  EXPECT_EQ(used, (std::set<int>{0, 1, 2}));
}

// ---- rays against shapes ------------------------------------------------------------

TEST(RayShape, RayTriangleFromOrigin) {
  const Eigen::Vector3d a(-1, -1, 2), b(1, -1, 2), c(0, 1, 2);
  double t = 0;
  ASSERT_TRUE(RayTriangleFromOrigin(Eigen::Vector3d(0, 0, 1), a, b, c, &t));
  EXPECT_DOUBLE_EQ(t, 2.0);
  ASSERT_TRUE(RayTriangleFromOrigin(Eigen::Vector3d(0, 0, 4), a, c, b, &t));  // either winding; t in |dir| units
  EXPECT_DOUBLE_EQ(t, 0.5);
  EXPECT_FALSE(RayTriangleFromOrigin(Eigen::Vector3d(0, 0, -1), a, b, c, &t));  // behind
  EXPECT_FALSE(RayTriangleFromOrigin(Eigen::Vector3d(2, 0, 1), a, b, c, &t));   // beside
  EXPECT_FALSE(RayTriangleFromOrigin(Eigen::Vector3d(1, 0, 0), a, b, c, &t));   // parallel
}

// A 2.5-D shape: a grid of features over camera (x, y), lifted by z(x, y).
DetectedShape GridShape(int n, double spacing, double (*z)(double, double), std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.3 * spacing, 0.3 * spacing);
  std::vector<Eigen::Vector2d> xy;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) xy.emplace_back(-0.5 + spacing * i + jitter(rng), -0.4 + spacing * j + jitter(rng));
  }
  DetectedShape s;
  for (std::size_t i = 0; i < xy.size(); ++i) {
    s.points.push_back(static_cast<int>(i));
    s.vertices_c.emplace_back(xy[i].x(), xy[i].y(), z(xy[i].x(), xy[i].y()));
    s.deviation.push_back(0);
  }
  for (const Face& f : AlphaShapeTriangles(xy, 1.5 * spacing)) s.triangles.push_back({f[0], f[2], f[1]});
  return s;
}

double Bumpy(double x, double y) { return 1.5 - 0.1 * std::exp(-(x * x + y * y) / 0.02) + 0.05 * x; }

TEST(RayShape, FirstHitIsTheNearestAndOnTheShape) {
  std::mt19937 rng(3);
  const DetectedShape s = GridShape(10, 0.08, Bumpy, rng);
  ASSERT_GT(s.triangles.size(), 50u);
  // Straight ahead through the bump's top.
  const Eigen::Vector3d dir(0.001, 0.002, 1);
  const ShapeHit h = FirstShapeHit(s, dir);
  ASSERT_TRUE(h.hit);
  // The point lies on the triangle met: between its corners' depths, and on its plane.
  const Face& f = s.triangles[static_cast<std::size_t>(h.triangle)];
  const Eigen::Vector3d &a = s.vertices_c[static_cast<std::size_t>(f[0])],
                        &b = s.vertices_c[static_cast<std::size_t>(f[1])],
                        &c = s.vertices_c[static_cast<std::size_t>(f[2])];
  const Eigen::Vector3d p = h.t * dir;
  EXPECT_GE(p.z(), std::min({a.z(), b.z(), c.z()}) - 1e-12);
  EXPECT_LE(p.z(), std::max({a.z(), b.z(), c.z()}) + 1e-12);
  EXPECT_NEAR((p - a).dot((b - a).cross(c - a).normalized()), 0.0, 1e-12);
  EXPECT_LT(p.z(), 1.45);  // on the bump, nearer than the surface around it
  // A shape in front of another: the nearer one wins.
  DetectedShape two = s;
  const int offset = static_cast<int>(two.vertices_c.size());
  for (const auto& v : s.vertices_c) two.vertices_c.push_back(v * 2.0);  // the same, twice as far
  for (const Face& f : s.triangles) two.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  const ShapeHit near = FirstShapeHit(two, Eigen::Vector3d(0.01, 0.01, 1));
  ASSERT_TRUE(near.hit);
  EXPECT_LT(near.triangle, static_cast<int>(s.triangles.size()));
  EXPECT_FALSE(FirstShapeHit(s, Eigen::Vector3d(3, 0, 1)).hit);  // outside the footprint
}

TEST(RayShape, FootprintGridIsBitIdenticalToTryingEveryTriangle) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  std::size_t hits = 0, misses = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const DetectedShape s = GridShape(6 + 3 * trial, 0.06, Bumpy, rng);
    const ShapeFootprint fp(s);
    ASSERT_TRUE(fp.narrow());
    for (int k = 0; k < 4000; ++k) {
      const Eigen::Vector3d dir(u(rng), u(rng), 1.0 + 0.5 * u(rng));
      const ShapeHit a = FirstShapeHit(s, dir), b = fp.Hit(dir);
      ASSERT_EQ(a.hit, b.hit);
      if (!a.hit) {
        ++misses;
        continue;
      }
      ++hits;
      ASSERT_EQ(a.triangle, b.triangle);
      ASSERT_EQ(a.t, b.t);
      // The cone holds every direction that hits.
      EXPECT_GE(fp.axis().dot(dir.normalized()), fp.cos_half_angle());
    }
    // Rays through the shape's own vertices and edges (the grid's cell borders).
    for (const Face& f : s.triangles) {
      const Eigen::Vector3d& p = s.vertices_c[static_cast<std::size_t>(f[0])];
      const Eigen::Vector3d& q = s.vertices_c[static_cast<std::size_t>(f[1])];
      for (const Eigen::Vector3d& dir : {p, Eigen::Vector3d(0.5 * (p + q))}) {
        const ShapeHit a = FirstShapeHit(s, dir), b = fp.Hit(dir);
        ASSERT_EQ(a.hit, b.hit);
        ASSERT_EQ(a.triangle, b.triangle);
        ASSERT_EQ(a.t, b.t);
      }
    }
  }
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(misses, 1000u);
}

// ---- the moving average of eq. 15 ----------------------------------------------------------

TEST(MovingAverage, IsTheMeanOfTheHitsAndForgetsThePrior) {
  MovingAverage m;
  m.value = Eigen::Vector3d(100, 100, 100);  // v_0: the prior vertex
  const std::vector<Eigen::Vector3d> p = {{1, 2, 3}, {3, 2, 1}, {2, 5, 2}, {0, -1, 6}};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    m.Add(p[i]);
    sum += p[i];
    EXPECT_EQ(m.n, static_cast<int>(i + 1));
    EXPECT_TRUE(m.value.isApprox(sum / static_cast<double>(i + 1), 1e-14));
  }
  // v_1 = p_1 exactly (n = 0 gives the prior no weight).
  MovingAverage one;
  one.value = Eigen::Vector3d(7, 7, 7);
  one.Add(Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(one.value, Eigen::Vector3d(0.1, 0.2, 0.3));
}

// ---- the peak-keeping rule ---------------------------------------------------------------

TEST(CombineHits, KeepsASupportedPeakAndIgnoresALoneOutlier) {
  const Eigen::Vector3d v(1, 2, 0), n(0, 0, -1);  // a bottom vertex, outward normal down
  auto at = [&](double h) { return Eigen::Vector3d(v + h * n); };
  FusionRule rule;  // keep peaks, support 2, band 5 mm
  int support = 0;
  // Two views reach a narrow 0.18 m peak over this vertex, four others land
  // lower on its flank: the mean (eq. 15) flattens it, the rule keeps it.
  const std::vector<Eigen::Vector3d> flank = {at(0.18), at(0.12), at(0.179), at(0.10), at(0.09), at(0.11)};
  EXPECT_NEAR(CombineHits(flank, v, n, rule, &support).z(), -0.179, 1e-12);
  EXPECT_EQ(support, 2);
  FusionRule mean;
  mean.keep_peaks = false;
  EXPECT_NEAR(CombineHits(flank, v, n, mean, &support).z(), -(0.18 + 0.12 + 0.179 + 0.10 + 0.09 + 0.11) / 6, 1e-12);
  EXPECT_EQ(support, 6);
  // One wrong hit far above the rest cannot raise the vertex: it rests on
  // the second highest and the hits within the band below it.
  const std::vector<Eigen::Vector3d> wrong = {at(0.002), at(0.40), at(-0.001), at(0.001)};
  EXPECT_NEAR(CombineHits(wrong, v, n, rule, &support).z(), -(0.002 - 0.001 + 0.001) / 3, 1e-12);
  EXPECT_EQ(support, 4);
  // Noise about the hull: the band averages what lies just below the
  // second highest hit.
  const std::vector<Eigen::Vector3d> noise = {at(0.003), at(-0.002), at(0.001), at(0.004), at(-0.004)};
  EXPECT_NEAR(CombineHits(noise, v, n, rule, &support).z(), -(0.003 + 0.001 - 0.002) / 3, 1e-12);
  EXPECT_EQ(support, 4);
  // A vertex with one hit stays where it was.
  EXPECT_EQ(CombineHits({at(0.15)}, v, n, rule, &support), v);
  EXPECT_EQ(support, 0);
  rule.support = 1;
  EXPECT_NEAR(CombineHits({at(0.15)}, v, n, rule, &support).z(), -0.15, 1e-12);
}

// ---- hull zones and ratings ------------------------------------------------------------

TEST(HullZones, SidesStationsAndDistances) {
  // Forward +x, up +z: port is +y. A 100 m hull from x = 0 (stern) to 100 (bow).
  const HullFrame h(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 0.0, 100.0, 20, 45.0);
  EXPECT_TRUE(h.port().isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(h.Side(Eigen::Vector3d(0, 0, -1)), HullSide::kBottom);
  EXPECT_EQ(h.Side(Eigen::Vector3d(0, 0.99, -1)), HullSide::kBottom);  // 44.7 deg off down
  EXPECT_EQ(h.Side(Eigen::Vector3d(0, 1.01, -1)), HullSide::kPort);    // 45.3 deg
  EXPECT_EQ(h.Side(Eigen::Vector3d(0, -1.01, -1)), HullSide::kStarboard);
  EXPECT_EQ(h.Side(Eigen::Vector3d(0, -1, 0.5)), HullSide::kStarboard);  // flaring side
  EXPECT_EQ(h.Side(Eigen::Vector3d(0, 0, 1)), HullSide::kNone);          // deck
  EXPECT_EQ(h.Side(Eigen::Vector3d(0.3, 0.1, 1)), HullSide::kNone);
  EXPECT_DOUBLE_EQ(h.DistanceFromBow(Eigen::Vector3d(100, 3, -2)), 0.0);
  EXPECT_DOUBLE_EQ(h.DistanceFromBow(Eigen::Vector3d(25, 0, 0)), 75.0);
  EXPECT_EQ(h.Station(Eigen::Vector3d(99.9, 0, 0)), 0);  // at the bow
  EXPECT_EQ(h.Station(Eigen::Vector3d(94.9, 0, 0)), 1);  // 5.1 m aft
  EXPECT_EQ(h.Station(Eigen::Vector3d(0.1, 0, 0)), 19);  // at the stern
  EXPECT_EQ(h.Station(Eigen::Vector3d(-3, 0, 0)), 19);   // beyond: clamped
  EXPECT_EQ(h.Station(Eigen::Vector3d(103, 0, 0)), 0);
  EXPECT_EQ(h.Zone(Eigen::Vector3d(94.9, 0, 0), Eigen::Vector3d(0, -1, 0)),
            HullFrame::ZoneIndex(1, HullSide::kStarboard));
  EXPECT_EQ(h.Zone(Eigen::Vector3d(94.9, 0, 0), Eigen::Vector3d(0, 0, 1)), -1);
}

TEST(HullZones, AxesFromTheContract) {
  TriangleMesh m;
  m.vertices = {{-10, 0, 0}, {30, 0, 0}, {0, 5, 0}, {0, 0, 8}};
  m.faces = {{0, 1, 2}};
  // model_axes given: forward along -y of M, up +x.
  const HullFrame a = MakeHullFrame(m, ModelAxes{{0, -2, 0}, {1, 0, 0}}, Pose(), 20, 45);
  EXPECT_TRUE(a.forward().isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_TRUE(a.up().isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_NEAR(a.length(), 5.0, 1e-12);  // y from 0 to 5
  // Without: forward +x, up the axis of M that x_gM maps closest to -z of g.
  // The simulator's placement turns z of M to -z of g (up, since z is depth).
  const Pose upright = Pose::FromXyzRpy(1, 2, 3, M_PI, 0, 0.4);
  const HullFrame b = MakeHullFrame(m, std::nullopt, upright, 20, 45);
  EXPECT_TRUE(b.forward().isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(b.up().isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(b.length(), 40.0, 1e-12);
  // A model whose y axis points up in g.
  const Pose y_up = Pose::FromXyzRpy(0, 0, 0, -M_PI / 2, 0, 0);  // M's y -> g's -z
  EXPECT_TRUE(MakeHullFrame(m, std::nullopt, y_up, 20, 45).up().isApprox(Eigen::Vector3d::UnitY()));
  // Forward parallel to up: refused.
  EXPECT_THROW(MakeHullFrame(m, ModelAxes{{0, 0, 1}, {0, 0, 2}}, Pose(), 20, 45), InputError);
}

TEST(Fouling, RatingsOfMepc378) {
  EXPECT_EQ(RateCover(0.0), FoulingRating::kZeroToOne);
  EXPECT_EQ(RateCover(0.99), FoulingRating::kZeroToOne);
  EXPECT_EQ(RateCover(1.0), FoulingRating::kLight);
  EXPECT_EQ(RateCover(15.0), FoulingRating::kLight);
  EXPECT_EQ(RateCover(15.01), FoulingRating::kMedium);
  EXPECT_EQ(RateCover(40.0), FoulingRating::kMedium);
  EXPECT_EQ(RateCover(40.01), FoulingRating::kHeavy);
  EXPECT_EQ(RateCover(100.0), FoulingRating::kHeavy);
  EXPECT_STREQ(FoulingRatingName(FoulingRating::kZeroToOne), "0-1");
  EXPECT_STREQ(FoulingRatingName(FoulingRating::kUninspected), "uninspected");
}

TEST(Fouling, UnseenZonesAreUninspectedNotClean) {
  const HullFrame h(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 0.0, 20.0, 2, 45.0);
  InspectionCoverage in;
  in.hull_area.assign(6, 10.0);
  in.inspected_area = {8.0, 0.0, 0.0, 4.0, 1.0, 0.0};  // station 0 bottom; station 1 bottom, port
  ObjectDetection obj;
  obj.zone_covered_area = {0.04, 0, 0, 1.0, 0.5, 0};
  obj.zone_height_integral = {0.002, 0, 0, 0.1, 0.05, 0};
  obj.zone_max_height = {0.07, 0, 0, 0.2, 0.1, 0};
  obj.zone_objects = {1, 0, 0, 2, 1, 0};
  const std::vector<ZoneAssessment> z = AssessFouling(h, in, obj);
  ASSERT_EQ(z.size(), 6u);
  EXPECT_EQ(z[0].rating, FoulingRating::kZeroToOne);  // 0.5 %
  EXPECT_NE(z[0].note.find("invisible"), std::string::npos);
  EXPECT_EQ(z[1].rating, FoulingRating::kUninspected);
  EXPECT_EQ(z[2].rating, FoulingRating::kUninspected);
  EXPECT_EQ(z[3].rating, FoulingRating::kMedium);  // 25 %
  EXPECT_NEAR(z[3].cover_percent, 25.0, 1e-12);
  EXPECT_NEAR(z[3].mean_height, 0.1, 1e-12);
  EXPECT_EQ(z[4].rating, FoulingRating::kHeavy);  // 50 % of the 10 % inspected
  EXPECT_NE(z[4].note.find("only 10 %"), std::string::npos);
  EXPECT_EQ(z[3].station, 1);
  EXPECT_EQ(z[3].side, HullSide::kBottom);
  EXPECT_DOUBLE_EQ(z[3].from_bow, 10.0);
}

// ---- exact clipping ------------------------------------------------------------------------

TEST(SurfaceClip, AreaAboveAThresholdOfALinearValue) {
  // The unit right triangle with value x: the part with x >= 0.5 is a
  // triangle of legs 0.5 (area 1/8), where the mean value is 2/3.
  ClipPolygon poly = {{{0, 0, 0}, 0.0}, {{1, 0, 0}, 1.0}, {{0, 1, 0}, 0.0}};
  ClipKeep(poly, [](const ClipVertex& v) { return v.value - 0.5; });
  const ClipMoments m = Moments(poly);
  EXPECT_NEAR(m.area, 0.125, 1e-15);
  EXPECT_NEAR(m.value / m.area, 2.0 / 3.0, 1e-15);
  EXPECT_TRUE((m.first / m.area).isApprox(Eigen::Vector3d(2.0 / 3.0, 1.0 / 6.0, 0), 1e-14));
  // Nothing and everything.
  ClipPolygon none = {{{0, 0, 0}, 0.0}, {{1, 0, 0}, 1.0}, {{0, 1, 0}, 0.0}};
  ClipKeep(none, [](const ClipVertex& v) { return v.value - 2; });
  EXPECT_EQ(Moments(none).area, 0.0);
  ClipPolygon all = {{{0, 0, 0}, 0.0}, {{1, 0, 0}, 1.0}, {{0, 1, 0}, 0.0}};
  ClipKeep(all, [](const ClipVertex& v) { return v.value + 1; });
  EXPECT_NEAR(Moments(all).area, 0.5, 1e-15);
  // Two slabs of a square's triangle add up to it.
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    ClipPolygon t = {{{0, 0, 0}, 0.0}, {{2, 0, 0}, 0.0}, {{0, 2, 0}, 0.0}};
    ClipKeep(t, [k](const ClipVertex& v) { return v.p.x() - 0.5 * k; });
    ClipKeep(t, [k](const ClipVertex& v) { return 0.5 * (k + 1) - v.p.x(); });
    sum += Moments(t).area;
  }
  EXPECT_NEAR(sum, 2.0, 1e-14);
}

// ---- refinement regions and the cone tree ---------------------------------------------------------

TEST(RefinementRegion, CellsDilationAndInclusion) {
  RefinementRegion a;
  a.Add(Eigen::Vector3d(0.01, 0.01, 0.01));
  EXPECT_EQ(a.num_cells(), 1u);
  EXPECT_TRUE(a.Contains(Eigen::Vector3d(0.025, 0.001, 0.03)));
  EXPECT_FALSE(a.Contains(Eigen::Vector3d(0.06, 0.01, 0.01)));
  EXPECT_TRUE(a.Contains(Eigen::Vector3d(0.02, 0.02, 0.02)));
  RefinementRegion b = a;
  b.Dilate(0.10);  // two cells: the ball of radius 2 in cell units
  EXPECT_EQ(b.num_cells(), 33u);
  EXPECT_TRUE(b.Contains(Eigen::Vector3d(0.11, 0.01, 0.01)));
  EXPECT_FALSE(b.Contains(Eigen::Vector3d(0.11, 0.11, 0.01)));
  EXPECT_TRUE(b.Includes(a));
  EXPECT_FALSE(a.Includes(b));
  RefinementRegion far;
  far.Add(Eigen::Vector3d(-120.3, 45.2, -7.9));  // negative and large coordinates
  EXPECT_TRUE(far.Contains(Eigen::Vector3d(-120.3, 45.2, -7.9)));
  EXPECT_FALSE(b.Includes(far));
  b.Merge(far);
  EXPECT_TRUE(b.Includes(far));
  EXPECT_EQ(b.CellCentres().size(), 34u);
}

TEST(PointConeTree, VisitsEveryPointInsideBallAndCone) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<Eigen::Vector3d> pts(5000);
  for (auto& p : pts) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  const PointConeTree tree(pts);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d apex(u(rng), u(rng), u(rng));
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double half = 0.05 + 0.02 * trial, radius = 1 + 0.1 * trial;
    std::vector<int> visited;
    tree.Query(apex, radius, axis, std::cos(half), std::sin(half), true, [&](int i) { visited.push_back(i); });
    std::sort(visited.begin(), visited.end());
    EXPECT_TRUE(std::adjacent_find(visited.begin(), visited.end()) == visited.end());  // once each
    for (int i = 0; i < static_cast<int>(pts.size()); ++i) {
      const Eigen::Vector3d d = pts[static_cast<std::size_t>(i)] - apex;
      const bool inside = d.norm() <= radius && d.normalized().dot(axis) >= std::cos(half);
      if (inside) {
        EXPECT_TRUE(std::binary_search(visited.begin(), visited.end(), i)) << "trial " << trial << " point " << i;
      }
    }
    if (half < 0.3 && radius < 2) {
      EXPECT_LT(visited.size(), pts.size() / 10);  // it culls
    }
  }
}

}  // namespace
}  // namespace hull
