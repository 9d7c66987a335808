// Mesh readers and writers. STL, PLY, OBJ and OFF are read by our own
// double-precision parsers (errors name the line and column), one file each
// (mesh_io_<format>.cc); every other format goes through assimp
// (mesh_io_assimp.cc). Readers produce a RawMesh; LoadMesh then welds
// triangle soups, applies the model-frame transform and orients. This file
// dispatches by extension, checks every loaded surface and gzips on save.
#include "geometry/mesh_io.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "geometry/mesh_io_internal.h"
#include "geometry/mesh_plugins.h"
#include "geometry/query_bounds.h"

namespace hull {
namespace mesh_io_internal {

std::string Quote(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string q = "'";
  for (char c : s.substr(0, kMax)) q += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  if (s.size() > kMax) q += "...";
  return q + "'";
}

[[noreturn]] void FailFile(const std::string& file, const std::string& message, const std::string& field) {
  throw InputError({file, 0, 0, field}, message);
}

[[noreturn]] void FailDegenerate(const std::string& file, std::uint64_t degenerate, std::uint64_t faces) {
  FailFile(file, std::to_string(degenerate) + " of " + std::to_string(faces) +
                     " triangles have zero area: not a usable surface (a mesh must be mostly real triangles; "
                     "more than half degenerate is refused)");
}

}  // namespace mesh_io_internal

namespace {

using mesh_io_internal::FailDegenerate;
using mesh_io_internal::FailFile;
using mesh_io_internal::RawMesh;

// The checks every loaded mesh passes (issue 14): coordinates within
// kMaxMeshCoordinate, a positive surface area, and at most half of the
// triangles degenerate. Indices are checked by each reader.
void CheckUsableSurface(const TriangleMesh& mesh, const std::string& file) {
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!(mesh.vertices[v].cwiseAbs().maxCoeff() <= kMaxMeshCoordinate)) {
      FailFile(file,
               "vertex coordinate " + FormatDouble(mesh.vertices[v].cwiseAbs().maxCoeff()) +
                   " is beyond the plausible " + FormatDouble(kMaxMeshCoordinate) +
                   " (after scaling); a hull mesh spans metres to kilometres, so the file is corrupt or the "
                   "scale wrong",
               "vertex " + std::to_string(v));
    }
  }
  double area = 0;
  std::uint64_t degenerate = 0;
  for (const Face& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const double twice = (mesh.vertices[static_cast<std::size_t>(f[1])] - a)
                             .cross(mesh.vertices[static_cast<std::size_t>(f[2])] - a)
                             .norm();
    if (!(twice > 0)) ++degenerate;
    area += 0.5 * twice;
  }
  if (2 * degenerate > mesh.faces.size()) FailDegenerate(file, degenerate, mesh.faces.size());
  if (!(area > 0)) FailFile(file, "the surface has zero area; expected a triangle mesh of a hull");
}

// `report`, when given, receives what a plugin importer reported.
RawMesh ReadAny(const std::string& path, std::vector<std::pair<std::string, std::string>>* report = nullptr) {
  if (auto p = ReadMeshWithPlugin(path)) {  // a plugin outbids the readers below
    if (report) *report = std::move(p->report);
    return {std::move(p->vertices), std::move(p->faces), std::move(p->scalars), p->soup};
  }
  const std::string data = ReadFileToString(path);
  if (data.empty()) FailFile(path, "the file is empty; expected a mesh");
  const std::string ext = MeshExtension(path);
  if (ext == ".stl") return mesh_io_internal::ReadStl(data, path);
  if (ext == ".ply") return mesh_io_internal::ReadPly(data, path);
  if (ext == ".obj") return mesh_io_internal::ReadObj(data, path);
  if (ext == ".off") return mesh_io_internal::ReadOff(data, path);
  return mesh_io_internal::ReadWithAssimp(data, path, ext);
}

std::string Gzip(const std::string& data, const std::string& path) {
  z_stream zs{};
  if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("cannot write " + path + ": zlib initialisation failed");
  }
  std::string out(deflateBound(&zs, static_cast<uLong>(data.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw std::runtime_error("cannot write " + path + ": gzip compression failed");
  return out;
}

}  // namespace

TriangleMesh LoadMesh(const std::string& path, const MeshLoadOptions& options) {
  if (!std::isfinite(options.scale) || options.scale == 0) {
    throw OptionError("scale", "must be finite and non-zero, got " + FormatDouble(options.scale));
  }
  RawMesh raw = ReadAny(path, options.import_report);
  if (raw.faces.empty()) {
    FailFile(path, raw.vertices.empty() ? "the file contains no geometry; expected a triangle mesh"
                                        : "the file has " + std::to_string(raw.vertices.size()) +
                                              " vertices but no faces; expected a triangle mesh (a point cloud "
                                              "is read with LoadPointCloud)");
  }
  TriangleMesh mesh;
  mesh.vertices = std::move(raw.vertices);
  mesh.faces = std::move(raw.faces);
  mesh.vertex_scalars = std::move(raw.scalars);
  const bool identity =
      options.pose.translation() == Eigen::Vector3d::Zero() && options.pose.rotation() == Eigen::Matrix3d::Identity();
  if (options.scale != 1.0 || !identity) {
    mesh.Transform(options.pose, options.scale);
  }
  CheckUsableSurface(mesh, path);
  if (options.weld && raw.soup) mesh.WeldVertices(0.0);
  const OrientationReport report = options.orient_outward ? mesh.OrientOutward() : mesh.CheckTopology();
  if (options.orientation) *options.orientation = report;
  mesh.ComputeNormals();
  return mesh;
}

std::vector<Eigen::Vector3d> LoadPointCloud(const std::string& path) {
  RawMesh raw = ReadAny(path);
  if (raw.vertices.empty()) FailFile(path, "the file contains no points");
  if (!raw.soup) return std::move(raw.vertices);
  // A triangle soup repeats each point once per face: keep one of each.
  TriangleMesh mesh;
  mesh.vertices = std::move(raw.vertices);
  mesh.WeldVertices(0.0);
  return std::move(mesh.vertices);
}

void SaveMesh(const TriangleMesh& mesh, const std::string& path, const MeshSaveOptions& options) {
  const int nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.faces[f][k] < 0 || mesh.faces[f][k] >= nv) {
        throw std::invalid_argument("SaveMesh " + path + ": face " + std::to_string(f) + " uses vertex " +
                                    std::to_string(mesh.faces[f][k]) + " of " + std::to_string(nv));
      }
    }
  }
  for (const auto& [name, values] : mesh.vertex_scalars) {
    if (values.size() != mesh.vertices.size()) {
      throw std::invalid_argument("SaveMesh " + path + ": scalar '" + name + "' has " + std::to_string(values.size()) +
                                  " values for " + std::to_string(nv) + " vertices");
    }
  }
  const std::string ext = MeshExtension(path);
  std::string data;
  if (ext == ".ply") {
    data = mesh_io_internal::WritePly(mesh, options);
  } else if (ext == ".obj") {
    data = mesh_io_internal::WriteObj(mesh);
  } else if (ext == ".stl") {
    data = mesh_io_internal::WriteStl(mesh);
  } else {
    throw std::invalid_argument("SaveMesh " + path + ": cannot write '" + ext + "' files; use .ply, .obj or .stl");
  }
  if (EndsWith(AsciiLower(path), ".gz")) data = Gzip(data, path);
  WriteFileAtomic(path, data);
}

bool IsMeshFile(const std::string& path) { return BuiltinMeshScore(MeshExtension(path)) > 0 || PluginReadsMesh(path); }

}  // namespace hull
