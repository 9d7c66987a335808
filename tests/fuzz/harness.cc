// The entry points of the bundle and mesh harnesses, one executable per
// input file kind (tests/fuzz/CMakeLists.txt): HI_FUZZ_BASE and HI_FUZZ_FILE
// (and HI_FUZZ_SONAR: an acoustic sequence's, run through the sonar chain)
// select a bundle file, HI_FUZZ_EXT a mesh format,
// HI_FUZZ_PLUGIN_DIR a plugin folder to load first.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
#ifdef HI_FUZZ_PLUGIN_DIR
  hull::fuzz::LoadPlugins(HI_FUZZ_PLUGIN_DIR);
#endif
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
#if defined(HI_FUZZ_BASE)
#ifdef HI_FUZZ_SONAR
  hull::fuzz::SonarChainFile(HI_FUZZ_BASE, HI_FUZZ_FILE, data, size);
#else
  hull::fuzz::BundleFile(HI_FUZZ_BASE, HI_FUZZ_FILE, false, data, size);
#endif
#elif defined(HI_FUZZ_EXT)
  hull::fuzz::MeshFile(HI_FUZZ_EXT, data, size);
#else
#error "define HI_FUZZ_BASE and HI_FUZZ_FILE, or HI_FUZZ_EXT"
#endif
  return 0;
}
