#include "results/pipeline_files.h"

#include <filesystem>

#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "results/adjustment_files.h"
#include "results/alignment_file.h"
#include "results/front_end_files.h"
#include "results/mapping_files.h"
#include "results/mosaic_files.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

std::string EvaluationText(const PipelineResult& r) {
  std::string eval;
  if (r.image_tracks) eval += r.image_tracks->ToString() + "\n";
  if (r.evaluation)
    eval += std::string(SurfaceModelName(r.adjustment.options.model)) + ":\n" + r.evaluation->ToString();
  for (std::size_t i = 0; i < r.baseline_evaluations.size(); ++i) {
    eval += std::string(SurfaceModelName(r.baselines[i].options.model)) + ":\n" + r.baseline_evaluations[i].ToString();
  }
  return eval;
}

std::string AdjustmentFolderName(const AdjustmentResult& a) {
  return "adjustment-" + std::string(SurfaceModelName(a.options.model));
}

}  // namespace

PipelineSummary SummarisePipeline(const PipelineInputs& in, const PipelineResult& r, const std::string& final_dir) {
  PipelineSummary s;
  s.bundle = in.bundle_path;
  s.mesh = in.mesh_path;
  s.mesh_scale = in.mesh_scale;
  s.model = SurfaceModelName(r.adjustment.options.model);
  s.keyframes = static_cast<std::int64_t>(in.bundle.nav.size());
  s.landmarks = static_cast<std::int64_t>(r.adjustment.landmarks.size());
  s.fraction_on_surface = r.adjustment.FractionOnSurface();
  s.adjustment_seconds = r.adjustment.seconds;
  s.converged = r.adjustment.converged;
  if (r.mapping) {
    s.mapped = true;
    s.objects = static_cast<std::int64_t>(r.mapping->objects.size());
    s.remeshed_model = (fs::path(final_dir) / "mapping" / "model.ply").string();
    s.inspected_area = r.mapping->summary.inspected_area;
    s.covered_area = r.mapping->summary.covered_area;
  }
  return s;
}

void WritePipelineSummary(const PipelineSummary& p, const std::string& dir) {
  Json s = Json::Object();
  s.Set("format", "hull-pipeline");
  s.Set("version", 1);
  s.Set("bundle", p.bundle);
  s.Set("mesh", p.mesh);
  s.Set("mesh_scale", p.mesh_scale);
  s.Set("model", p.model);
  s.Set("keyframes", p.keyframes);
  s.Set("landmarks", p.landmarks);
  s.Set("fraction_on_surface", p.fraction_on_surface);
  s.Set("adjustment_seconds", p.adjustment_seconds);
  s.Set("converged", p.converged);
  if (p.mapped) {
    s.Set("objects", p.objects);
    s.Set("remeshed_model", p.remeshed_model);
    s.Set("inspected_area", p.inspected_area);
    s.Set("covered_area", p.covered_area);
  }
  WriteFileAtomic(Path(dir, "summary.json"), s.Dump());
}

PipelineSummary ReadPipelineSummary(const std::string& dir) {
  const std::string path = Path(dir, "summary.json");
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader r(doc, path);
  if (r.String("format") != "hull-pipeline") r.Fail(r.Required("format"), "format", "expected \"hull-pipeline\"");
  PipelineSummary s;
  s.bundle = r.String("bundle");
  s.mesh = r.String("mesh");
  s.mesh_scale = r.NumberOr("mesh_scale", 1.0);
  s.model = r.OptionalString("model").value_or("");
  s.keyframes = static_cast<std::int64_t>(r.NumberOr("keyframes", 0));
  s.landmarks = static_cast<std::int64_t>(r.NumberOr("landmarks", 0));
  s.fraction_on_surface = r.NumberOr("fraction_on_surface", 0);
  s.adjustment_seconds = r.NumberOr("adjustment_seconds", 0);
  if (const Json* c = doc.Get("converged"); c && c->is_bool()) s.converged = c->as_bool();
  s.mapped = r.Has("remeshed_model");
  s.objects = static_cast<std::int64_t>(r.NumberOr("objects", 0));
  s.remeshed_model = r.OptionalString("remeshed_model").value_or("");
  s.inspected_area = r.NumberOr("inspected_area", 0);
  s.covered_area = r.NumberOr("covered_area", 0);
  return s;
}

