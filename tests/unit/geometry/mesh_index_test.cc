// MeshIndex and PointIndex against closed-form answers and brute force.
#include "geometry/mesh_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <thread>

#include "geometry/mesh_io.h"
#include "geometry/point_index.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

using Eigen::Vector3d;
using test::MakeBox;
using test::MakeCylinder;
using test::MakeGrid;
using test::MakeIcosphere;

// ---- brute force, written independently of the index -----------------------

// Closest point on a triangle by projection onto its plane, else the
// nearest point of its three edges.
Vector3d BruteClosestOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Vector3d x = p - ((p - a).dot(n) / n2) * n;
    const double u = (b - x).cross(c - x).dot(n), v = (c - x).cross(a - x).dot(n), w = (a - x).cross(b - x).dot(n);
    if (u >= 0 && v >= 0 && w >= 0) return x;
  }
  Vector3d best = a;
  double best_d = std::numeric_limits<double>::infinity();
  const Vector3d* pts[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Vector3d& s = *pts[k];
    const Vector3d& e = *pts[(k + 1) % 3];
    const double len2 = (e - s).squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - s).dot(e - s) / len2, 0.0, 1.0) : 0.0;
    const Vector3d x = s + t * (e - s);
    if ((x - p).norm() < best_d) {
      best_d = (x - p).norm();
      best = x;
    }
  }
  return best;
}

// Distance from q to face f, worked out relative to q for full precision.
double FaceDistance(const TriangleMesh& m, int f, const Vector3d& q) {
  const Face& F = m.faces[f];
  return BruteClosestOnTriangle(Vector3d::Zero(), m.vertices[F[0]] - q, m.vertices[F[1]] - q, m.vertices[F[2]] - q)
      .norm();
}

double BruteDistance(const TriangleMesh& m, const Vector3d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) best = std::min(best, FaceDistance(m, f, q));
  return best;
}

// First hit by Moeller-Trumbore over every face, in double.
double BruteRay(const TriangleMesh& m, const Vector3d& o, const Vector3d& d, int* face) {
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
    const Vector3d& v0 = m.vertices[m.faces[f][0]];
    const Vector3d e1 = m.vertices[m.faces[f][1]] - v0, e2 = m.vertices[m.faces[f][2]] - v0;
    const Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) continue;
    const Vector3d s = o - v0;
    const double u = s.dot(p) / det;
    const Vector3d qv = s.cross(e1);
    const double v = d.dot(qv) / det;
    const double t = e2.dot(qv) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && t > 0 && t < best) {
      best = t;
      *face = f;
    }
  }
  return best;
}

Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Vector3d v(n(rng), n(rng), n(rng));
  return v.normalized();
}

// Points spread over and around a mesh: near its faces (within a few cm,
// like landmarks), inside, and far away.
std::vector<Vector3d> QueryPoints(const TriangleMesh& m, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const Eigen::AlignedBox3d box = m.Bounds();
  const double size = box.diagonal().norm();
  std::vector<Vector3d> pts;
  for (int i = 0; i < n; ++i) {
    const int kind = i % 3;
    if (kind == 0) {
      const int f = static_cast<int>(u(rng) * m.faces.size()) % static_cast<int>(m.faces.size());
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Face& F = m.faces[f];
      const Vector3d p =
          m.vertices[F[0]] + a * (m.vertices[F[1]] - m.vertices[F[0]]) + b * (m.vertices[F[2]] - m.vertices[F[0]]);
      pts.push_back(p + 0.05 * (2 * u(rng) - 1) * RandomUnit(rng));
    } else if (kind == 1) {
      pts.push_back(box.min() + box.diagonal().cwiseProduct(Vector3d(u(rng), u(rng), u(rng))));
    } else {
      pts.push_back(box.center() + size * (0.5 + 2 * u(rng)) * RandomUnit(rng));
    }
  }
  return pts;
}

