// The gltf plugin: the remeshed model as glTF 2.0 (.glb, .gltf) through
// assimp, for web viewers, Blender and digital-twin tools. Coloured by the
// deviation from the CAD surface (the report's RdBu map), or textured with
// the photomosaic when the results hold one (<results>/mosaic/mosaic.obj,
// mosaic.mtl, mosaic_atlas.png: an OBJ with UVs).
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>

#include "base/deviation_colours.h"
#include "plugin/plugin_api.h"

namespace hull::gltf {
namespace {
namespace fs = std::filesystem;

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string Metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f m", v);
  return buf;
}

// HullInspect's model frame is z-up (x forward, y to port); glTF is y-up.
// The root node turns one into the other, so the vertex data stays in the
// model frame: (x, y, z) -> (x, z, -y).
aiMatrix4x4 ZUpToYUp() {
  return aiMatrix4x4(1, 0, 0, 0,   //
                     0, 0, 1, 0,   //
                     0, -1, 0, 0,  //
                     0, 0, 0, 1);
}

const std::vector<double>* FindScalar(const plugin::MeshData& m, const std::string& name) {
  for (const auto& [n, values] : m.vertex_scalars) {
    if (n == name) return &values;
  }
  return nullptr;
}

// The colour-map half-range: the user's, or the report's rule over the
// vertices the survey fused (all of them when the model has no "fusions").
double ColourRange(const plugin::MeshData& m, const std::vector<double>& deviation, double requested) {
  if (requested > 0) return requested;
  const std::vector<double>* fusions = FindScalar(m, "fusions");
  std::vector<double> magnitudes;
  for (std::size_t i = 0; i < deviation.size(); ++i) {
    if (!fusions || (*fusions)[i] > 0) magnitudes.push_back(std::abs(deviation[i]));
  }
  return DeviationColourRange(std::move(magnitudes));
}

// A scene of the model alone, its vertices coloured by the deviation.
std::unique_ptr<aiScene> ColouredScene(const plugin::MeshData& m, const std::vector<double>& deviation, double range) {
  const unsigned nv = static_cast<unsigned>(m.num_vertices());
  const unsigned nf = static_cast<unsigned>(m.num_triangles());
  if (deviation.size() != nv) throw std::runtime_error("the deviation has not one value per vertex");
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("hull");
  scene->mRootNode->mTransformation = ZUpToYUp();
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial };
  const aiString name("deviation");
  scene->mMaterials[0]->AddProperty(&name, AI_MATKEY_NAME);
  const aiColor4D white(1, 1, 1, 1);  // glTF multiplies the vertex colours by it
  scene->mMaterials[0]->AddProperty(&white, 1, AI_MATKEY_COLOR_DIFFUSE);
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { new aiMesh };
  aiMesh* mesh = scene->mMeshes[0];
  mesh->mName = aiString("remeshed-model");
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = nv;
  mesh->mVertices = new aiVector3D[nv];
  mesh->mNormals = new aiVector3D[nv];
  mesh->mColors[0] = new aiColor4D[nv];
  for (unsigned v = 0; v < nv; ++v) {
    mesh->mVertices[v] =
        aiVector3D(static_cast<ai_real>(m.positions[3 * v]), static_cast<ai_real>(m.positions[3 * v + 1]),
                   static_cast<ai_real>(m.positions[3 * v + 2]));
    mesh->mNormals[v] = aiVector3D(0, 0, 0);
    const auto rgb = DivergingRgb(deviation[v] / range);
    mesh->mColors[0][v] =
        aiColor4D(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2]), 1.0f);
  }
  mesh->mNumFaces = nf;
  mesh->mFaces = new aiFace[nf];
  for (unsigned f = 0; f < nf; ++f) {
    aiFace& face = mesh->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(m.triangles[3 * f + k]);
    // Area-weighted vertex normals: the cross product's length is twice the area.
    const aiVector3D& a = mesh->mVertices[face.mIndices[0]];
    const aiVector3D n = (mesh->mVertices[face.mIndices[1]] - a) ^ (mesh->mVertices[face.mIndices[2]] - a);
    for (int k = 0; k < 3; ++k) mesh->mNormals[face.mIndices[k]] += n;
  }
  for (unsigned v = 0; v < nv; ++v) {
    if (mesh->mNormals[v].SquareLength() > 0) mesh->mNormals[v].Normalize();
  }
  return scene;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The photomosaic's OBJ with its atlas embedded (so a .glb is one file).
