// Model-assisted mapping of one adjusted survey (Ozog et al., Section 3):
// Algorithm 1 per keyframe, the mesh refined where the shapes depart from
// the CAD, Algorithm 2's fusion, detected objects and the fouling
// assessment. A Mapper keeps what does not depend on the cheap parameters,
// so that re-running after a change of tau, alpha or eps is fast (the GUI
// keeps one per open survey):
//   - the refined mesh, keyed by the region it was refined for: a run whose
//     departure region lies inside it reuses it; one whose region grows
//     refines the union once (so the cached region only grows);
//   - the inspected area per zone (keyed by stations, bottom angle,
//     inspection spacing and range);
//   - Algorithm 1's shapes (keyed by tau, alpha, eps and min points).
// Runs are serialised (one at a time; a second caller waits).
#pragma once

#include <memory>

#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "mapping/mapping_input.h"
#include "mapping/mapping_options.h"
#include "mapping/mapping_result.h"

namespace hull {

class Mapper {
 public:
  // cad: the prior (CAD) mesh in its own frame M, as the adjustment used it.
  Mapper(MappingInput input, TriangleMesh cad);
  ~Mapper();
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  // Throws OptionError when options fail Check(), hull::Cancelled when
  // progress asks (the caches stay valid; the caller keeps its last result).
  MappingResult Run(const MappingOptions& options, Progress& progress);

  const MappingInput& input() const;
  const TriangleMesh& cad() const;
  // How many times the mesh has been refined (for tests and benchmarks).
  int refinements() const;
  // The mesh the latest run fused into (the CAD refined where shapes departed,
  // in M; fusing along normals, with vertices moved under supported features:
  // SnapVerticesToFeatures), or nullptr before the first run. Valid until the
  // next Run.
  const TriangleMesh* prior_mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One run without keeping a Mapper (the command line, the batch pipeline).
MappingResult RunMapping(MappingInput input, TriangleMesh cad, const MappingOptions& options, Progress& progress);

}  // namespace hull
