// Every vertex's reported deviation is its distance to the CAD mesh: on a
// coarse, curved bottom (a shallow trough, faceted at 0.25 m, so that the
// remeshing's collapses cut its curvature) carrying a 0.12 m lump, the
// fused model's "deviation" of every vertex (fused or not) is checked
// against a brute-force point-triangle distance over every CAD face.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/mesh_index.h"
#include "keyframe_grid.h"
#include "mapping/mapper.h"
#include "mapping/mesh_refinement.h"
#include "mapping/refinement_region.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

// The trough's depth below z = 0 (outward normal roughly -z).
double Trough(double x) { return 0.08 * (x - 2.0) * (x - 2.0); }

TriangleMesh CurvedBottom() {
  TriangleMesh m = test::MakeGrid(16, 16, 0.25);
  for (auto& v : m.vertices) v.z() = Trough(v.x());
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  m.ComputeNormals();
  return m;
}

// Closest point on triangle (a, b, c) to p (Ericson 5.1.5), written out
// independently of the project's MeshIndex.
Eigen::Vector3d ClosestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Brute force over every face: the unsigned distance, and the sign of the
// offset along the closest face's outward normal.
double BruteSignedDistance(const TriangleMesh& m, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  double sign = 1;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const Face& F = m.faces[f];
    const Eigen::Vector3d q = ClosestOnTriangle(p, m.vertices[F[0]], m.vertices[F[1]], m.vertices[F[2]]);
    const double d = (p - q).norm();
    if (d < best) {
      best = d;
      sign = (p - q).dot(m.face_normals[f]) >= 0 ? 1 : -1;
    }
  }
  return sign * best;
}

MappingInput LumpScene() {
  MappingInput in;
  in.source = "curved test scene";
  in.model_axes = ModelAxes{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Vector2d lump(2.1, 1.9);
  auto add = [&](double x, double y) {
    const double r = (Eigen::Vector2d(x, y) - lump).norm();
    const double h = r < 0.25 ? 0.12 * (1 - (r / 0.25) * (r / 0.25)) : 0.0;
    in.landmarks.push_back({static_cast<std::int64_t>(in.landmarks.size()), Eigen::Vector3d(x, y, Trough(x) - h), h});
  };
  for (int i = 0; i < 800; ++i) add(4 * u(rng), 4 * u(rng));
  for (int i = 0; i < 150; ++i) {
    const double r = 0.25 * std::sqrt(u(rng)), a = 2 * M_PI * u(rng);
    add(lump.x() + r * std::cos(a), lump.y() + r * std::sin(a));
  }
  AddKeyframeGrid(in, 0, Eigen::Vector2d(1.6, 1.5), Eigen::Vector2d(0.4, 0.4));
  return in;
}

TEST(Deviation, RefinedVerticesLieOnTheCad) {
  const TriangleMesh cad = CurvedBottom();
  const MeshIndex index(cad);
  RefinementRegion region(0.1);
  for (double x = 1.5; x <= 2.6; x += 0.05) {
    for (double y = 1.4; y <= 2.4; y += 0.05) region.Add(Eigen::Vector3d(x, y, Trough(x)));
  }
  const RefinedMesh r = RefineMesh(cad, index, region, 0.03);
  ASSERT_GT(r.refined_faces, 300);
  double worst = 0;
  for (const auto& v : r.mesh.vertices) worst = std::max(worst, std::abs(BruteSignedDistance(cad, v)));
  EXPECT_LT(worst, 1e-9);
}

TEST(Deviation, EveryVertexReportsItsDistanceToTheCad) {
  const TriangleMesh cad = CurvedBottom();
  MappingOptions o;
  NullProgress p;
  const MappingResult r = RunMapping(LumpScene(), cad, o, p);
  const std::vector<double>& dev = *r.model.FindScalar("deviation");
  const std::vector<double>& fusions = *r.model.FindScalar("fusions");
  ASSERT_EQ(dev.size(), r.model.num_vertices());
  std::size_t fused = 0, lump = 0;
  double worst = 0;
  for (std::size_t v = 0; v < dev.size(); ++v) {
    const double truth = BruteSignedDistance(cad, r.model.vertices[v]);
    worst = std::max(worst, std::abs(dev[v] - truth));
    fused += fusions[v] > 0;
    lump += dev[v] > 0.08;
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(fused, 200u);
  EXPECT_GT(lump, 10u);
}

}  // namespace
}  // namespace hull
