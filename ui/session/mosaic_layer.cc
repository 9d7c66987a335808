#include "ui/session/mosaic_layer.h"

#include "results/mosaic_files.h"

namespace hull::ui {

std::optional<std::string> FindMosaicDir(const std::string& folder) { return FindMosaicResults(folder); }

MosaicLayer LoadMosaicLayer(const std::string& folder) {
  const MosaicOnDisk m = ReadMosaicResults(folder);
  MosaicLayer layer;
  layer.dir = m.dir;
  layer.obj = m.obj;
  layer.atlas = m.atlas;
  layer.x_gM = m.x_gM;
  layer.vertices = m.vertices;
  layer.faces = m.faces;
  layer.coloured = m.coloured;
  layer.ply = m.ply;
  return layer;
}

}  // namespace hull::ui
