#include "pipeline/pipeline.h"

#include <filesystem>

#include "adjust/bundle_adjuster.h"
#include "geometry/mesh_io.h"
#include "mapping/mapper.h"
#include "mapping/mapping_input.h"
#include "survey/survey_import.h"

namespace hull {
namespace fs = std::filesystem;

PipelineInputs LoadPipelineInputs(const std::string& bundle_dir, const std::string& mesh_path, double mesh_scale,
                                  Progress* progress, const FrontEndOptions& front_end) {
  PipelineInputs in;
  in.bundle = OpenSurveyBundle(bundle_dir);  // a bundle folder, or a survey a plugin converts
  in.bundle_path = fs::absolute(in.bundle.directory).string();
  NullProgress quiet;
  FrontEndResult fe;
  if (ExtractFeaturesIfNeeded(in.bundle, front_end, progress ? *progress : quiet, &fe)) in.front_end = std::move(fe);
  if (in.bundle.features_from_images && in.bundle.truth) in.image_tracks = AttachImageTrackTruth(in.bundle);
  const std::string mesh = mesh_path.empty() ? in.bundle.ModelHintPath() : mesh_path;
  if (mesh.empty()) {
    throw InputError({(fs::path(bundle_dir) / "survey.json").string(), 0, 0, "model_hint"},
                     "the bundle names no mesh (model_hint) and none was given");
  }
  MeshLoadOptions lo;
  lo.scale = mesh_scale;
  in.mesh = LoadMesh(mesh, lo);
  in.mesh_path = fs::absolute(mesh).string();
  in.mesh_scale = mesh_scale;
  return in;
}

void PipelineOptions::Check() const {
  alignment.Check();
  adjustment.Check();
  mapping.Check();
}

ModelAlignment RunAlignment(const PipelineInputs& in, const PipelineOptions& o, Progress& progress) {
  return AlignDvlToModel(in.bundle, in.mesh, ModelPoseGuess(in.bundle), o.alignment, progress);
}

AdjustmentResult RunAdjustmentStep(const PipelineInputs& in, const Pose& x_gM_initial, const AdjustmentOptions& o,
                                   Progress& progress, const AdjustmentResult* warm) {
  AdjustmentResult r = RunAdjustment(in.bundle, in.mesh, x_gM_initial, o, progress, warm);
  r.bundle_path = in.bundle_path;
  r.mesh_path = in.mesh_path;
  r.mesh_scale = in.mesh_scale;
  return r;
}

MappingResult RunMappingStep(const PipelineInputs& in, const AdjustmentResult& adjustment,
                             const MappingOptions& options, Progress& progress) {
  MappingResult m = RunMapping(MappingInputFromAdjustment(adjustment, in.bundle), in.mesh, options, progress);
  m.inputs.emplace_back("bundle", in.bundle_path);
  m.inputs.emplace_back("mesh", in.mesh_path);
  return m;
}

PipelineResult RunPipeline(const PipelineInputs& in, const PipelineOptions& o, Progress& progress) {
  o.Check();
  PipelineResult r;
  r.image_tracks = in.image_tracks;
  {
    SubProgress p(progress, 0.0, 0.1);
    r.alignment = RunAlignment(in, o, p);
  }
  // Progress shares: alignment 10 %, the adjustments, mapping 20 %.
  const int runs = o.compare_models ? 3 : 1;
  const double adjust_end = o.run_mapping ? 0.8 : 1.0;
  const double share = (adjust_end - 0.1) / runs;
  {
    SubProgress p(progress, 0.1, 0.1 + share);
    r.adjustment = RunAdjustmentStep(in, r.alignment.x_gM, o.adjustment, p);
  }
  if (in.bundle.truth) r.evaluation = EvaluateAdjustment(in.bundle, in.mesh, r.adjustment);
  if (o.compare_models) {
    int k = 1;
    for (SurfaceModel m : {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture}) {
      if (m == o.adjustment.model) continue;
      AdjustmentOptions b = o.adjustment;
      b.model = m;
      SubProgress p(progress, 0.1 + share * k, 0.1 + share * (k + 1));
      r.baselines.push_back(RunAdjustmentStep(in, r.alignment.x_gM, b, p));
      if (in.bundle.truth) r.baseline_evaluations.push_back(EvaluateAdjustment(in.bundle, in.mesh, r.baselines.back()));
      ++k;
    }
  }
  if (o.run_mapping) {
    SubProgress p(progress, adjust_end, 1.0);
    r.mapping = RunMappingStep(in, r.adjustment, o.mapping, p);
  }
  progress.Update(1.0, "pipeline done");
  return r;
}

}  // namespace hull
