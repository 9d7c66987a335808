// The pipeline's results folder (docs/results-format.md, "Pipeline results,
// version 1"), the one owner of its summary.json:
//   summary.json      format "hull-pipeline": inputs, the adjustment's
//                     outcome and, when mapped, the mapping's
//   alignment.json    the initial alignment (alignment_file.h)
//   adjustment/       the chosen model's adjustment (adjustment_files.h)
//   adjustment-<model>/  the baselines, with --compare-models
//   mapping/          the mapping (mapping_files.h), when it ran
//   features/         features.csv and match-graph.csv, when the front end ran
//   evaluation.txt    against the bundle's truth, when it has one
#pragma once

#include <cstdint>
#include <string>

#include "pipeline/pipeline.h"
#include "results/results_folder.h"

namespace hull {

struct PipelineSummary {
  std::string bundle, mesh;  // absolute
  double mesh_scale = 1.0;
  std::string model;  // the surface model's name
  std::int64_t keyframes = 0, landmarks = 0;
  double fraction_on_surface = 0;
  double adjustment_seconds = 0;  // wall
  bool converged = false;
  // When mapped: the objects found, the remeshed model (absolute, where the
  // folder lies) and the inspected and covered areas (m^2).
  bool mapped = false;
  std::int64_t objects = 0;
  std::string remeshed_model;
  double inspected_area = 0, covered_area = 0;
};

// What summary.json says of a run whose folder is final_dir.
PipelineSummary SummarisePipeline(const PipelineInputs& in, const PipelineResult& result, const std::string& final_dir);
void WritePipelineSummary(const PipelineSummary& summary, const std::string& dir);
PipelineSummary ReadPipelineSummary(const std::string& dir);

// The files into `dir` (created when needed); final_dir is where the folder
// will lie ("": dir), for the paths summary.json records.
void WritePipelineResult(const PipelineInputs& in, const PipelineResult& result, const std::string& dir,
                         const std::string& final_dir = "");
// `hullinspect-cli run`: the folder out.path replaced as a whole by the
// files and a manifest naming `run` (inputs: the bundle and the mesh).
void SavePipelineResults(const PipelineInputs& in, const PipelineResult& result, const OutputFolder& out,
                         ResultsRun run);

// A pipeline's folder as the report reads it: the summary, the alignment,
// the adjustment and its baselines (no evaluation: that needs the bundle),
// and where its mapping and photomosaic lie ("" : none). Throws InputError
// naming file and field, and when the files are not those of one run.
struct PipelineResultsOnDisk {
  PipelineSummary summary;
  PipelineResult result;
  std::string mapping_dir;
  std::string mosaic_dir;
};
PipelineResultsOnDisk ReadPipelineResults(const std::string& dir);

// Before writing a survey's results into `dir` (an existing results folder
// the GUI adds to): throws InputError when dir's adjustment (dir/adjustment
// or dir itself) was computed from another survey than `bundle_dir` (by the
// manifest's fingerprint; by the path adjustment.json records for results
// without a manifest).
void CheckResultsFolderOfSurvey(const std::string& dir, const std::string& bundle_dir);

// True when `dir` holds a pipeline's summary.json.
bool IsPipelineResults(const std::string& dir);

}  // namespace hull