std::unique_ptr<aiScene> TexturedScene(const fs::path& obj, std::string* atlas_name) {
  Assimp::Importer importer;
  if (!importer.ReadFile(obj.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices)) {
    throw std::runtime_error("cannot read the photomosaic " + obj.string() + ": " + importer.GetErrorString());
  }
  std::unique_ptr<aiScene> scene(importer.GetOrphanedScene());
  if (scene->mNumMeshes == 0) throw std::runtime_error(obj.string() + " holds no mesh");
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    if (!scene->mMeshes[i]->HasTextureCoords(0)) throw std::runtime_error(obj.string() + " has no texture coordinates");
  }
  std::vector<aiTexture*> textures;
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    aiMaterial* material = scene->mMaterials[i];
    aiString path;
    if (material->GetTexture(aiTextureType_DIFFUSE, 0, &path) != AI_SUCCESS || path.data[0] == '*') continue;
    const fs::path image = obj.parent_path() / path.C_Str();
    const std::string bytes = ReadBytes(image);
    auto* texture = new aiTexture;
    texture->mWidth = static_cast<unsigned>(bytes.size());  // compressed: mWidth is the byte count
    texture->mHeight = 0;
    const std::string ext = Lower(image.extension().string());
    std::strncpy(texture->achFormatHint, ext == ".jpg" || ext == ".jpeg" ? "jpg" : "png", HINTMAXTEXTURELEN - 1);
    texture->pcData = new aiTexel[(bytes.size() + sizeof(aiTexel) - 1) / sizeof(aiTexel)];
    std::memcpy(texture->pcData, bytes.data(), bytes.size());
    texture->mFilename = aiString(image.filename().string());
    const aiString embedded("*" + std::to_string(textures.size()));
    material->AddProperty(&embedded, AI_MATKEY_TEXTURE_DIFFUSE(0));
    textures.push_back(texture);
    *atlas_name = image.filename().string();
  }
  if (textures.empty()) throw std::runtime_error(obj.string() + ": its material names no texture image");
  scene->mNumTextures = static_cast<unsigned>(textures.size());
  scene->mTextures = new aiTexture*[textures.size()];
  std::copy(textures.begin(), textures.end(), scene->mTextures);
  scene->mRootNode->mTransformation = ZUpToYUp() * scene->mRootNode->mTransformation;
  return scene;
}

class GltfExporter final : public plugin::ResultExporter {
 public:
  std::string Name() const override { return "glTF 2.0 (assimp)"; }
  std::vector<std::string> Extensions() const override { return {".glb", ".gltf"}; }

  plugin::Report Export(const plugin::Results& results, const std::string& target,
                        const plugin::Settings& settings) const override {
    const std::string ext = Lower(fs::path(target).extension().string());
    if (ext != ".glb" && ext != ".gltf") throw std::invalid_argument("writes .glb and .gltf files only");
    const fs::path mosaic = results.results_dir.empty() ? fs::path() : fs::path(results.results_dir) / "mosaic";
    std::error_code ec;
    std::unique_ptr<aiScene> scene;
    plugin::Report report;
    if (!mosaic.empty() && fs::exists(mosaic / "mosaic.obj", ec)) {
      std::string atlas;
      scene = TexturedScene(mosaic / "mosaic.obj", &atlas);
      report.emplace_back("content", "the photomosaic, textured with " + atlas + " (embedded)");
    } else {
      const std::vector<double>* deviation = FindScalar(results.model, "deviation");
      if (!deviation) throw std::runtime_error("the model has no per-vertex deviation to colour by");
      const double r = ColourRange(results.model, *deviation, std::stod(settings.at("deviation-range")));
      scene = ColouredScene(results.model, *deviation, r);
      report.emplace_back("content", "deviation as vertex colour, blue -" + Metres(r) + " to red +" + Metres(r));
    }
    unsigned vertices = 0, triangles = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
      vertices += scene->mMeshes[i]->mNumVertices;
      triangles += scene->mMeshes[i]->mNumFaces;
    }
    Assimp::Exporter exporter;
    if (exporter.Export(scene.get(), ext == ".glb" ? "glb2" : "gltf2", target) != AI_SUCCESS) {
      throw std::runtime_error(std::string("assimp: ") + exporter.GetErrorString());
    }
    report.emplace_back("vertices", std::to_string(vertices));
    report.emplace_back("triangles", std::to_string(triangles));
    report.emplace_back("frame", "model frame, z-up turned y-up by the root node");
    return report;
  }
};

class GltfPlugin final : public plugin::Plugin {
 public:
  std::string Version() const override { return HI_VERSION; }
  std::string Description() const override {
    return "glTF 2.0 export of the remeshed model (assimp): deviation colours, or the photomosaic texture";
  }
  std::vector<plugin::OptionSpec> Options() const override {
    return {{"deviation-range", "0",
             "half-range of the deviation colours, metres (0: the report's, from the fused vertices)", true, 0.0,
             100.0}};
  }
  std::vector<std::unique_ptr<plugin::ResultExporter>> ResultExporters() const override {
    std::vector<std::unique_ptr<plugin::ResultExporter>> v;
    v.push_back(std::make_unique<GltfExporter>());
    return v;
  }
};

}  // namespace
}  // namespace hull::gltf

HULLINSPECT_PLUGIN(hull::gltf::GltfPlugin, "gltf")
