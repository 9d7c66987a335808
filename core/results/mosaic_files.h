// The photomosaic's files (docs/results-format.md, "Photomosaic"): where its
// inputs lie in a results folder, the writer of the mosaic folder
//   mosaic.obj, mosaic.mtl, mosaic_atlas.png   the textured model (OBJ with UVs)
//   mosaic.ply                                 per-vertex colour
//   mosaic.json, mosaic_faces.csv              summary and per-face view, score, error
// and its reader (the GUI's layer and the report's Photomosaic section; the
// glTF exporter plugin embeds mosaic.obj's atlas when RESULTS/mosaic/ holds it).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "mosaic/photomosaic.h"
#include "results/results_folder.h"

namespace hull {

// The file names written.
inline constexpr const char* kMosaicObj = "mosaic.obj";
inline constexpr const char* kMosaicMtl = "mosaic.mtl";
inline constexpr const char* kMosaicAtlas = "mosaic_atlas.png";
inline constexpr const char* kMosaicPly = "mosaic.ply";
inline constexpr const char* kMosaicJson = "mosaic.json";
inline constexpr const char* kMosaicFacesCsv = "mosaic_faces.csv";

struct MosaicSources {
  std::string adjustment_dir;  // holds adjustment.json and poses.csv
  std::string model_path;      // the remeshed model (mapping/model.ply)
  // The manifest of the run that wrote the adjustment (nullopt: none).
  std::optional<ResultsManifest> adjustment_run;
};

// In RESULTS, the folder 'run' wrote (adjustment/, mapping/model.ply) or
// the one 'adjust' wrote with 'map' run into it (adjustment.json,
// mapping/model.ply). Throws InputError naming RESULTS and what is missing,
// and when the model was not mapped from the adjustment beside it (the
// manifests say another run's).
MosaicSources LocateMosaicSources(const std::string& results);

// The files into `dir` (created when needed).
void WriteMosaic(const MosaicResult& result, const std::string& dir);
// `hullinspect-cli mosaic`: the folder out.path replaced as a whole by the
// mosaic's files and a manifest naming `run` (inputs: the adjustment, the
// model and the bundle the result names).
void SaveMosaicResults(const MosaicResult& result, const OutputFolder& out, ResultsRun run);

// A mosaic folder as the GUI and the report show it.
struct MosaicOnDisk {
  std::string dir;                      // holds mosaic.obj, mosaic.mtl, mosaic_atlas.png
  std::string obj;                      // dir/mosaic.obj
  std::string atlas;                    // dir/mosaic_atlas.png
  Pose x_gM;                            // the adjusted model pose of the results it was built from
  std::size_t vertices = 0, faces = 0;  // of mosaic.obj's mesh
  // mosaic.ply (per-vertex red, green, blue: the estimated albedo x 255);
  // nullptr when the folder has none.
  std::shared_ptr<const TriangleMesh> coloured;
  std::string ply;  // dir/mosaic.ply ("" : none)
};

// The mosaic folder of `folder`: `folder` itself when it holds mosaic.obj,
// else folder/mosaic when that does (a results folder); nullopt otherwise.
std::optional<std::string> FindMosaicResults(const std::string& folder);

// Reads the mosaic in `folder` (a mosaic folder or a results folder holding
// mosaic/): mosaic.obj (core's mesh reader: errors name its line) and the
// atlas must be there; x_gM is the adjustment's of the results folder the
// mosaic lies in (the parent of a mosaic folder); mosaic.ply when present
// (with per-vertex red, green and blue). Throws InputError naming the
// folder and what is missing, and when the files are not those of one run.
MosaicOnDisk ReadMosaicResults(const std::string& folder);
// Only mosaic.ply (the report's figure): nullptr when absent.
std::shared_ptr<const TriangleMesh> ReadMosaicColours(const std::string& mosaic_dir);

}  // namespace hull
