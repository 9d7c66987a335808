// Coordinates the float-based libraries (Embree, PCL's k-d tree and voxel
// grid) may be given (issue 14): finite and at most 1e9 m in magnitude. An
// absurd coordinate (an optimiser's wild trial step, a corrupt file) must
// never reach them. MeshIndex answers such a query with no ray hit, an
// infinite closest distance or a NaN signed distance (which makes a solver
// reject the step) and refuses such a mesh with an InputError; AlignGicp
// refuses such a point. Loaded meshes are bounded tighter (kMaxMeshCoordinate).
#pragma once

#include <Eigen/Core>

namespace hull {

constexpr double kMaxQueryCoordinate = 1e9;
// Loaded meshes, after the load transform (m): no hull spans 10,000 km.
constexpr double kMaxMeshCoordinate = 1e7;

inline bool Queryable(const Eigen::Vector3d& q) {
  return q.allFinite() && q.cwiseAbs().maxCoeff() <= kMaxQueryCoordinate;
}

}  // namespace hull
