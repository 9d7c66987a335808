// Fewer triangles for viewers that cannot take a fine remeshed model (a web
// page, a headset): quadric edge collapses (Garland and Heckbert) with
// OpenMesh's decimater on its half-edge mesh. A halfedge collapse keeps one
// of the edge's vertices where it was, so every remaining vertex is an input
// vertex with its own per-vertex values (the deviation colour stays true).
#pragma once

#include <string>

#include "plugin/plugin_api.h"

namespace hull::gltf {

struct DecimationResult {
  bool done = false;
  std::string note;  // what was done, or why not
};

// Collapses edges of `mesh` until it has at most max_triangles, none moving
// the surface by more than max_error (m; the quadric error bound) and none
// flipping a normal. A mesh OpenMesh cannot hold as a 2-manifold is left as
// it is (the note says why): nothing is dropped.
DecimationResult Decimate(plugin::MeshData& mesh, std::size_t max_triangles, double max_error);

}  // namespace hull::gltf
