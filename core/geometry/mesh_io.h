// Loading and saving triangle meshes.
//
// Read: STL (ASCII and binary), PLY (ASCII and binary, any numeric property
// types, polygons triangulated), OBJ and OFF by our own double-precision
// readers (so a bundle's mesh reads back bit-identical and errors name the
// line), everything else assimp reads (glTF/GLB, DAE, 3DS, FBX, ...); any of
// them gzip-compressed ("hull.stl.gz"). Write: PLY (binary or ASCII, with the
// per-vertex scalars such as "deviation", readable by CloudCompare and
// ParaView), OBJ and STL (binary).
#pragma once

#include <string>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace hull {

struct MeshLoadOptions {
  // Model-frame transform applied on load: p -> pose * (scale * p).
  // (The DTC model in ../shared/data is 1:59.4, so scale = 59.4.)
  double scale = 1.0;
  Pose pose;
  // Merge coincident vertices (STL and other triangle soups).
  bool weld = true;
  // Make face normals point out of the hull (see TriangleMesh::OrientOutward).
  bool orient_outward = true;
  // Filled with what orientation found, if not null.
  OrientationReport* orientation = nullptr;
};

// Throws InputError naming the file (and line, for text formats).
TriangleMesh LoadMesh(const std::string& path, const MeshLoadOptions& options = {});

struct MeshSaveOptions {
  bool binary = true;            // PLY: binary_little_endian; STL is always binary
  bool double_precision = true;  // PLY vertex coordinates as double (else float)
  bool include_scalars = true;   // PLY: write vertex_scalars as vertex properties
};

// Format from the extension: .ply, .obj or .stl. Writes atomically.
void SaveMesh(const TriangleMesh& mesh, const std::string& path, const MeshSaveOptions& options = {});

// True when the extension is one LoadMesh reads (including through assimp).
bool IsMeshFile(const std::string& path);

}  // namespace hull