void WritePipelineResult(const PipelineInputs& in, const PipelineResult& r, const std::string& dir,
                         const std::string& final_dir) {
  fs::create_directories(dir);
  if (in.front_end) WriteFrontEndResult(*in.front_end, in.bundle.manifest, Path(Path(dir, "features"), "features.csv"));
  WriteAlignment(r.alignment, {in.bundle_path, in.mesh_path, in.mesh_scale}, Path(dir, "alignment.json"));
  WriteAdjustmentResult(r.adjustment, Path(dir, "adjustment"));
  for (const auto& b : r.baselines) WriteAdjustmentResult(b, (fs::path(dir) / AdjustmentFolderName(b)).string());
  if (r.mapping) WriteMappingResult(*r.mapping, Path(dir, "mapping"));
  const std::string eval = EvaluationText(r);
  if (!eval.empty()) WriteFileAtomic(Path(dir, "evaluation.txt"), eval);
  WritePipelineSummary(SummarisePipeline(in, r, final_dir.empty() ? dir : final_dir), dir);
}

void SavePipelineResults(const PipelineInputs& in, const PipelineResult& r, const OutputFolder& out, ResultsRun run) {
  run.AddSurvey("bundle", in.bundle_path);
  run.AddFile("mesh", in.mesh_path);
  const std::string final_dir = fs::absolute(out.path).lexically_normal().string();
  WriteResultsFolder(out, run, [&](const std::string& tmp) { WritePipelineResult(in, r, tmp, final_dir); });
}

namespace {

bool SamePath(const std::string& a, const std::string& b) {
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ea);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b), eb);
  if (ea || eb) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  return ca == cb;
}

}  // namespace

void CheckResultsFolderOfSurvey(const std::string& dir, const std::string& bundle_dir) {
  std::error_code ec;
  for (const fs::path& json : {fs::path(dir) / "adjustment" / "adjustment.json", fs::path(dir) / "adjustment.json"}) {
    if (!fs::is_regular_file(json, ec)) continue;
    const std::optional<ResultsManifest> m = ManifestOf(json.string());
    if (m && !m->legacy) {
      CheckBundleOfResults(json.string(), bundle_dir);
      continue;
    }
    const Json doc = Json::Parse(ReadFileToString(json.string()), json.string());
    const Json* inputs = doc.Get("inputs");
    const Json* bundle = inputs ? inputs->Get("bundle") : nullptr;
    if (bundle && bundle->is_string() && !bundle->as_string().empty() && !SamePath(bundle->as_string(), bundle_dir)) {
      throw InputError({json.string(), 0, 0, "inputs.bundle"},
                       "the folder holds the results of another survey (" + bundle->as_string() + "), not of " +
                           bundle_dir + ": choose an empty folder or this survey's results folder");
    }
  }
}

bool IsPipelineResults(const std::string& dir) {
  std::error_code ec;
  return fs::is_regular_file(Path(dir, "summary.json"), ec) && fs::is_regular_file(Path(dir, "alignment.json"), ec);
}

PipelineResultsOnDisk ReadPipelineResults(const std::string& dir) {
  CheckResultsFiles({Path(dir, "summary.json"), Path(dir, "alignment.json"), Path(dir, "adjustment/adjustment.json")},
                    "the pipeline's results in " + dir);
  PipelineResultsOnDisk out;
  out.summary = ReadPipelineSummary(dir);
  out.result.alignment = ReadAlignment(Path(dir, "alignment.json"));
  out.result.adjustment = ReadAdjustmentResult(Path(dir, "adjustment"));
  for (SurfaceModel m : {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture}) {
    const fs::path b = fs::path(dir) / ("adjustment-" + std::string(SurfaceModelName(m)));
    if (m != out.result.adjustment.options.model && fs::is_directory(b)) {
      out.result.baselines.push_back(ReadAdjustmentResult(b.string()));
    }
  }
  std::error_code ec;
  if (fs::is_regular_file(fs::path(dir) / "mapping" / "mapping.json", ec)) out.mapping_dir = Path(dir, "mapping");
  if (fs::is_regular_file(fs::path(dir) / "mosaic" / kMosaicPly, ec)) out.mosaic_dir = Path(dir, "mosaic");
  return out;
}

}  // namespace hull
