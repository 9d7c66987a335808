// A photomosaic on screen: the folder 'hullinspect-cli mosaic' wrote
// (docs/mosaic.md) and the pose placing its model (in M) in g. Qt-free; the
// scene view reads mosaic.obj and mosaic_atlas.png from `dir`.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace hull::ui {

struct MosaicLayer {
  std::string dir;                      // holds mosaic.obj, mosaic.mtl, mosaic_atlas.png
  std::string obj;                      // dir/mosaic.obj
  std::string atlas;                    // dir/mosaic_atlas.png
  Pose x_gM;                            // the adjusted model pose of the results it was built from
  std::size_t vertices = 0, faces = 0;  // of mosaic.obj's mesh
  // mosaic.ply (per-vertex red, green, blue: the estimated albedo x 255) as
  // the report draws it; nullptr when the folder has none.
  std::shared_ptr<const TriangleMesh> coloured;
  std::string ply;  // dir/mosaic.ply ("" : none)
  // Set when the application built it (MosaicController): the key of the
  // adjustment on screen it was made from (the report shows the mosaic of
  // the results on screen only). "" for a mosaic opened from a folder.
  std::string adjustment_key;
};

// The mosaic folder of `folder`: `folder` itself when it holds mosaic.obj,
// else folder/mosaic when that does (a results folder); nullopt otherwise.
std::optional<std::string> FindMosaicDir(const std::string& folder);

// Reads what the scene needs of the mosaic in `folder` (a mosaic folder or
// a results folder holding mosaic/): checks that mosaic.obj (read with
// core's mesh reader: errors name its line) and the atlas are there, and
// reads the model pose x_gM from the adjustment of the results folder the
// mosaic lies in (the parent of a mosaic folder), and mosaic.ply when it is
// there (with per-vertex red, green and blue). Throws InputError naming the
// folder and what is missing.
MosaicLayer LoadMosaicLayer(const std::string& folder);

}  // namespace hull::ui
