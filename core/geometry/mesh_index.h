// Spatial queries over a triangle mesh: ray casting (first hit), closest
// point / closest face, the paper's orthogonal signed distance (eq. 5) and
// the exact signed Euclidean distance. Built on Embree's BVH (the fastest
// well-kept ray caster in Debian: see docs/benchmarks.md); every answer is
// refined in double precision on the mesh's own vertices. A closest-point
// query near the surface is usually answered, and proven exact, from the
// faces around the hint (or the nearest vertex) alone, using each vertex's
// precomputed clearance; otherwise the BVH finishes the search.
//
// All queries are const and thread-safe once constructed. The mesh must
// outlive the index and must not change while indexed.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace hull {

struct RayHit {
  bool hit = false;
  double range = 0;  // distance along the unit direction
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int face = -1;
};

struct ClosestPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // exact closest point on the surface
  int face = -1;                                    // the face it lies on
  double distance = 0;                              // unsigned Euclidean distance
};

// How h(x_gM, l) of eq. 5 finds the face whose plane it measures against.
enum class SurfaceLookup {
  kClosestFace,    // p = exact closest point, n = normal of its face (default)
  kNearestVertex,  // the paper's: nearest vertex (k-d tree), any adjacent face
};

struct SurfaceDistance {
  double signed_distance = 0;                        // (q - p)^T n / |n|, positive outside
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // p
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit outward n of the face
  int face = -1;
};

class MeshIndex {
 public:
  explicit MeshIndex(const TriangleMesh& mesh);
  ~MeshIndex();
  MeshIndex(const MeshIndex&) = delete;
  MeshIndex& operator=(const MeshIndex&) = delete;

  const TriangleMesh& mesh() const { return mesh_; }

  // First hit of the ray origin + t * direction (direction need not be unit;
  // range is reported in units of |direction| = 1 after normalising), t in
  // (t_min, t_max]. Both faces of a triangle are hit.
  RayHit Raycast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_max = 1e30,
                 double t_min = 0.0) const;

  // Many rays from one origin (e.g. a camera's pixels): unit directions in
  // single precision, t in (0, t_max]. Embree traces them as a coherent
  // stream (about ten times faster per ray than Raycast); each hit is
  // refined in double precision as Raycast refines it. hits[i] answers
  // directions[i]. Thread-safe; n any size.
  void RaycastFan(const Eigen::Vector3d& origin, const Eigen::Vector3f* directions, int n, double t_max,
                  RayHit* hits) const;
  // Whether the segment from each of `n` points to `target` is blocked by the
  // surface, ignoring the first t_min of it (so that a point on the surface
  // does not shadow itself). blocked[i] answers points[i].
  void OccludedToward(const Eigen::Vector3d* points, int n, const Eigen::Vector3d& target, double t_min,
                      bool* blocked) const;

  // Exact closest point on the surface. hint_face, when >= 0 (e.g. the answer
  // for a nearby query or the previous iteration), bounds the search first
  // and makes queries near the surface several times faster; the result is
  // the same with or without it.
  ClosestPoint Closest(const Eigen::Vector3d& q, int hint_face = -1) const;

  // Eq. 5 of Ozog et al. for a point q already in the model frame M.
  SurfaceDistance OrthogonalSignedDistance(const Eigen::Vector3d& q, SurfaceLookup lookup = SurfaceLookup::kClosestFace,
                                           int hint_face = -1) const;
  // Eq. 5 for a landmark l in g and the model pose x_gM (H = (-)x_gM).
  SurfaceDistance OrthogonalSignedDistance(const Pose& x_gM, const Eigen::Vector3d& l_g,
                                           SurfaceLookup lookup = SurfaceLookup::kClosestFace,
                                           int hint_face = -1) const;

  // Exact signed Euclidean distance: |q - p|, negative inside. The sign comes
  // from the angle-weighted pseudonormal of the closest feature (vertex,
  // edge or face; Baerentzen and Aanaes), exact for a closed, consistently
  // oriented mesh.
  double SignedDistance(const Eigen::Vector3d& q, int hint_face = -1) const;

  // Nearest vertex (k-d tree); returns its index.
  int NearestVertex(const Eigen::Vector3d& q) const;
  // Faces that use a vertex.
  const std::vector<int>& FacesOfVertex(int v) const;

 private:
  struct Impl;
  const TriangleMesh& mesh_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hull