// Exact signed distance to an axis-aligned box.
double BoxSignedDistance(const Vector3d& q, const Vector3d& lo, const Vector3d& hi) {
  const Vector3d c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  const Vector3d d = (q - c).cwiseAbs() - h;
  const double outside = d.cwiseMax(0.0).norm();
  const double inside = std::min(d.maxCoeff(), 0.0);
  return outside + inside;
}

// ---- ray casting ----------------------------------------------------------------

TEST(MeshIndexRaycast, BoxKnownAnswers) {
  const TriangleMesh box = MakeBox(Vector3d(-1, -1, -1), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  RayHit h = index.Raycast(Vector3d(-5, 0.3, 0.2), Vector3d(2, 0, 0));  // direction need not be unit
  ASSERT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.range, 4.0);
  EXPECT_TRUE(h.point.isApprox(Vector3d(-1, 0.3, 0.2), 1e-15));
  EXPECT_NEAR(std::abs(box.face_normals[h.face].x()), 1.0, 1e-15);
  EXPECT_LT(box.face_normals[h.face].x(), 0);  // the x = -1 side
  // From inside: the far wall (faces are hit from both sides).
  h = index.Raycast(Vector3d(0, 0, 0), Vector3d(0, 0, 1));
  ASSERT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.range, 1.0);
  // Pointing away, or stopping short, or starting past the first wall.
  EXPECT_FALSE(index.Raycast(Vector3d(-5, 0, 0), Vector3d(-1, 0, 0)).hit);
  EXPECT_FALSE(index.Raycast(Vector3d(-5, 0, 0), Vector3d(1, 0, 0), 3.9).hit);
  h = index.Raycast(Vector3d(-5, 0.1, 0.2), Vector3d(1, 0, 0), 1e30, 4.5);
  ASSERT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.range, 6.0);
  EXPECT_FALSE(index.Raycast(Vector3d(-5, 0, 0), Vector3d::Zero()).hit);
}

TEST(MeshIndexRaycast, EdgesAndVerticesAreWatertight) {
  // The x = 0 side is split along y + z = 1; rays along that diagonal and
  // through the corners must not slip between the two triangles.
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  for (double y = 0.0; y <= 1.0; y += 0.125) {
    const RayHit h = index.Raycast(Vector3d(-3, y, 1.0 - y), Vector3d(1, 0, 0));
    ASSERT_TRUE(h.hit) << "y = " << y;
    EXPECT_DOUBLE_EQ(h.range, 3.0);
  }
  // A dense fan of rays through the middle of a subdivided sphere: all hit.
  const TriangleMesh sphere = MakeIcosphere(1.0, 3);
  const MeshIndex sindex(sphere);
  std::mt19937 rng(2);
  for (int i = 0; i < 2000; ++i) {
    const Vector3d d = RandomUnit(rng);
    EXPECT_TRUE(sindex.Raycast(Vector3d::Zero(), d).hit);
    // Aimed exactly at a vertex from outside.
    const Vector3d& v = sphere.vertices[i % sphere.vertices.size()];
    const RayHit h = sindex.Raycast(3.0 * v, -v);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.range, 2.0, 1e-12);
  }
}

TEST(MeshIndexRaycast, RayStartingOnTheSurfaceLeavesIt) {
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  // Starts on the bottom and goes up: the top at 1, not the bottom at 0.
  const RayHit h = index.Raycast(Vector3d(0.3, 0.4, 0.0), Vector3d(0, 0, 1));
  ASSERT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.range, 1.0);
}

