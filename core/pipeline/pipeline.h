// The end-to-end job: survey bundle + prior mesh -> initial alignment (GICP
// of the DVL returns) -> model-assisted bundle adjustment -> model-assisted
// mapping (shapes, remeshed hull, objects, fouling assessment); its results
// folder is results/pipeline_files.h's. Qt-free; the GUI runs the same steps in worker threads, one at a time, and
// the CLI's `run` command (the headless main job) runs them in a row.
#pragma once

#include <optional>
#include <string>

#include "adjust/adjust_options.h"
#include "adjust/adjust_result.h"
#include "adjust/evaluation.h"
#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "mapping/mapping_options.h"
#include "mapping/mapping_result.h"
#include "registration/model_alignment.h"
#include "simulate/image_track_truth.h"
#include "survey/survey.h"
#include "vision/front_end.h"
#include "vision/vision_options.h"

namespace hull {

struct PipelineInputs {
  SurveyBundle bundle;
  TriangleMesh mesh;        // the prior (CAD) mesh in M
  std::string bundle_path;  // absolute
  std::string mesh_path;    // absolute
  double mesh_scale = 1.0;
  // Set when the bundle's observations came from its images (a version 2
  // bundle without features.csv): what the visual front end found.
  std::optional<FrontEndResult> front_end;
  // Tracks from the front end on a simulated survey with truth/scene.ply:
  // their truth, derived from the true scene (bundle.truth->landmarks holds it).
  std::optional<ImageTrackTruth> image_tracks;
};

// Reads the bundle and its mesh (mesh_path empty: the bundle's model_hint).
// A version 2 bundle with images and no features.csv gets its feature
// observations from the visual front end (vision/front_end.h, `front_end`
// options; progress reported to `progress` when given). Throws InputError
// naming the file at fault.
PipelineInputs LoadPipelineInputs(const std::string& bundle_dir, const std::string& mesh_path = "",
                                  double mesh_scale = 1.0, Progress* progress = nullptr,
                                  const FrontEndOptions& front_end = {});

struct PipelineOptions {
  // GICP of the DVL returns to the mesh, from the bundle's model_pose_guess
  // when it has one, else after a coarse search (see model_alignment.h).
  ModelAlignmentOptions alignment;
  AdjustmentOptions adjustment;
  // Also run the two baselines (naive, all-on-surface) for comparison.
  bool compare_models = false;
  MappingOptions mapping;
  bool run_mapping = true;

  void Check() const;  // throws OptionError
};

struct PipelineResult {
  ModelAlignment alignment;
  AdjustmentResult adjustment;                     // with options.adjustment.model
  std::vector<AdjustmentResult> baselines;         // compare_models: the other two models
  std::optional<AdjustmentEvaluation> evaluation;  // when the bundle has truth
  std::vector<AdjustmentEvaluation> baseline_evaluations;
  std::optional<MappingResult> mapping;         // of the chosen model's adjustment
  std::optional<ImageTrackTruth> image_tracks;  // the inputs', for evaluation.txt
};

// Step 1: the initial model pose.
ModelAlignment RunAlignment(const PipelineInputs& in, const PipelineOptions& options, Progress& progress);
// Step 2: adjustment from an alignment (warm: optional previous result).
AdjustmentResult RunAdjustmentStep(const PipelineInputs& in, const Pose& x_gM_initial, const AdjustmentOptions& options,
                                   Progress& progress, const AdjustmentResult* warm = nullptr);
// Step 3: mapping of an adjustment (one run; the GUI keeps a Mapper instead).
MappingResult RunMappingStep(const PipelineInputs& in, const AdjustmentResult& adjustment,
                             const MappingOptions& options, Progress& progress);
// All steps.
PipelineResult RunPipeline(const PipelineInputs& in, const PipelineOptions& options, Progress& progress);

}  // namespace hull
