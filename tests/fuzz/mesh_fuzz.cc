// Mesh files read by LoadMesh and LoadPointCloud, the readers the pipeline,
// CLI and GUI share (built-in readers, assimp, and the run-time plugins
// loaded with LoadPlugins).
#include <string>

#include "fuzz_support.h"
#include "fuzz_targets.h"
#include "geometry/mesh_io.h"
#include "plugin/plugin_registry.h"

namespace hull::fuzz {

void MeshFile(const char* extension, const std::uint8_t* data, std::size_t size) {
  static const std::string path = ScratchDir() + "/input." + extension;
  WriteInput(path, data, size);
  ExpectOnlyInputError([&] { LoadMesh(path); });
  ExpectOnlyInputError([&] { LoadPointCloud(path); });
}

void LoadPlugins(const char* folder) { plugin::Registry::Global().LoadFolder(folder); }

}  // namespace hull::fuzz
