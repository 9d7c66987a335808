// The initial alignment's record, alignment.json (docs/results-format.md,
// "alignment.json"): written by `hullinspect-cli run` into its results
// folder and by `hullinspect-cli align --out FILE`; read by the report.
#pragma once

#include <string>

#include "registration/model_alignment.h"

namespace hull {

// Where the alignment came from, recorded with it.
struct AlignmentSources {
  std::string bundle;  // absolute
  std::string mesh;    // absolute
  double mesh_scale = 1.0;
};

// The text of alignment.json (format "hull-alignment", version 2).
std::string AlignmentJson(const ModelAlignment& alignment, const AlignmentSources& sources);
// Writes it to `path` atomically.
void WriteAlignment(const ModelAlignment& alignment, const AlignmentSources& sources, const std::string& path);
// Reads version 2 and the version 1 files of older results (x_gM,
// initial_x_gM, the GICP's fit, the DVL residuals' RMS; per-beam residuals
// where written). Throws InputError naming file and field.
ModelAlignment ReadAlignment(const std::string& path, AlignmentSources* sources = nullptr);

}  // namespace hull
