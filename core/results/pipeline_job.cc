#include "results/pipeline_job.h"

#include <filesystem>

#include "results/pipeline_files.h"
#include "simulate/survey_simulator.h"

namespace hull {
namespace {

namespace fs = std::filesystem;

// `path` under `from` moved to the same place under `to`; other paths as they are.
std::string Moved(const std::string& path, const fs::path& from, const fs::path& to) {
  const fs::path rel = fs::path(path).lexically_relative(from);
  if (rel.empty() || *rel.begin() == "..") return path;
  return (to / rel).lexically_normal().string();
}

// The survey and mesh read, the paths recorded as they will lie.
PipelineInputs LoadInputs(const PipelineSource& source, const std::string& tmp, const fs::path& final_dir,
                          ResultsRun& run, Progress& progress) {
  std::string bundle = source.bundle;
  double start = 0;
  if (source.demo) {
    bundle = (fs::path(tmp) / "demo-survey").string();
    SubProgress p(progress, 0, 0.05);
    WriteSimulatedSurvey(SimulateSurvey(SurveyPreset("demo"), p), bundle);
    start = 0.05;
  }
  // A version 2 bundle without features.csv: the visual front end first.
  SubProgress pf(progress, start, start + 0.2);
  PipelineInputs in = LoadPipelineInputs(bundle, source.mesh, source.mesh_scale, &pf, source.front_end);
  const std::string bundle_read = in.bundle_path, mesh_read = in.mesh_path;
  in.bundle_path = Moved(in.bundle_path, tmp, final_dir);
  in.mesh_path = Moved(in.mesh_path, tmp, final_dir);
  run.AddSurvey("bundle", bundle_read, in.bundle_path);
  run.AddFile("mesh", mesh_read);
  run.inputs.back().path = in.mesh_path;
  return in;
}

}  // namespace

PipelineRun RunPipelineJob(const PipelineSource& source, const PipelineOptions& options, const OutputFolder& out,
                           const std::string& command, Progress& progress,
                           const std::function<void(const std::string& tmp, const PipelineRun& run)>& more) {
  options.Check();
  source.front_end.Check();
  CheckResultsFolder(out);
  PipelineRun job;
  job.folder = fs::absolute(out.path).lexically_normal().string();
  ResultsRun run = NewResultsRun(command);
  WriteResultsFolder(out, run, [&](const std::string& tmp) {
    job.inputs = LoadInputs(source, tmp, job.folder, run, progress);
    const double start = (source.demo ? 0.05 : 0.0) + (job.inputs.front_end ? 0.2 : 0.0);
    SubProgress p(progress, start, 1.0);
    job.result = RunPipeline(job.inputs, options, p);
    WritePipelineResult(job.inputs, job.result, tmp, job.folder);
    if (more) more(tmp, job);
  });
  return job;
}

}  // namespace hull