TEST(MeshIndexRaycast, SphereMatchesAnalyticAndBruteForce) {
  const double R = 3.0;
  const Vector3d centre(10, -4, 2);
  const TriangleMesh sphere = MakeIcosphere(R, 4, centre);
  const double sag = test::IcosphereSagitta(sphere, R, centre);
  const MeshIndex index(sphere);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const Vector3d o = centre + 8.0 * RandomUnit(rng);
    const Vector3d target = centre + 2.5 * Vector3d(u(rng), u(rng), u(rng));
    const Vector3d d = (target - o).normalized();
    const RayHit h = index.Raycast(o, target - o);
    int bf = -1;
    const double bt = BruteRay(sphere, o, d, &bf);
    // The analytic sphere: the mesh lies within the sagitta inside it.
    const double b = d.dot(o - centre), c = (o - centre).squaredNorm() - R * R;
    const double disc = b * b - c;
    if (!h.hit) {
      EXPECT_FALSE(std::isfinite(bt)) << "missed a face brute force hits, ray " << i;
      continue;
    }
    ++hits;
    ASSERT_GT(disc, 0);
    const double t_sphere = -b - std::sqrt(disc);
    EXPECT_GE(h.range, t_sphere - 1e-12);
    EXPECT_LE((h.point - centre).norm(), R + 1e-12);
    EXPECT_GE((h.point - centre).norm(), R - sag - 1e-12);
    EXPECT_NEAR(h.range, bt, 1e-12 * bt);
    EXPECT_TRUE((h.point - (o + h.range * d)).norm() < 1e-12);
    // The point lies on the face's plane.
    const Face& F = sphere.faces[h.face];
    EXPECT_NEAR((h.point - sphere.vertices[F[0]]).dot(sphere.face_normals[h.face]), 0.0, 1e-12);
  }
  EXPECT_GT(hits, 450);
}

TEST(MeshIndexRaycast, FarFromTheOriginKeepsDoublePrecision) {
  // UTM-like coordinates: float alone would be off by centimetres.
  const Vector3d off(512345.25, 6123456.5, -30.0);
  const TriangleMesh box = MakeBox(off + Vector3d(0, 0, 0), off + Vector3d(2, 3, 4));
  const MeshIndex index(box);
  const RayHit h = index.Raycast(off + Vector3d(-10, 1.234567, 2.345678), Vector3d(1, 0, 0));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.range, 10.0, 1e-9);
  EXPECT_EQ(h.point.x(), off.x());
  EXPECT_NEAR(h.point.y(), off.y() + 1.234567, 1e-9);
}

TEST(MeshIndexRaycast, FanAgreesWithSingleRays) {
  const Vector3d centre(10, -4, 2);
  const TriangleMesh sphere = MakeIcosphere(3.0, 4, centre);
  const MeshIndex index(sphere);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const Vector3d& o : {Vector3d(centre + Vector3d(0, 0, -7)), centre}) {  // outside, and inside
    std::vector<Eigen::Vector3f> dirs;
    for (int i = 0; i < 700; ++i) {  // more than one Embree stream chunk
      dirs.push_back(Eigen::Vector3f(float(u(rng)), float(u(rng)), float(u(rng)) + 2.0f).normalized());
    }
    std::vector<RayHit> fan(dirs.size());
    index.RaycastFan(o, dirs.data(), static_cast<int>(dirs.size()), 20.0, fan.data());
    int hits = 0;
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      const RayHit one = index.Raycast(o, dirs[i].cast<double>(), 20.0);
      ASSERT_EQ(fan[i].hit, one.hit) << i;
      if (!one.hit) continue;
      ++hits;
      EXPECT_NEAR(fan[i].range, one.range, 1e-9);
      EXPECT_LT((fan[i].point - one.point).norm(), 1e-9);
      EXPECT_NEAR((fan[i].point - sphere.vertices[sphere.faces[fan[i].face][0]]).dot(sphere.face_normals[fan[i].face]),
                  0.0, 1e-12);
    }
    EXPECT_GT(hits, 300);
  }
  // t_max cuts the fan as it cuts a single ray.
  const Eigen::Vector3f up(0, 0, 1);
  RayHit h;
  index.RaycastFan(centre + Vector3d(0, 0, -7), &up, 1, 3.9, &h);
  EXPECT_FALSE(h.hit);
  index.RaycastFan(centre + Vector3d(0, 0, -7), &up, 1, 4.1, &h);
  EXPECT_TRUE(h.hit);
}

