// Inputs the fuzzers (tests/fuzz) found to break a mesh reader, kept in
// tests/fuzz/regressions/<harness>/: each is now refused with an InputError
// naming the file and what is wrong (docs/reliability.md, "Findings").
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "base/error.h"
#include "geometry/mesh_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

// Copies the checked-in input under a name with `extension` (the readers
// choose the format by it) and returns the reader's message.
std::string RefusalOf(const std::string& input, const std::string& extension) {
  const fs::path dir = fs::temp_directory_path() / ("hull_mesh_fuzz_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / ("input" + extension);
  fs::copy_file(fs::path(HI_SOURCE_DIR) / "tests/fuzz/regressions" / input, path, fs::copy_options::overwrite_existing);
  std::string message;
  try {
    LoadMesh(path.string());
    ADD_FAILURE() << input << " was read";
  } catch (const InputError& e) {
    message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  }
  fs::remove_all(dir);
  return message;
}

// A PLY vertex element declaring y and z twice: the first y and z were
// taken for per-vertex scalars without a slot, and the reader wrote through
// index -1 (UBSan: "applying non-zero offset to null pointer").
TEST(MeshFuzzRegressions, PlyPropertyDeclaredTwice) {
  const std::string message = RefusalOf("mesh_ply/duplicate-property.ply", ".ply");
  EXPECT_NE(message.find("property 'y' declared twice in element 'vertex'"), std::string::npos) << message;
  EXPECT_NE(message.find(":8:"), std::string::npos) << message;  // the second 'property double y'
}

}  // namespace
}  // namespace hull
