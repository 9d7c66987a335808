// The photomosaic's files (docs/results-format.md, "Photomosaic"): where its
// inputs lie in a results folder, the input built from an adjustment and a
// survey bundle, and the writer of the mosaic folder
//   mosaic.obj, mosaic.mtl, mosaic_atlas.png   the textured model (OBJ with UVs)
//   mosaic.ply                                 per-vertex colour
//   mosaic.json, mosaic_faces.csv              summary and per-face view, score, error
// (the glTF exporter plugin embeds mosaic.obj's atlas when RESULTS/mosaic/ holds it).
#pragma once

#include <string>

#include "adjust/adjust_result.h"
#include "mosaic/photomosaic.h"
#include "survey/survey.h"

namespace hull {

struct MosaicSources {
  std::string adjustment_dir;  // holds adjustment.json and poses.csv
  std::string model_path;      // the remeshed model (mapping/model.ply)
};

// In RESULTS, the folder 'run' wrote (adjustment/, mapping/model.ply) or
// the one 'adjust' wrote with 'map' run into it (adjustment.json,
// mapping/model.ply). Throws InputError naming RESULTS and what is missing.
MosaicSources LocateMosaicSources(const std::string& results);

// The adjusted poses, servo angles, extrinsic and model pose of `adjustment`
// with the images of `bundle` (which must outlive the input). Throws
// InputError when the bundle has no images.
MosaicInput MosaicInputFromAdjustment(const AdjustmentResult& adjustment, const SurveyBundle& bundle,
                                      TriangleMesh model);

// Writes the mosaic folder, replacing `dir` as a whole (WriteDirectoryAtomic).
void WriteMosaic(const MosaicResult& result, const std::string& dir);

// The file names written.
inline constexpr const char* kMosaicObj = "mosaic.obj";
inline constexpr const char* kMosaicMtl = "mosaic.mtl";
inline constexpr const char* kMosaicAtlas = "mosaic_atlas.png";
inline constexpr const char* kMosaicPly = "mosaic.ply";
inline constexpr const char* kMosaicJson = "mosaic.json";
inline constexpr const char* kMosaicFacesCsv = "mosaic_faces.csv";

}  // namespace hull
