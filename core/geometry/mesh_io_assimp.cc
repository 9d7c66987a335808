// Every format assimp reads (glTF/GLB, DAE, 3DS, FBX, ...).
#include "geometry/mesh_io_internal.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "base/file_io.h"

namespace hull::mesh_io_internal {

RawMesh ReadWithAssimp(const std::string& data, const std::string& file, const std::string& ext) {
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices;
  // A plain file is read by name so that files it refers to (a glTF's .bin,
  // an OBJ's .mtl) are found; a compressed one from the inflated memory.
  const aiScene* scene = nullptr;
  std::string lower = file;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (EndsWith(lower, ".gz")) {
    const std::string hint = ext.empty() ? std::string() : ext.substr(1);
    scene = aiImportFileFromMemory(data.data(), static_cast<unsigned>(data.size()), flags, hint.c_str());
  } else {
    scene = aiImportFile(file.c_str(), flags);
  }
  if (!scene) {
    const std::string why = aiGetErrorString();
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
  aiReleaseImport(scene);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (!m.vertices[v].allFinite()) FailFile(file, "non-finite vertex coordinate", "vertex " + std::to_string(v));
  }
  return m;
}

}  // namespace hull::mesh_io_internal
