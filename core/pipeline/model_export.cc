#include "pipeline/model_export.h"

#include "base/file_io.h"
#include "geometry/mesh_io.h"
#include "plugin/plugin_registry.h"

namespace hull {
namespace {

bool BuiltIn(const std::string& ext) { return ext == ".ply" || ext == ".obj" || ext == ".stl"; }

}  // namespace

std::vector<std::pair<std::string, std::string>> ExportModel(const TriangleMesh& model, const std::string& results_dir,
                                                             const std::string& target) {
  if (BuiltIn(MeshExtension(target))) {
    SaveMesh(model, target);
    return {};
  }
  plugin::Results results;
  results.results_dir = results_dir;
  plugin::MeshData& m = results.model;
  m.positions.reserve(3 * model.num_vertices());
  for (const auto& v : model.vertices) m.positions.insert(m.positions.end(), {v.x(), v.y(), v.z()});
  m.triangles.reserve(3 * model.num_faces());
  for (const Face& f : model.faces) m.triangles.insert(m.triangles.end(), {f[0], f[1], f[2]});
  m.vertex_scalars = model.vertex_scalars;
  return plugin::Registry::Global().ExportResults(results, target);
}

std::vector<std::string> ModelExportExtensions() {
  std::vector<std::string> all = {".ply", ".obj", ".stl"};
  for (const std::string& e : plugin::Registry::Global().ExportExtensions()) {
    if (!BuiltIn(e)) all.push_back(e);
  }
  return all;
}

}  // namespace hull
