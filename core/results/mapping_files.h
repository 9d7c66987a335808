// The mapping results folder (docs/results-format.md, "Mapping results,
// version 1"):
//   mapping.json   format "hull-mapping", version, inputs, options, hull
//                  axes, summary (counts, areas, timings), files
//   model.ply      the fused, locally remeshed model in M (binary; per-vertex
//                  "deviation" in m and "fusions", the hits of eq. 15; with
//                  landmark covariances "sigma" and "significant")
//   model.obj, model.stl   the same geometry
//   objects.csv, objects.json   the detected objects
//   zones.csv, zones.json       the fouling assessment per hull zone
//   shapes.csv     one row per shape of Algorithm 1 (keyframe, size, deviations)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "mapping/mapping_result.h"
#include "results/results_folder.h"

namespace hull {

// The files, into the folder `dir` (created when needed). Programs write a
// whole results folder (SaveMappingResults, or within WriteResultsFolder).
// Throws std::runtime_error when a file cannot be written.
void WriteMappingResult(const MappingResult& result, const std::string& dir);

// `hullinspect-cli map`: the folder out.path replaced as a whole by the
// result's files and a manifest naming `run` (its inputs: those the result
// names, i.e. the adjustment folder, the survey bundle and the mesh).
void SaveMappingResults(const MappingResult& result, const OutputFolder& out, ResultsRun run);

// The texts of objects.csv and zones.csv as WriteMappingResult writes them;
// WriteObjectsCsv / WriteZonesCsv also write the GUI's exports of the
// mapping on screen to a file the user names (atomically).
std::string ObjectsCsv(const MappingResult& result);
std::string ZonesCsv(const MappingResult& result);
void WriteObjectsCsv(const MappingResult& result, const std::string& path);
void WriteZonesCsv(const MappingResult& result, const std::string& path);

// The mapping folder as the report and the GUI need it: options, inputs,
// the hull frame (made again from the CAD mesh `cad` and the adjusted model
// pose x_gM with the recorded axes), the fused model with its scalars, the
// objects, the zones and the summary (Algorithm 1's per-keyframe shapes are
// not read). Throws InputError naming file and field, and when the files
// are not those of one run.
MappingResult ReadMappingResult(const std::string& dir, const TriangleMesh& cad, const Pose& x_gM);

// The mapping results folder of `results`: itself when it holds model.ply,
// else its mapping/ (a pipeline's results folder); nullopt when neither.
std::optional<std::string> FindMappingResults(const std::string& results);

// A mapping results folder as the survey comparison needs it: model.ply with
// its scalars and objects.json (id, centroid, max_height and, when written,
// normal, area and the footprint's vertices). Throws InputError.
struct MappingResultsOnDisk {
  TriangleMesh model;
  std::vector<DetectedObject> objects;
  std::string mesh_path;  // the CAD mapping.json names ("" if none)
  // The manifest of the run that wrote the folder (nullopt: none).
  std::optional<ResultsManifest> manifest;
};
MappingResultsOnDisk ReadMappingResultsForCompare(const std::string& dir);

}  // namespace hull
