// Loading and saving triangle meshes.
//
// Read: STL (ASCII and binary), PLY (ASCII and binary, any numeric property
// types, polygons triangulated), OBJ and OFF by our own double-precision
// readers (so a bundle's mesh reads back bit-identical and errors name the
// line), everything else assimp reads (glTF/GLB, DAE, 3DS, FBX, ...); any of
// them gzip-compressed ("hull.stl.gz"), and what run-time plugins read (STEP,
// IGES: geometry/mesh_plugins.h) when they outbid these readers. Write: PLY (binary or ASCII, with the
// per-vertex scalars such as "deviation", readable by CloudCompare and
// ParaView), OBJ and STL (binary).
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace hull {

struct MeshLoadOptions {
  // Model-frame transform applied on load: p -> pose * (scale * p).
  // (The DTC model in ../shared/data is 1:59.4, so scale = 59.4.)
  double scale = 1.0;
  Pose pose;
  // Merge coincident vertices (STL and other triangle soups). PLY, OBJ and
  // OFF are indexed already and keep their vertices in file order, so
  // per-vertex data stays aligned with them.
  bool weld = true;
  // Make face normals point out of the hull (see TriangleMesh::OrientOutward).
  bool orient_outward = true;
  // Filled with what orientation found, if not null.
  OrientationReport* orientation = nullptr;
  // Filled with what a plugin importer reported (e.g. {"unit", "millimetre"},
  // {"surfaces", "12"}), if not null; left empty by the built-in readers.
  std::vector<std::pair<std::string, std::string>>* import_report = nullptr;
};

// Throws InputError naming the file (and line, for text formats); a file
// with vertices but no faces (a point cloud) is an error here.
TriangleMesh LoadMesh(const std::string& path, const MeshLoadOptions& options = {});

// The vertices of any file LoadMesh reads, faces or not: e.g. a PLY with
// only an `element vertex` (a scan). Triangle soups (STL) give each point
// once; no transform is applied. Throws InputError as LoadMesh does.
std::vector<Eigen::Vector3d> LoadPointCloud(const std::string& path);

struct MeshSaveOptions {
  bool binary = true;            // PLY: binary_little_endian; STL is always binary
  bool double_precision = true;  // PLY vertex coordinates as double (else float)
  bool include_scalars = true;   // PLY: write vertex_scalars as vertex properties
};

// Format from the extension: .ply, .obj or .stl, gzip-compressed when the
// name ends in ".gz" (e.g. "hull.ply.gz"). Writes atomically. Throws
// std::invalid_argument for another extension or an inconsistent mesh.
void SaveMesh(const TriangleMesh& mesh, const std::string& path, const MeshSaveOptions& options = {});

// True when LoadMesh reads the file: by its extension (including through
// assimp), or a plugin bids for it.
bool IsMeshFile(const std::string& path);

}  // namespace hull
