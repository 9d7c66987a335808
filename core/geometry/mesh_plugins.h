// Mesh formats read by run-time plugins (core/plugin): LoadMesh asks the
// plugin registry first and uses a plugin's importer when it outbids
// HullInspect's own readers (plugin::kByExtension for STL/PLY/OBJ/OFF,
// plugin::kFallback for what assimp reads). What a plugin returns is checked
// here, so a faulty plugin gives an InputError, never a broken mesh.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace hull {

struct PluginMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  bool soup = false;
  std::vector<std::pair<std::string, std::string>> report;  // what the importer reported
};

// The score HullInspect's own readers bid for an extension (".stl").
int BuiltinMeshScore(const std::string& extension);

// Reads `path` with the best plugin importer of plugin::Registry::Global()
// when it outbids the built-in readers; std::nullopt otherwise (also for a
// path that is no regular file: the built-in reader then names the error).
std::optional<PluginMesh> ReadMeshWithPlugin(const std::string& path);

// True when a plugin reads `path` better than the built-in readers.
bool PluginReadsMesh(const std::string& path);

// The extensions LoadMesh reads: the built-in ones, assimp's and the plugins'.
std::vector<std::string> ReadableMeshExtensions();

}  // namespace hull
