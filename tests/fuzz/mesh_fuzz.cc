// A mesh file (extension HI_FUZZ_EXT: "stl", "ply", "obj", "off", "stl.gz",
// "gltf", "step") read by LoadMesh and LoadPointCloud, the readers the
// pipeline, CLI and GUI share (built-in readers, assimp, and with
// HI_FUZZ_PLUGIN_DIR the run-time plugins loaded from that folder).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "geometry/mesh_io.h"
#ifdef HI_FUZZ_PLUGIN_DIR
#include "plugin/plugin_registry.h"
#endif

extern "C" int LLVMFuzzerInitialize(int*, char***) {
#ifdef HI_FUZZ_PLUGIN_DIR
  hull::plugin::Registry::Global().LoadFolder(HI_FUZZ_PLUGIN_DIR);
#endif
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = hull::fuzz::ScratchDir() + "/input." HI_FUZZ_EXT;
  hull::fuzz::WriteInput(path, data, size);
  hull::fuzz::ExpectOnlyInputError([&] { hull::LoadMesh(path); });
  hull::fuzz::ExpectOnlyInputError([&] { hull::LoadPointCloud(path); });
  return 0;
}
