// Inputs the fuzzers (tests/fuzz) found to break a mesh reader, kept in
// tests/fuzz/regressions/<harness>/: each is now refused with an InputError
// naming the file and what is wrong (docs/reliability.md, "Findings").
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "base/error.h"
#include "geometry/mesh_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

// Copies the checked-in input under a name with `extension` (the readers
// choose the format by it; one ending in .gz is written gzip-compressed) and
// returns the reader's message.
std::string RefusalOf(const std::string& input, const std::string& extension) {
  const fs::path dir = fs::temp_directory_path() / ("hull_mesh_fuzz_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / ("input" + extension);
  const fs::path source = fs::path(HI_SOURCE_DIR) / "tests/fuzz/regressions" / input;
  if (path.extension() == ".gz") {
    std::ifstream in(source, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    gzFile out = gzopen(path.c_str(), "wb");
    EXPECT_EQ(gzwrite(out, bytes.data(), static_cast<unsigned>(bytes.size())), static_cast<int>(bytes.size()));
    gzclose(out);
  } else {
    fs::copy_file(source, path, fs::copy_options::overwrite_existing);
  }
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

// Not glTF, but holding the OpenGEX keyword "indexarray": glTF's importers
// did not recognise it, assimp then asked every importer and gave it to its
// OpenGEX parser, which read past its buffer (ASan: heap-buffer-overflow in
// strlen inside libassimp). Now only the importers of the extension may read
// a file, also when it is gzip-compressed (assimp reads it from memory).
TEST(MeshFuzzRegressions, AssimpReadsAFileOnlyWithTheImportersOfItsExtension) {
  for (const char* extension : {".gltf", ".gltf.gz"}) {
    const std::string message = RefusalOf("mesh_gltf/opengex-keyword.gltf", extension);
    EXPECT_NE(message.find("not in the format its extension names"), std::string::npos) << extension << message;
    EXPECT_NE(message.find("glTF"), std::string::npos) << extension << message;
  }
}

}  // namespace
}  // namespace hull
