#include "pipeline/pipeline.h"

#include <filesystem>

#include "adjust/bundle_adjuster.h"
#include "base/atomic_directory.h"
#include "base/file_io.h"
#include "base/json.h"
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

namespace {
Json PoseJson(const Pose& p) {
  const Vector6d v = p.ToVector();
  Json a = Json::Array();
  for (int i = 0; i < 6; ++i) a.Push(Json(v[i]));
  return a;
}
}  // namespace

void WritePipelineResult(const PipelineInputs& in, const PipelineResult& r, const std::string& final_dir) {
  WriteDirectoryAtomic(final_dir, [&](const std::string& dir) {
    if (in.front_end) {
      WriteFrontEndResult(*in.front_end, in.bundle.manifest, (fs::path(dir) / "features" / "features.csv").string());
    }
    {
      Json j = Json::Object();
      j.Set("format", "hull-alignment");
      j.Set("version", 1);
      j.Set("x_gM", PoseJson(r.alignment.x_gM));
      j.Set("initial_x_gM", PoseJson(r.alignment.initial_x_gM));
      j.Set("gicp_converged", r.alignment.gicp.converged);
      j.Set("gicp_fitness", r.alignment.gicp.fitness);
      j.Set("constrained_directions", r.alignment.constrained_directions);
      j.Set("dvl_points", static_cast<std::int64_t>(r.alignment.dvl_points));
      j.Set("residual_rms_before", r.alignment.residual_rms_before);
      j.Set("residual_rms_after", r.alignment.residual_rms_after);
      WriteFileAtomic((fs::path(dir) / "alignment.json").string(), j.Dump());
    }
    WriteAdjustmentResult(r.adjustment, (fs::path(dir) / "adjustment").string());
    for (const auto& b : r.baselines) {
      WriteAdjustmentResult(
          b, (fs::path(dir) / ("adjustment-" + std::string(SurfaceModelName(b.options.model)))).string());
    }
    if (r.mapping) WriteMappingResult(*r.mapping, (fs::path(dir) / "mapping").string());
    std::string eval;
    if (r.image_tracks) eval += r.image_tracks->ToString() + "\n";
    if (r.evaluation) {
      eval += std::string(SurfaceModelName(r.adjustment.options.model)) + ":\n" + r.evaluation->ToString();
    }
    for (std::size_t i = 0; i < r.baseline_evaluations.size(); ++i) {
      eval +=
          std::string(SurfaceModelName(r.baselines[i].options.model)) + ":\n" + r.baseline_evaluations[i].ToString();
    }
    if (!eval.empty()) WriteFileAtomic((fs::path(dir) / "evaluation.txt").string(), eval);
    Json s = Json::Object();
    s.Set("format", "hull-pipeline");
    s.Set("version", 1);
    s.Set("bundle", in.bundle_path);
    s.Set("mesh", in.mesh_path);
    s.Set("mesh_scale", in.mesh_scale);
    s.Set("model", SurfaceModelName(r.adjustment.options.model));
    s.Set("keyframes", static_cast<std::int64_t>(in.bundle.nav.size()));
    s.Set("landmarks", static_cast<std::int64_t>(r.adjustment.landmarks.size()));
    s.Set("fraction_on_surface", r.adjustment.FractionOnSurface());
    s.Set("adjustment_seconds", r.adjustment.seconds);
    s.Set("converged", r.adjustment.converged);
    if (r.mapping) {
      s.Set("objects", static_cast<std::int64_t>(r.mapping->objects.size()));
      s.Set("remeshed_model", (fs::path(final_dir) / "mapping" / "model.ply").string());
      s.Set("inspected_area", r.mapping->summary.inspected_area);
      s.Set("covered_area", r.mapping->summary.covered_area);
    }
    WriteFileAtomic((fs::path(dir) / "summary.json").string(), s.Dump());
  });
}

}  // namespace hull
