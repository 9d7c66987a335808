// Writing the fused, remeshed model for other tools: PLY, OBJ and STL by
// SaveMesh, every other format (glTF 2.0, ...) by a result exporter plugin
// (plugin::ResultExporter), so the CLI and the GUI offer the same formats.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace hull {

// Writes `model` (with its "deviation" and "fusions" vertex scalars) to
// `target`, the format by the extension. `results_dir` is the pipeline's
// output folder an exporter may take more from (mosaic/: the photomosaic);
// empty when the results were never written. Returns what a plugin
// exporter reported (empty for the built-in formats). Throws
// std::invalid_argument for an extension nothing writes.
std::vector<std::pair<std::string, std::string>> ExportModel(const TriangleMesh& model, const std::string& results_dir,
                                                             const std::string& target);

// Every extension ExportModel writes (".ply", ".obj", ".stl", then the
// plugins'), lower case with the dot.
std::vector<std::string> ModelExportExtensions();

}  // namespace hull
