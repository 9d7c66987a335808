#include "geometry/mesh_plugins.h"

#include <assimp/cimport.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "base/error.h"
#include "base/file_io.h"
#include "plugin/plugin_registry.h"

namespace hull {
namespace {

[[noreturn]] void Fail(const std::string& path, const std::string& field, const std::string& message) {
  throw InputError({path, 0, 0, field}, "the plugin importer returned a broken mesh: " + message);
}

PluginMesh Check(plugin::ImportedMesh&& in, const std::string& path) {
  const plugin::MeshData& m = in.mesh;
  if (m.positions.size() % 3 != 0 || m.triangles.size() % 3 != 0) {
    Fail(path, "", "coordinate or index count not a multiple of 3");
  }
  PluginMesh out;
  const std::size_t nv = m.num_vertices();
  out.vertices.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d p(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
    if (!p.allFinite()) Fail(path, "vertex " + std::to_string(v), "a non-finite coordinate");
    out.vertices.push_back(p);
  }
  out.faces.reserve(m.num_triangles());
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    Face f;
    for (int k = 0; k < 3; ++k) {
      f[k] = m.triangles[3 * t + k];
      if (f[k] < 0 || static_cast<std::size_t>(f[k]) >= nv) {
        Fail(path, "triangle " + std::to_string(t),
             "vertex index " + std::to_string(f[k]) + " out of range 0.." + std::to_string(nv));
      }
    }
    out.faces.push_back(f);
  }
  for (auto& [name, values] : in.mesh.vertex_scalars) {
    if (values.size() != nv) {
      Fail(path, name,
           "scalar with " + std::to_string(values.size()) + " values for " + std::to_string(nv) + " vertices");
    }
    out.scalars.emplace_back(name, std::move(values));
  }
  out.soup = m.soup;
  out.report = std::move(in.report);
  return out;
}

bool OwnFormat(const std::string& ext) { return ext == ".stl" || ext == ".ply" || ext == ".obj" || ext == ".off"; }

}  // namespace

int BuiltinMeshScore(const std::string& extension) {
  if (OwnFormat(extension)) return plugin::kByExtension;
  if (!extension.empty() && aiIsExtensionSupported(extension.c_str()) == AI_TRUE) return plugin::kFallback;
  return plugin::kCannotRead;
}

std::optional<PluginMesh> ReadMeshWithPlugin(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  auto imported = plugin::Registry::Global().ImportMesh(path, BuiltinMeshScore(MeshExtension(path)));
  if (!imported) return std::nullopt;
  return Check(std::move(*imported), path);
}

bool PluginReadsMesh(const std::string& path) {
  return plugin::Registry::Global().BestMeshScore(path) > BuiltinMeshScore(MeshExtension(path));
}

std::vector<std::string> ReadableMeshExtensions() {
  std::set<std::string> all = {".stl", ".ply", ".obj", ".off"};
  aiString list;  // "*.3ds;*.obj;..."
  aiGetExtensionList(&list);
  std::stringstream ss(list.C_Str());
  for (std::string item; std::getline(ss, item, ';');) {
    if (item.rfind("*.", 0) == 0) all.insert(item.substr(1));
  }
  for (const std::string& e : plugin::Registry::Global().MeshExtensions()) all.insert(e);
  return {all.begin(), all.end()};
}

}  // namespace hull
