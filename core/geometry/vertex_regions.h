// Connected regions of a mesh's vertices: the vertices a predicate keeps,
// joined over the mesh's edges (both ends kept). Used by the object
// detection (vertices above h_min) and the survey comparison (the same
// footprints, for results written without them).
#pragma once

#include <functional>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace hull {

struct VertexRegions {
  std::vector<int> region_of;  // per vertex: its region, -1 where `keep` is false
  int num_regions = 0;         // numbered in the order of their lowest vertex
};
VertexRegions ConnectedVertexRegions(const TriangleMesh& mesh, const std::function<bool(int)>& keep);

}  // namespace hull