TEST(MeshIndexRaycast, OccludedTowardAgreesWithSegments) {
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 2);
  const Vector3d target(3.5, 0.5, 0.5);
  std::vector<Vector3d> points;
  for (int i = 0; i < 600; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  points.push_back(Vector3d(0, 0.5, 0.5));  // on the far face: the box shadows it
  points.push_back(Vector3d(1, 0.5, 0.5));  // on the near face: lit (its own face is skipped by t_min)
  std::unique_ptr<bool[]> blocked(new bool[points.size()]);
  index.OccludedToward(points.data(), static_cast<int>(points.size()), target, 1e-6, blocked.get());
  int shadowed = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vector3d d = target - points[i];
    const bool expected = index.Raycast(points[i], d, d.norm(), 1e-6).hit;
    EXPECT_EQ(blocked[i], expected) << points[i].transpose();
    shadowed += expected;
  }
  EXPECT_GT(shadowed, 50);
  EXPECT_TRUE(blocked[points.size() - 2]);
  EXPECT_FALSE(blocked[points.size() - 1]);
}

// ---- closest point --------------------------------------------------------------

void ExpectClosestMatchesBruteForce(const TriangleMesh& m, int n, unsigned seed) {
  const MeshIndex index(m);
  std::mt19937 rng(seed);
  for (const Vector3d& q : QueryPoints(m, n, rng)) {
    const ClosestPoint c = index.Closest(q);
    const double bd = BruteDistance(m, q);
    ASSERT_GE(c.face, 0);
    EXPECT_NEAR(c.distance, bd, 1e-12 * std::max(1.0, bd)) << "q = " << q.transpose();
    // The point itself is rounded to the precision of its coordinates.
    const double coord_ulp = std::numeric_limits<double>::epsilon() * q.cwiseAbs().maxCoeff();
    EXPECT_NEAR((c.point - q).norm(), c.distance, 1e-12 * std::max(1.0, bd) + 4 * coord_ulp);
    EXPECT_NEAR(FaceDistance(m, c.face, q), bd, 1e-12 * std::max(1.0, bd));
  }
}

TEST(MeshIndexClosest, MatchesBruteForceOnTestMeshes) {
  ExpectClosestMatchesBruteForce(MakeIcosphere(2.0, 3), 600, 1);
  ExpectClosestMatchesBruteForce(MakeBox(Vector3d(-1, -2, -3), Vector3d(4, 5, 6)), 600, 2);
  ExpectClosestMatchesBruteForce(MakeCylinder(0.15, 0.11, 48), 600, 3);
  ExpectClosestMatchesBruteForce(MakeGrid(20, 10, 0.5), 600, 4);
  TriangleMesh far = MakeIcosphere(5.0, 3);
  far.Transform(Pose::FromXyzRpy(512345.25, 6123456.5, -30, 0.1, 0.2, 0.3));
  ExpectClosestMatchesBruteForce(far, 600, 5);
}

TEST(MeshIndexClosest, HintGivesTheIdenticalAnswer) {
  TriangleMesh m = test::Subdivide(MakeCylinder(1.0, 2.0, 24));
  m.Append(MakeBox(Vector3d(3, 3, 3), Vector3d(4, 4, 4)));
  const MeshIndex index(m);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> face(0, static_cast<int>(m.faces.size()) - 1);
  for (const Vector3d& q : QueryPoints(m, 1500, rng)) {
    const ClosestPoint a = index.Closest(q);
    for (const int hint : {a.face, face(rng), face(rng), 0, static_cast<int>(m.faces.size()) - 1}) {
      const ClosestPoint b = index.Closest(q, hint);
      ASSERT_EQ(a.face, b.face) << "hint " << hint << " q " << q.transpose();
      ASSERT_EQ(a.point, b.point);
      ASSERT_EQ(a.distance, b.distance);
      ASSERT_EQ(index.SignedDistance(q), index.SignedDistance(q, hint));
    }
  }
  // Invalid hints are ignored.
  const Vector3d q(0.2, 0.1, 2.5);
  EXPECT_EQ(index.Closest(q, -7).face, index.Closest(q).face);
  EXPECT_EQ(index.Closest(q, 1 << 30).face, index.Closest(q).face);
}

