// What a report is made of: the survey and its prior mesh, the pipeline's
// results (alignment, adjustment, the baselines when the models were
// compared, the evaluation against truth) and, when it ran, mapping's
// (the fused model, detected objects, the fouling assessment per zone).
// Qt-free; the GUI fills it from its session, the headless job from a run or
// from a results folder (results_reader.h).
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "geometry/triangle_mesh.h"
#include "mapping/mapping_result.h"
#include "pipeline/pipeline.h"
#include "results/compare_files.h"
#include "sonar/sonar_pipeline_result.h"
#include "survey/survey.h"

namespace hull::report {

struct ReportInputs {
  // A sonar run's report (sonar_report.h) when set: then only results_path
  // and run_seconds of the rest are read, and bundle, cad and pipeline may
  // be empty.
  std::shared_ptr<const SonarPipelineResult> sonar;
  std::shared_ptr<const SurveyBundle> bundle;      // required (but for a sonar report)
  std::shared_ptr<const TriangleMesh> cad;         // required: the prior (CAD) mesh in M
  std::shared_ptr<const PipelineResult> pipeline;  // required
  std::shared_ptr<const MappingResult> mapping;    // optional: without it the heatmap shows the landmarks
  std::string bundle_path;                         // shown in the summary ("" : the bundle's directory)
  std::string mesh_path;                           // shown in the summary
  // Where the results came from or go to, shown in the summary ("" : not shown).
  std::string results_path;
  // Wall seconds of the whole run (pipeline and mapping) when known (0: not shown).
  double run_seconds = 0;
  // Optional: the change since an earlier survey of the hull (this survey
  // is B), for the "Change between surveys" section.
  std::shared_ptr<const SurveyComparisonRun> comparison;
  // Optional: the 3-D photomosaic of the fused model (mosaic.ply of
  // 'hullinspect-cli mosaic', in M, with the vertex scalars red, green and
  // blue, 0-255: the estimated albedo), for the "Photomosaic" section.
  std::shared_ptr<const TriangleMesh> mosaic;
  std::string mosaic_path;  // shown in the section ("" : not shown)
};

// Throws std::invalid_argument naming the first required member missing
// (a sonar report needs only its sonar run, with at least one step).
void CheckInputs(const ReportInputs& inputs);

struct ReportOptions {
  // The cross-section's slab: its centre in metres from the bow (NaN: through
  // the detected object with the most features, or the middle of the
  // surveyed stretch without mapping) and its width along the hull (m).
  double slab_from_bow = std::nan("");
  double slab_width = 0.30;
  // Half-range of the deviation colour map (m; <= 0: from the data, at
  // least 5 cm).
  double deviation_range = 0;
  // Figure images: width in pixels of the PNGs (the height follows each
  // figure's aspect). The PDF draws the same figures as vectors.
  int figure_width_px = 1600;
  // The significance factor k of the significance heatmap (|h| > k sigma).
  double significance_k = 1.96;
  // Title; "" : "Hull inspection report" and the survey's name.
  std::string title;
};

}  // namespace hull::report
