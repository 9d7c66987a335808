// TriangleMesh: normals, area, volume, welding, orientation and topology on
// meshes with closed-form answers.
#include "geometry/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/test_meshes.h"

namespace hull {
namespace {

using Eigen::Vector3d;

TEST(TriangleMesh, BoxNormalsAreaAndVolume) {
  const TriangleMesh box = test::MakeBox(Vector3d(-1, 0, 2), Vector3d(1, 3, 6));
  EXPECT_DOUBLE_EQ(box.SurfaceArea(), 2 * (2 * 3 + 2 * 4 + 3 * 4));
  EXPECT_DOUBLE_EQ(box.SignedVolume(), 24.0);
  ASSERT_EQ(box.face_normals.size(), 12u);
  for (int f = 0; f < 12; ++f) {
    const Vector3d n = box.face_normals[f];
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0, 1e-15);  // axis aligned
    // Outward: the centroid moves away from the box centre along n.
    EXPECT_GT((box.FaceCentroid(f) - Vector3d(0, 1.5, 4)).dot(n), 0);
  }
  for (const Vector3d& n : box.vertex_normals) EXPECT_NEAR(n.norm(), 1.0, 1e-15);
  // A corner's area-weighted normal points diagonally out.
  EXPECT_GT(box.vertex_normals[7].minCoeff(), 0);
  EXPECT_LT(box.vertex_normals[0].maxCoeff(), 0);
}

TEST(TriangleMesh, IcosphereApproachesTheSphere) {
  const double R = 2.0;
  for (int s = 1; s <= 4; ++s) {
    const TriangleMesh m = test::MakeIcosphere(R, s);
    EXPECT_EQ(m.faces.size(), 20u * (1u << (2 * s)));
    const double sag = test::IcosphereSagitta(m, R);
    const double v = 4.0 / 3.0 * M_PI;
    EXPECT_LT(m.SignedVolume(), v * R * R * R);
    EXPECT_GT(m.SignedVolume(), v * std::pow(R - sag, 3));
    EXPECT_LT(m.SurfaceArea(), 4 * M_PI * R * R);
    EXPECT_GT(m.SurfaceArea(), 4 * M_PI * (R - sag) * (R - sag));
    EXPECT_TRUE(m.CheckTopology().closed);
  }
}

TEST(TriangleMesh, CylinderVolume) {
  const TriangleMesh c = test::MakeCylinder(0.15, 0.11, 64, -1.0);
  // A 64-gon prism.
  EXPECT_NEAR(c.SignedVolume(), 0.5 * 64 * 0.15 * 0.15 * std::sin(2 * M_PI / 64) * 0.11, 1e-15);
  EXPECT_NEAR(c.Bounds().min().z(), -1.0, 1e-15);
  EXPECT_TRUE(c.CheckTopology().closed);
}

TEST(TriangleMesh, WeldTurnsASoupIntoTheIndexedMesh) {
  const TriangleMesh box = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  TriangleMesh soup;
  std::vector<double> scalar;
  for (const Face& f : box.faces) {
    const int base = static_cast<int>(soup.vertices.size());
    for (int k = 0; k < 3; ++k) {
      soup.vertices.push_back(box.vertices[f[k]]);
      scalar.push_back(f[k]);  // the original vertex id travels with it
    }
    soup.faces.push_back({base, base + 1, base + 2});
  }
  // And one face that collapses to a line when welded.
  soup.vertices.push_back(Vector3d(0, 0, 0));
  soup.vertices.push_back(Vector3d(0, 0, 0));
  soup.vertices.push_back(Vector3d(1, 0, 0));
  scalar.insert(scalar.end(), {0, 0, 1});
  soup.faces.push_back({36, 37, 38});
  soup.SetScalar("id", scalar);
  EXPECT_EQ(soup.WeldVertices(), 31u);
  EXPECT_EQ(soup.vertices.size(), 8u);
  EXPECT_EQ(soup.faces.size(), 12u);  // the degenerate face is dropped
  EXPECT_TRUE(soup.CheckTopology().closed);
  EXPECT_DOUBLE_EQ(soup.SignedVolume(), 1.0);
  const auto& id = *soup.FindScalar("id");
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) EXPECT_EQ(soup.vertices[v], box.vertices[id[v]]);
  // With a tolerance, nearly coincident vertices merge too.
  TriangleMesh near = test::MakeGrid(2, 1, 1.0);
  near.vertices.push_back(Vector3d(1e-9, 0, 0));
  near.faces.push_back({6, 4, 3});
  EXPECT_EQ(near.WeldVertices(1e-6), 1u);
  const Face& last = near.faces.back();
  EXPECT_EQ(near.vertices[last[0]], Vector3d(0, 0, 0));
  EXPECT_EQ(near.vertices[last[1]], Vector3d(1, 1, 0));
  EXPECT_EQ(near.vertices[last[2]], Vector3d(0, 1, 0));
}

TEST(TriangleMesh, OrientOutwardFixesAnInsideOutSphere) {
  TriangleMesh s = test::MakeIcosphere(1.0, 2);
  for (auto& f : s.faces) std::swap(f[1], f[2]);
  s.ComputeNormals();
  ASSERT_LT(s.SignedVolume(), 0);
  const OrientationReport r = s.OrientOutward();
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.was_inside_out);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.faces_flipped, static_cast<int>(s.faces.size()));
  EXPECT_GT(s.SignedVolume(), 0);
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) EXPECT_GT(s.face_normals[f].dot(s.FaceCentroid(f)), 0);
}

