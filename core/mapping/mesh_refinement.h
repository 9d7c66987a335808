// The mesh that Algorithm 2 fuses into: a copy of the CAD mesh refined by
// CGAL's isotropic remeshing (Botsch and Kobbelt) to a target edge length
// inside a region, and left as it is elsewhere. Two passes keep the work
// proportional to the region: the CAD faces the region touches are first
// remeshed to a coarse edge (8 x target), then the coarse faces the region
// touches to the target. Remeshed vertices are projected back onto the CAD
// surface, so the refined mesh is the CAD surface with more vertices.
#pragma once

#include "geometry/mesh_index.h"
#include "geometry/triangle_mesh.h"
#include "mapping/refinement_region.h"

namespace hull {

struct RefinedMesh {
  TriangleMesh mesh;        // in M, with normals; no scalars
  RefinementRegion region;  // what it was refined for
  double edge = 0;          // target edge length (m)
  double refined_area = 0;  // area remeshed to the target edge (m^2)
  int refined_faces = 0;    // faces of that area
};

// cad_index indexes cad. An empty region returns the CAD mesh unchanged.
// Deterministic.
RefinedMesh RefineMesh(const TriangleMesh& cad, const MeshIndex& cad_index, const RefinementRegion& region,
                       double target_edge);

}  // namespace hull