TEST(MeshIndexClosest, ThinPlatesAndSoupsStayExact) {
  // Where the search around a hint cannot prove its answer (the other side
  // of a 2 mm plate is nearer than the hint's neighbours; an unwelded soup
  // has faces touching every vertex that do not use it), the BVH must
  // finish the search: still brute-force exact, still hint-independent.
  const TriangleMesh plate = test::Subdivide(test::Subdivide(MakeBox(Vector3d(0, 0, 0), Vector3d(1, 0.5, 0.002))));
  const TriangleMesh sphere = MakeIcosphere(1.0, 2);
  TriangleMesh soup;
  for (const Face& f : sphere.faces) {
    const int base = static_cast<int>(soup.vertices.size());
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(sphere.vertices[f[k]]);
    soup.faces.push_back({base, base + 1, base + 2});
  }
  soup.ComputeNormals();
  for (const TriangleMesh* m : {&plate, static_cast<const TriangleMesh*>(&soup)}) {
    const MeshIndex index(*m);
    std::mt19937 rng(31);
    std::uniform_int_distribution<int> face(0, static_cast<int>(m->faces.size()) - 1);
    for (const Vector3d& q : QueryPoints(*m, 900, rng)) {
      const ClosestPoint c = index.Closest(q);
      ASSERT_NEAR(c.distance, BruteDistance(*m, q), 1e-12);
      for (const int hint : {c.face, face(rng)}) {
        const ClosestPoint h = index.Closest(q, hint);
        ASSERT_EQ(h.face, c.face);
        ASSERT_EQ(h.point, c.point);
      }
    }
  }
}

TEST(MeshIndexClosest, TiesGoToTheLowestFace) {
  // On the box's edge region both sides are equally near.
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  const ClosestPoint c = index.Closest(Vector3d(1.5, 0.5, 1.5));
  EXPECT_TRUE(c.point.isApprox(Vector3d(1, 0.5, 1), 1e-15));
  EXPECT_NEAR(c.distance, std::sqrt(0.5), 1e-15);
  int lowest = -1;
  for (int f = 0; f < 12 && lowest < 0; ++f) {
    if (std::abs(FaceDistance(box, f, Vector3d(1.5, 0.5, 1.5)) - c.distance) < 1e-15) lowest = f;
  }
  EXPECT_EQ(c.face, lowest);
}

// ---- signed distances ---------------------------------------------------------------

TEST(MeshIndexSignedDistance, BoxMatchesTheExactFieldEverywhere) {
  // Including near edges and corners, where a face normal alone gives the
  // wrong sign: the pseudonormals must not.
  const Vector3d lo(-1, -0.5, 0), hi(2, 0.5, 1);
  const TriangleMesh box = MakeBox(lo, hi);
  const MeshIndex index(box);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::vector<Vector3d> qs;
  // Around every corner and edge midpoint, and in the whole volume.
  for (int i = 0; i < 8; ++i) {
    const Vector3d corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
    for (int k = 0; k < 200; ++k) qs.push_back(corner + Vector3d(u(rng), u(rng), u(rng)));
    for (int j = 0; j < 3; ++j) {
      Vector3d mid = corner;
      mid[j] = 0.5 * (lo[j] + hi[j]);
      for (int k = 0; k < 100; ++k) qs.push_back(mid + Vector3d(u(rng), u(rng), u(rng)));
    }
  }
  std::uniform_real_distribution<double> w(-3, 3);
  for (int k = 0; k < 2000; ++k) qs.push_back(Vector3d(w(rng), w(rng), w(rng)));
  for (const Vector3d& q : qs) {
    const double expect = BoxSignedDistance(q, lo, hi);
    ASSERT_NEAR(index.SignedDistance(q), expect, 1e-12) << "q = " << q.transpose();
  }
  // Named cases: outside a corner, outside an edge, inside near an edge.
  EXPECT_GT(index.SignedDistance(Vector3d(2.1, 0.6, 1.1)), 0);
  EXPECT_GT(index.SignedDistance(Vector3d(2.1, 0.0, 1.1)), 0);
  EXPECT_LT(index.SignedDistance(Vector3d(1.95, 0.0, 0.97)), 0);
}

