// Report inputs from a results folder: what WritePipelineResult wrote
// (summary.json naming the bundle and mesh, alignment.json, adjustment/ and
// adjustment-<model>/ for the compared models) and, in its mapping/
// sub-folder, what WriteMappingResult wrote; mosaic/mosaic.ply when
// 'hullinspect-cli mosaic' wrote one (the report's Photomosaic section). The survey bundle and the mesh
// are read from the paths summary.json names; the evaluation against truth
// is computed again when the bundle has truth.
#pragma once

#include <string>

#include "ui/report/report_inputs.h"

namespace hull::report {

// Throws InputError naming the file at fault (a missing summary.json, a
// bundle or mesh that cannot be read, a malformed result).
ReportInputs ReadReportInputs(const std::string& results_dir);

}  // namespace hull::report
