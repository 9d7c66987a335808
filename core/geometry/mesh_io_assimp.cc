// Every format assimp reads (glTF/GLB, DAE, 3DS, FBX, ...).
#include "geometry/mesh_io_internal.h"

#include <assimp/BaseImporter.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "base/file_io.h"

namespace hull::mesh_io_internal {

namespace {

// Only the importers assimp registers for the file's extension may read it.
// When several claim the extension (glTF 1 and 2 both claim .gltf) and none
// recognises the content, assimp would go on to every importer's signature
// check, and a file that merely contains another format's keyword reaches
// that format's parser: a .gltf file holding the word "indexarray" ran
// assimp 5.2's OpenGEX parser past its buffer (found by fuzzing,
// docs/reliability.md). Such a file is refused here instead. `name` is the
// name assimp will open (the memory file's name for an inflated file).
void RequireImporterForExtension(const Assimp::Importer& importer, const std::string& name, Assimp::IOSystem* io,
                                 const std::string& file) {
  const std::string lower = AsciiLower(name);
  std::vector<const Assimp::BaseImporter*> candidates;
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
    Assimp::BaseImporter* candidate = importer.GetImporter(i);
    std::set<std::string> extensions;
    candidate->GetExtensionList(extensions);
    for (const std::string& e : extensions) {
      if (EndsWith(lower, "." + AsciiLower(e))) {
        candidates.push_back(candidate);
        break;
      }
    }
  }
  if (candidates.empty()) FailFile(file, "no mesh reader (built in, plugin or assimp) for this file's extension");
  if (candidates.size() == 1) return;  // assimp takes it without looking
  std::string names;
  for (const Assimp::BaseImporter* c : candidates) {
    if (c->CanRead(name, io, true)) return;  // assimp takes the first that recognises the content
    const aiImporterDesc* desc = c->GetInfo();
    names += std::string(names.empty() ? "" : ", ") + (desc && desc->mName ? desc->mName : "?");
  }
  FailFile(file, "the content is not in the format its extension names (assimp's importers for it, " + names +
                     ", do not recognise it)");
}

}  // namespace

RawMesh ReadWithAssimp(const std::string& data, const std::string& file, const std::string& ext) {
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices;
  // A plain file is read by name so that files it refers to (a glTF's .bin,
  // an OBJ's .mtl) are found; a compressed one from the inflated memory.
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  if (EndsWith(AsciiLower(file), ".gz")) {
    const std::string hint = ext.empty() ? std::string() : ext.substr(1);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(data.data());
    Assimp::MemoryIOSystem memory(bytes, data.size(), importer.GetIOHandler());
    RequireImporterForExtension(importer, std::string(AI_MEMORYIO_MAGIC_FILENAME) + "." + hint, &memory, file);
    scene = importer.ReadFileFromMemory(data.data(), data.size(), flags, hint.c_str());
  } else {
    RequireImporterForExtension(importer, file, importer.GetIOHandler(), file);
    scene = importer.ReadFile(file, flags);
  }
  if (!scene) {
    const std::string why = importer.GetErrorString();
    FailFile(file, "cannot read the mesh" + (why.empty() ? std::string() : ": " + why));
  }
  RawMesh m;
  m.soup = true;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[i];
    const int base = static_cast<int>(m.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      m.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      m.faces.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                         base + static_cast<int>(face.mIndices[2])});
    }
  }
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (!m.vertices[v].allFinite()) FailFile(file, "non-finite vertex coordinate", "vertex " + std::to_string(v));
  }
  return m;
}

}  // namespace hull::mesh_io_internal