TEST(MeshIndexSignedDistance, SphereAndCylinderSigns) {
  const double R = 1.5;
  const TriangleMesh sphere = MakeIcosphere(R, 3);
  const double sag = test::IcosphereSagitta(sphere, R);
  const MeshIndex sindex(sphere);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  int tested = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vector3d q(u(rng), u(rng), u(rng));
    const double r = q.norm();
    if (r > R - sag - 1e-9 && r < R + 1e-9) continue;  // between sphere and mesh
    const double sd = sindex.SignedDistance(q);
    EXPECT_EQ(sd > 0, r > R) << q.transpose();
    EXPECT_NEAR(std::abs(sd), BruteDistance(sphere, q), 1e-12);
    ++tested;
  }
  EXPECT_GT(tested, 2500);
  const TriangleMesh cyl = MakeCylinder(0.15, 0.11, 32);
  const MeshIndex cindex(cyl);
  EXPECT_LT(cindex.SignedDistance(Vector3d(0, 0, 0.05)), 0);
  EXPECT_LT(cindex.SignedDistance(Vector3d(0.1, 0.0, 0.105)), 0);
  EXPECT_GT(cindex.SignedDistance(Vector3d(0.16, 0.0, 0.115)), 0);  // beyond the rim
  EXPECT_GT(cindex.SignedDistance(Vector3d(0, 0, -0.01)), 0);
}

TEST(MeshIndexSignedDistance, OpenGridSignFollowsItsNormal) {
  const TriangleMesh grid = MakeGrid(8, 8, 0.25);
  const MeshIndex index(grid);
  EXPECT_NEAR(index.SignedDistance(Vector3d(1.0, 1.1, 0.3)), 0.3, 1e-15);
  EXPECT_NEAR(index.SignedDistance(Vector3d(1.0, 1.1, -0.3)), -0.3, 1e-15);
}

TEST(MeshIndexOrthogonal, SignOutsideAndInsideASphere) {
  const double R = 2.0;
  const TriangleMesh sphere = MakeIcosphere(R, 4);
  const MeshIndex index(sphere);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> s(-0.05, 0.05);
  std::uniform_int_distribution<int> face(0, static_cast<int>(sphere.faces.size()) - 1);
  for (int i = 0; i < 1000; ++i) {
    // Along a face normal from its centroid, the closest point is interior:
    // eq. 5 and the Euclidean signed distance both equal the offset.
    const int f = face(rng);
    const double off = s(rng);
    const Vector3d q = sphere.FaceCentroid(f) + off * sphere.face_normals[f];
    const SurfaceDistance h = index.OrthogonalSignedDistance(q);
    EXPECT_EQ(h.face, f);
    EXPECT_NEAR(h.signed_distance, off, 1e-13);
    EXPECT_NEAR(index.SignedDistance(q), off, 1e-13);
    EXPECT_TRUE(h.normal.isApprox(sphere.face_normals[f], 1e-15));
    EXPECT_NEAR((h.point - sphere.FaceCentroid(f)).norm(), 0.0, 1e-13);
  }
  // Far outside and deep inside.
  EXPECT_GT(index.OrthogonalSignedDistance(Vector3d(0, 0, 3)).signed_distance, 0.9);
  EXPECT_LT(index.OrthogonalSignedDistance(Vector3d(0.1, 0.2, 0.3)).signed_distance, -1.5);
}

