// Reading a STEP or IGES file with OpenCASCADE and tessellating its faces
// (the one OCCT-heavy unit of the step-iges plugin; no OCCT type leaks).
#pragma once

#include <string>

#include "plugin/plugin_api.h"

namespace hull::step_iges {

enum class CadFormat { kStep, kIges };

struct TessellationOptions {
  double chord_tolerance = 0.005;  // m: largest distance of a triangle from the surface
  double angular_tolerance = 0.5;  // rad: largest angle between neighbouring triangles' normals
};

// The triangles of every face in metres (a soup: vertices repeat along the
// faces' shared edges; the host merges them) and a report: the file's unit,
// its scale to metres, the surface (face), shell and solid counts, the
// triangle count and the tolerances used. Throws std::runtime_error with
// OpenCASCADE's reason when the file cannot be read or has no surfaces.
plugin::ImportedMesh ReadAndTessellate(const std::string& path, CadFormat format, const TessellationOptions& options);

}  // namespace hull::step_iges
