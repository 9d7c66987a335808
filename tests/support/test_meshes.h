// Small meshes made in code with known answers (COLMAP's scene/synthetic.h
// habit): closed, outward-oriented solids whose distances, areas and volumes
// are known in closed form, and an open flat grid. Every mesh returned has
// its normals computed.
#pragma once

#include <Eigen/Core>

#include "geometry/triangle_mesh.h"

namespace hull::test {

// Axis-aligned closed box [lo, hi]: 8 vertices, 12 faces, outward normals.
TriangleMesh MakeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// Icosphere: an icosahedron subdivided 1 -> 4 `subdivisions` times with every
// vertex projected onto the sphere of `radius` about `centre`
// (20 * 4^subdivisions faces). Closed, outward normals. Its faces are chords,
// so the surface lies inside the sphere by up to IcosphereSagitta().
TriangleMesh MakeIcosphere(double radius, int subdivisions, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());
// An upper bound on how far the surface of an icosphere made by MakeIcosphere
// lies inside its sphere: radius minus the smallest distance from the centre
// to a face plane.
double IcosphereSagitta(const TriangleMesh& sphere, double radius,
                        const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

// Closed cylinder about the z axis from z = z0 to z = z0 + height with
// `segments` sides, capped by triangle fans around a centre vertex on each
// cap. Outward normals.
TriangleMesh MakeCylinder(double radius, double height, int segments, double z0 = 0.0);

// Open, flat grid in the plane z = z0 over [0, nx * cell] x [0, ny * cell]:
// (nx + 1) * (ny + 1) vertices, 2 * nx * ny faces, normals +z.
TriangleMesh MakeGrid(int nx, int ny, double cell, double z0 = 0.0);

// Every face split 1 -> 4 at its edge midpoints (shared midpoints shared), so
// the surface is unchanged and the face count grows fourfold.
TriangleMesh Subdivide(const TriangleMesh& mesh);

}  // namespace hull::test