TEST(TriangleMesh, OrientOutwardFixesSomeFlippedFacesOfABox) {
  TriangleMesh box = test::MakeBox(Vector3d(0, 0, 0), Vector3d(2, 1, 1));
  const std::vector<Face> good = box.faces;
  for (int f : {1, 5, 8}) std::swap(box.faces[f][1], box.faces[f][2]);
  const OrientationReport r = box.OrientOutward();
  EXPECT_TRUE(r.closed);
  EXPECT_FALSE(r.was_inside_out);
  EXPECT_EQ(r.faces_flipped, 3);
  EXPECT_DOUBLE_EQ(box.SignedVolume(), 2.0);
  for (int f = 0; f < 12; ++f) {
    // Same triangle, same cyclic winding as the good box.
    const Face& a = box.faces[f];
    const Face& b = good[f];
    const bool same = (a == b) || (a == Face{b[1], b[2], b[0]}) || (a == Face{b[2], b[0], b[1]});
    EXPECT_TRUE(same) << "face " << f;
  }
}

TEST(TriangleMesh, OpenGridTopologyAndConsistentWinding) {
  TriangleMesh grid = test::MakeGrid(4, 3, 0.5);
  const OrientationReport t = grid.CheckTopology();
  EXPECT_FALSE(t.closed);
  EXPECT_EQ(t.boundary_edges, 2 * (4 + 3));
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_DOUBLE_EQ(grid.SurfaceArea(), 2.0 * 1.5);
  // Flip every other face: orientation makes them agree again.
  for (std::size_t f = 0; f < grid.faces.size(); f += 2) std::swap(grid.faces[f][1], grid.faces[f][2]);
  const OrientationReport r = grid.OrientOutward();
  EXPECT_EQ(r.components, 1);
  EXPECT_FALSE(r.closed);
  const double z0 = grid.face_normals[0].z();
  EXPECT_NEAR(std::abs(z0), 1.0, 1e-15);
  for (const Vector3d& n : grid.face_normals) EXPECT_EQ(n.z(), z0);
}

TEST(TriangleMesh, NonManifoldEdgesAreCounted) {
  TriangleMesh m = test::MakeGrid(1, 1, 1.0);  // faces {0,1,3}, {0,3,2}
  m.vertices.push_back(Vector3d(0.5, 0.5, 1));
  m.faces.push_back({0, 3, 4});  // a third face on the diagonal
  const OrientationReport r = m.CheckTopology();
  EXPECT_EQ(r.non_manifold_edges, 1);
  EXPECT_FALSE(r.closed);
}

TEST(TriangleMesh, TransformAndMirror) {
  TriangleMesh box = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 2, 3));
  const Pose T = Pose::FromXyzRpy(5, -1, 2, 0.3, -0.2, 1.1);
  TriangleMesh moved = box;
  moved.Transform(T, 2.0);
  EXPECT_NEAR(moved.SignedVolume(), 48.0, 1e-12);
  EXPECT_TRUE(moved.vertices[7].isApprox(T * Vector3d(2, 4, 6), 1e-15));
  TriangleMesh mirrored = box;
  mirrored.Transform(Pose(), -1.0);
  EXPECT_NEAR(mirrored.SignedVolume(), 6.0, 1e-12);  // still outward
}

TEST(TriangleMesh, AppendKeepsSharedScalars) {
  TriangleMesh a = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  TriangleMesh b = test::MakeBox(Vector3d(2, 0, 0), Vector3d(3, 1, 1));
  a.SetScalar("deviation", std::vector<double>(8, 1.0));
  a.SetScalar("only_a", std::vector<double>(8, 2.0));
  b.SetScalar("deviation", std::vector<double>(8, 3.0));
  a.Append(b);
  EXPECT_EQ(a.vertices.size(), 16u);
  EXPECT_EQ(a.faces.size(), 24u);
  EXPECT_EQ(a.faces[12], (Face{8, 10, 9}));
  ASSERT_NE(a.FindScalar("deviation"), nullptr);
  EXPECT_EQ(a.FindScalar("deviation")->size(), 16u);
  EXPECT_EQ((*a.FindScalar("deviation"))[15], 3.0);
  EXPECT_EQ(a.FindScalar("only_a"), nullptr);
  EXPECT_DOUBLE_EQ(a.SignedVolume(), 2.0);
  EXPECT_EQ(a.OrientOutward().components, 2);
}

TEST(TestMeshes, SubdivideKeepsTheSurface) {
  const TriangleMesh box = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 2, 3));
  const TriangleMesh fine = test::Subdivide(test::Subdivide(box));
  EXPECT_EQ(fine.faces.size(), 12u * 16u);
  EXPECT_NEAR(fine.SignedVolume(), 6.0, 1e-12);
  EXPECT_NEAR(fine.SurfaceArea(), box.SurfaceArea(), 1e-12);
  EXPECT_TRUE(fine.CheckTopology().closed);
  // Shared midpoints: V - E + F = 2 for a sphere-like surface.
  const long V = static_cast<long>(fine.vertices.size()), F = static_cast<long>(fine.faces.size());
  EXPECT_EQ(V - 3 * F / 2 + F, 2);
}

}  // namespace
}  // namespace hull