TEST(MeshIndexOrthogonal, EqualsEuclideanAwayFromEdgesAndNotNearThem) {
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  // Over the middle of the top: both agree.
  const Vector3d q1(0.4, 0.6, 1.2);
  EXPECT_NEAR(index.OrthogonalSignedDistance(q1).signed_distance, 0.2, 1e-15);
  EXPECT_NEAR(index.SignedDistance(q1), 0.2, 1e-15);
  // Off an edge: the Euclidean distance is the hypotenuse, eq. 5 measures
  // against one face's plane only.
  const Vector3d q2(1.3, 0.5, 1.4);
  EXPECT_NEAR(index.SignedDistance(q2), 0.5, 1e-15);
  const double h = index.OrthogonalSignedDistance(q2).signed_distance;
  EXPECT_TRUE(std::abs(h - 0.3) < 1e-15 || std::abs(h - 0.4) < 1e-15) << h;
}

TEST(MeshIndexOrthogonal, NearestVertexVariant) {
  const TriangleMesh sphere = MakeIcosphere(1.0, 3);
  const MeshIndex index(sphere);
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> vert(0, static_cast<int>(sphere.vertices.size()) - 1);
  std::uniform_real_distribution<double> s(-0.02, 0.02);
  for (int i = 0; i < 300; ++i) {
    const int v = vert(rng);
    const Vector3d q = sphere.vertices[v] * (1.0 + s(rng));
    const SurfaceDistance h = index.OrthogonalSignedDistance(q, SurfaceLookup::kNearestVertex);
    EXPECT_EQ(index.NearestVertex(q), v);
    EXPECT_EQ(h.point, sphere.vertices[v]);
    const auto& faces = index.FacesOfVertex(v);
    EXPECT_NE(std::find(faces.begin(), faces.end(), h.face), faces.end());
    EXPECT_NEAR(h.signed_distance, (q - sphere.vertices[v]).dot(sphere.face_normals[h.face]), 1e-15);
    EXPECT_EQ(h.signed_distance > 0, q.norm() > 1.0);
  }
}

TEST(MeshIndexOrthogonal, PoseOverloadMapsTheLandmarkIntoTheModel) {
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  const Pose x_gM = Pose::FromXyzRpy(10, -3, 2, 0.1, -0.2, 1.3);
  const Vector3d q_M(0.4, 0.6, 1.2);
  const Vector3d l_g = x_gM * q_M;
  const SurfaceDistance a = index.OrthogonalSignedDistance(x_gM, l_g);
  const SurfaceDistance b = index.OrthogonalSignedDistance(q_M);
  EXPECT_NEAR(a.signed_distance, 0.2, 1e-12);
  EXPECT_EQ(a.face, b.face);
}

TEST(MeshIndex, FacesOfVertexAndNearestVertex) {
  const TriangleMesh box = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const MeshIndex index(box);
  int total = 0;
  for (int v = 0; v < 8; ++v) {
    for (int f : index.FacesOfVertex(v)) {
      const Face& F = box.faces[f];
      EXPECT_TRUE(F[0] == v || F[1] == v || F[2] == v);
    }
    total += static_cast<int>(index.FacesOfVertex(v).size());
  }
  EXPECT_EQ(total, 36);
  EXPECT_EQ(index.NearestVertex(Vector3d(0.9, 1.2, 0.1)), 3);  // (1, 1, 0)
}

TEST(MeshIndex, ConcurrentQueriesAgreeWithSerial) {
  const TriangleMesh m = MakeIcosphere(1.0, 4);
  const MeshIndex index(m);
  std::mt19937 rng(21);
  const std::vector<Vector3d> qs = QueryPoints(m, 4000, rng);
  std::vector<ClosestPoint> serial;
  for (const auto& q : qs) serial.push_back(index.Closest(q));
  std::vector<ClosestPoint> out(qs.size());
  std::vector<RayHit> rays(qs.size());
  auto work = [&](std::size_t begin, std::size_t step) {
    for (std::size_t i = begin; i < qs.size(); i += step) {
      out[i] = index.Closest(qs[i]);
      rays[i] = index.Raycast(qs[i], -qs[i]);
    }
  };
  std::thread t1(work, 0, 2), t2(work, 1, 2);
  t1.join();
  t2.join();
  for (std::size_t i = 0; i < qs.size(); ++i) {
    EXPECT_EQ(out[i].face, serial[i].face);
    EXPECT_EQ(out[i].point, serial[i].point);
    const RayHit r = index.Raycast(qs[i], -qs[i]);
    EXPECT_EQ(rays[i].face, r.face);
    EXPECT_EQ(rays[i].range, r.range);
  }
}

