#include "ui/session/mosaic_layer.h"

#include <filesystem>
#include <memory>
#include <system_error>

#include "adjust/adjust_result.h"
#include "base/error.h"
#include "geometry/mesh_io.h"
#include "mosaic/mosaic_io.h"

namespace hull::ui {

namespace fs = std::filesystem;

std::optional<std::string> FindMosaicDir(const std::string& folder) {
  std::error_code ec;
  if (fs::is_regular_file(fs::path(folder) / kMosaicObj, ec)) return folder;
  const fs::path sub = fs::path(folder) / "mosaic";
  if (fs::is_regular_file(sub / kMosaicObj, ec)) return sub.string();
  return std::nullopt;
}

MosaicLayer LoadMosaicLayer(const std::string& folder) {
  const std::optional<std::string> dir = FindMosaicDir(folder);
  if (!dir) {
    throw InputError({folder, 0, 0, ""}, std::string("holds no photomosaic: neither ") + kMosaicObj + " nor mosaic/" +
                                             kMosaicObj + " (write one with 'hullinspect-cli mosaic RESULTS')");
  }
  MosaicLayer layer;
  layer.dir = *dir;
  layer.obj = (fs::path(*dir) / kMosaicObj).string();
  layer.atlas = (fs::path(*dir) / kMosaicAtlas).string();
  std::error_code ec;
  if (!fs::is_regular_file(layer.atlas, ec)) {
    throw InputError({*dir, 0, 0, ""}, std::string("has mosaic.obj but not its texture ") + kMosaicAtlas);
  }
  MeshLoadOptions read;
  read.weld = false;
  read.orient_outward = false;
  const TriangleMesh mesh = LoadMesh(layer.obj, read);
  layer.vertices = mesh.vertices.size();
  layer.faces = mesh.faces.size();
  // The mosaic's model is in M: placed by the adjusted x_gM of the results
  // folder it was written into (RESULTS/mosaic by default).
  const std::string results = fs::absolute(fs::path(*dir), ec).parent_path().string();
  const MosaicSources sources = LocateMosaicSources(results);
  layer.x_gM = Pose::FromVector(ReadAdjustmentResult(sources.adjustment_dir).x_gM);
  const fs::path ply = fs::path(*dir) / kMosaicPly;
  if (fs::is_regular_file(ply, ec)) {
    auto coloured = std::make_shared<TriangleMesh>(LoadMesh(ply.string(), read));
    for (const char* c : {"red", "green", "blue"}) {
      if (!coloured->FindScalar(c)) {
        throw InputError({ply.string(), 0, 0, c}, "a photomosaic needs per-vertex " + std::string(c));
      }
    }
    layer.ply = ply.string();
    layer.coloured = std::move(coloured);
  }
  return layer;
}

}  // namespace hull::ui
