// The gltf plugin through ExportModel, read back with assimp: the remeshed
// model with its deviation as vertex colours (.glb and .gltf), the
// photomosaic textured and embedded when the results hold one, and a model
// without deviations refused.
#include <assimp/material.h>
#include <assimp/scene.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>

#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "base/deviation_colours.h"
#include "pipeline/model_export.h"
#include "plugin/plugin_registry.h"
#include "support/test_files.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::ScratchDir;

class GltfExport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto& record =
        plugin::Registry::Global().LoadFile(std::string(HI_BINARY_DIR) + "/lib/hullinspect/plugins/gltf.so");
    ASSERT_TRUE(record.loaded) << record.refused;
  }

  // A 2 x 1 x 1 box whose deviation grows along x from -0.1 to +0.1 m.
  static TriangleMesh Model() {
    TriangleMesh m = test::MakeBox({0, 0, 0}, {2, 1, 1});
    std::vector<double> deviation, fusions;
    for (const auto& v : m.vertices) {
      deviation.push_back(-0.1 + 0.1 * v.x());
      fusions.push_back(1);
    }
    m.SetScalar("deviation", deviation);
    m.SetScalar("fusions", fusions);
    return m;
  }

  ScratchDir tmp_{"gltf_export"};
};

TEST_F(GltfExport, DeviationBecomesVertexColours) {
  const TriangleMesh model = Model();
  for (const char* name : {"model.glb", "model.gltf"}) {
    SCOPED_TRACE(name);
    const std::string target = tmp_ / name;
    const auto report = ExportModel(model, "", target);
    const std::map<std::string, std::string> facts(report.begin(), report.end());
    EXPECT_EQ(facts.at("content"), "deviation as vertex colour, blue -0.100 m to red +0.100 m");
    EXPECT_EQ(facts.at("vertices"), "8");

    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(target, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    ASSERT_EQ(scene->mNumMeshes, 1u);
    const aiMesh* mesh = scene->mMeshes[0];
    EXPECT_EQ(mesh->mNumVertices, 8u);
    EXPECT_EQ(mesh->mNumFaces, 12u);
    ASSERT_TRUE(mesh->HasVertexColors(0));
    ASSERT_TRUE(mesh->HasNormals());
    // Each vertex keeps its model-frame position and the colour of its deviation.
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const auto rgb = DivergingRgb((-0.1 + 0.1 * p.x) / 0.1);
      const aiColor4D& c = mesh->mColors[0][v];
      EXPECT_NEAR(c.r, rgb[0], 1e-5);
      EXPECT_NEAR(c.g, rgb[1], 1e-5);
      EXPECT_NEAR(c.b, rgb[2], 1e-5);
    }
    // The root node turns the z-up model frame y-up.
    const aiMatrix4x4& t = scene->mRootNode->mTransformation;
    EXPECT_EQ(t * aiVector3D(0, 0, 1), aiVector3D(0, 1, 0));
  }
  // The colour range an inspector asks for.
  plugin::Registry::Global().SetOption("gltf.deviation-range=0.25");
  const auto report = ExportModel(model, "", tmp_ / "ranged.glb");
  EXPECT_EQ(report.front().second, "deviation as vertex colour, blue -0.250 m to red +0.250 m");
  plugin::Registry::Global().SetOption("gltf.deviation-range=0");
}

TEST_F(GltfExport, ThePhotomosaicIsExportedTexturedWhenTheResultsHoldOne) {
  const fs::path mosaic = fs::path(tmp_.path()) / "results" / "mosaic";
  fs::create_directories(mosaic);
  cv::Mat atlas(16, 32, CV_8UC3, cv::Scalar(40, 120, 200));
  ASSERT_TRUE(cv::imwrite((mosaic / "mosaic_atlas.png").string(), atlas));
  testing::WriteText((mosaic / "mosaic.mtl").string(), "newmtl mosaic\nKd 1 1 1\nmap_Kd mosaic_atlas.png\n");
  testing::WriteText((mosaic / "mosaic.obj").string(),
                     "mtllib mosaic.mtl\n"
                     "v 0 0 0\nv 2 0 0\nv 2 0 1\nv 0 0 1\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                     "usemtl mosaic\n"
                     "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  const std::string target = tmp_ / "textured.glb";
  const auto report = ExportModel(Model(), (fs::path(tmp_.path()) / "results").string(), target);
  EXPECT_EQ(report.front().second, "the photomosaic, textured with mosaic_atlas.png (embedded)");

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(target, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];
  EXPECT_EQ(mesh->mNumFaces, 2u);
  ASSERT_TRUE(mesh->HasTextureCoords(0));
  aiString path;
  ASSERT_EQ(scene->mMaterials[mesh->mMaterialIndex]->GetTexture(aiTextureType_DIFFUSE, 0, &path), AI_SUCCESS);
  const aiTexture* texture = scene->GetEmbeddedTexture(path.C_Str());
  ASSERT_NE(texture, nullptr) << path.C_Str();
  const std::string png = testing::ReadText((mosaic / "mosaic_atlas.png").string());
  ASSERT_EQ(texture->mHeight, 0u);  // compressed, as written
  ASSERT_EQ(texture->mWidth, png.size());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(texture->pcData), png.size()), png);
}

TEST_F(GltfExport, AModelWithoutDeviationIsRefusedWithTheReason) {
  const TriangleMesh bare = test::MakeBox({0, 0, 0}, {1, 1, 1});
  try {
    ExportModel(bare, "", tmp_ / "bare.glb");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("glTF 2.0 (assimp) (plugin gltf): the model has no per-vertex deviation"));
  }
  EXPECT_FALSE(fs::exists(tmp_ / "bare.glb"));
}

}  // namespace
}  // namespace hull