TEST(MeshIndex, EmptyMeshAnswersNothing) {
  const TriangleMesh empty;
  const MeshIndex index(empty);
  EXPECT_FALSE(index.Raycast(Vector3d::Zero(), Vector3d::UnitX()).hit);
  EXPECT_EQ(index.Closest(Vector3d::Zero()).face, -1);
}

TEST(MeshIndex, RejectsFacesOutOfRange) {
  TriangleMesh bad = MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  bad.faces[3][1] = 8;
  EXPECT_THROW(MeshIndex{bad}, std::invalid_argument);
}

TEST(MeshIndex, RealHullClosestMatchesBruteForce) {
  const std::string path = std::string(HI_SHARED_DATA_DIR) + "/dtmb5415.stl.gz";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "reference data absent: " << path;
  const TriangleMesh hull = LoadMesh(path);
  const MeshIndex index(hull);
  std::mt19937 rng(13);
  for (const Vector3d& q : QueryPoints(hull, 150, rng)) {
    const ClosestPoint c = index.Closest(q);
    EXPECT_NEAR(c.distance, BruteDistance(hull, q), 1e-9);
    EXPECT_EQ(index.Closest(q, c.face).face, c.face);
  }
}

// ---- point index ---------------------------------------------------------------------

TEST(PointIndex, NearestAndWithinMatchBruteForce) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-10, 10);
  std::vector<Vector3d> pts(3000);
  for (auto& p : pts) p = Vector3d(u(rng), u(rng), u(rng));
  const PointIndex index(pts);
  ASSERT_EQ(index.size(), pts.size());
  EXPECT_EQ(index.point(17), pts[17]);
  for (int i = 0; i < 200; ++i) {
    const Vector3d q(u(rng), u(rng), u(rng));
    std::vector<std::pair<double, int>> all;
    for (int j = 0; j < static_cast<int>(pts.size()); ++j) all.emplace_back((pts[j] - q).squaredNorm(), j);
    std::sort(all.begin(), all.end());
    const auto knn = index.Nearest(q, 12);
    ASSERT_EQ(knn.size(), 12u);
    for (int k = 0; k < 12; ++k) {
      EXPECT_EQ(knn[k].first, all[k].second);
      EXPECT_DOUBLE_EQ(knn[k].second, all[k].first);
    }
    const double r = 2.5;
    const auto within = index.Within(q, r);
    std::size_t expect = 0;
    while (expect < all.size() && all[expect].first < r * r) ++expect;
    ASSERT_EQ(within.size(), expect);
    for (std::size_t k = 0; k < expect; ++k) {
      EXPECT_EQ(within[k].first, all[k].second);
      if (k > 0) {
        EXPECT_LE(within[k - 1].second, within[k].second);
      }
    }
    // Unsorted: the same points with the same distances, in any order.
    auto unsorted = index.Within(q, r, false);
    std::sort(unsorted.begin(), unsorted.end());
    auto sorted_by_index = within;
    std::sort(sorted_by_index.begin(), sorted_by_index.end());
    EXPECT_EQ(unsorted, sorted_by_index);
  }
  EXPECT_EQ(index.Nearest(Vector3d::Zero(), 5000).size(), pts.size());
  EXPECT_TRUE(index.Nearest(Vector3d::Zero(), 0).empty());
  EXPECT_TRUE(index.Within(Vector3d::Zero(), -1).empty());
  const PointIndex empty({});
  EXPECT_TRUE(empty.Nearest(Vector3d::Zero(), 3).empty());
}

}  // namespace
}  // namespace hull
