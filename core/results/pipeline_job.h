// The whole pipeline as one job writing one results folder: `hullinspect-cli
// run` and the headless `hullinspect --demo` (app/report). The survey is a
// bundle (or a survey a plugin converts) or the embedded demo, simulated
// into the new folder's demo-survey/; the run happens before the folder is
// swapped into place, so a run that fails, is cancelled or killed leaves
// the previous folder whole (and a new --out folder does not appear).
#pragma once

#include <functional>
#include <string>

#include "base/progress.h"
#include "pipeline/pipeline.h"
#include "results/results_folder.h"
#include "vision/vision_options.h"

namespace hull {

struct PipelineSource {
  std::string bundle;  // the survey ("" with demo)
  bool demo = false;   // the embedded demo survey, simulated into DIR/demo-survey
  std::string mesh;    // the prior mesh ("" : the bundle's model_hint)
  double mesh_scale = 1.0;
  FrontEndOptions front_end;  // for a version 2 bundle without features.csv
};

struct PipelineRun {
  PipelineInputs inputs;  // paths as they lie once the folder is in place
  PipelineResult result;
  std::string folder;  // the results folder (absolute)
};

// Runs the pipeline and writes its results folder (results/pipeline_files.h)
// as a whole, with a manifest naming a run of `command`. `more`, when given,
// writes further files into the new folder before the swap (the headless
// job's report), with the run's final folder in PipelineRun::folder.
// Progress: the demo's simulation 5 %, the front end 20 % when it runs.
// Throws as CheckResultsFolder (before any work), LoadPipelineInputs,
// RunPipeline and WriteResultsFolder.
PipelineRun RunPipelineJob(const PipelineSource& source, const PipelineOptions& options, const OutputFolder& out,
                           const std::string& command, Progress& progress,
                           const std::function<void(const std::string& tmp, const PipelineRun& run)>& more = {});

}  // namespace hull
