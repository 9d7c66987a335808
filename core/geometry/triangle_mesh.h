// An indexed triangle mesh in double precision with face and vertex normals
// and named per-vertex scalars (e.g. "deviation").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "geometry/pose.h"

namespace hull {

using Face = std::array<int, 3>;

// What OrientOutward() found and did.
struct OrientationReport {
  bool closed = false;          // every edge shared by exactly two faces
  int components = 0;           // edge-connected components
  int faces_flipped = 0;        // faces whose winding was changed
  bool was_inside_out = false;  // the mesh as a whole had inward normals
  int non_manifold_edges = 0;   // edges with more than two faces
  int boundary_edges = 0;
};

class TriangleMesh {
 public:
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  // Derived by ComputeNormals(): unit face normals (right-hand rule on the
  // winding) and area-weighted unit vertex normals.
  std::vector<Eigen::Vector3d> face_normals;
  std::vector<Eigen::Vector3d> vertex_normals;
  // Named per-vertex values, each of size vertices.size().
  std::vector<std::pair<std::string, std::vector<double>>> vertex_scalars;

  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_faces() const { return faces.size(); }
  bool empty() const { return faces.empty(); }

  void ComputeNormals();
  Eigen::AlignedBox3d Bounds() const;
  double SurfaceArea() const;
  double FaceArea(int f) const;
  Eigen::Vector3d FaceCentroid(int f) const;
  // Volume enclosed (positive for a closed, outward-oriented mesh).
  double SignedVolume() const;

  // p -> T * (scale * p); normals are recomputed.
  void Transform(const Pose& T, double scale = 1.0);
  // Merges vertices closer than tol (STL soup -> indexed mesh) and drops
  // degenerate faces; returns the number of vertices removed.
  std::size_t WeldVertices(double tol = 0.0);
  // Makes the winding consistent per component and outward: for a closed
  // component by its signed volume, for an open one so that the area-weighted
  // normals point away from the component's centroid. Recomputes normals.
  OrientationReport OrientOutward();
  // Counts boundary and non-manifold edges without changing anything.
  OrientationReport CheckTopology() const;

  // Per-vertex scalar access (nullptr when absent); Set replaces or adds.
  const std::vector<double>* FindScalar(const std::string& name) const;
  void SetScalar(const std::string& name, std::vector<double> values);

  // Appends another mesh (its scalars are dropped unless both carry them).
  void Append(const TriangleMesh& other);
};

}  // namespace hull
