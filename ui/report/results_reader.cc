#include "ui/report/results_reader.h"

#include <filesystem>

#include "base/error.h"
#include "results/mapping_files.h"
#include "results/mosaic_files.h"
#include "results/pipeline_files.h"

namespace hull::report {
namespace fs = std::filesystem;

ReportInputs ReadReportInputs(const std::string& results_dir) {
  PipelineResultsOnDisk disk = ReadPipelineResults(results_dir);
  PipelineInputs in = LoadPipelineInputs(disk.summary.bundle, disk.summary.mesh, disk.summary.mesh_scale);

  auto result = std::make_shared<PipelineResult>(std::move(disk.result));
  if (in.bundle.truth) {
    result->evaluation = EvaluateAdjustment(in.bundle, in.mesh, result->adjustment);
    for (const AdjustmentResult& b : result->baselines) {
      result->baseline_evaluations.push_back(EvaluateAdjustment(in.bundle, in.mesh, b));
    }
  }

  ReportInputs r;
  if (!disk.mapping_dir.empty()) {
    r.mapping = std::make_shared<const MappingResult>(
        ReadMappingResult(disk.mapping_dir, in.mesh, Pose::FromVector(result->adjustment.x_gM)));
  }
  if (!disk.mosaic_dir.empty()) {
    r.mosaic = ReadMosaicColours(disk.mosaic_dir);
    r.mosaic_path = fs::absolute(fs::path(disk.mosaic_dir) / kMosaicPly).string();
  }
  r.bundle_path = in.bundle_path;
  r.mesh_path = in.mesh_path;
  r.results_path = fs::absolute(results_dir).string();
  r.bundle = std::make_shared<const SurveyBundle>(std::move(in.bundle));
  r.cad = std::make_shared<const TriangleMesh>(std::move(in.mesh));
  r.pipeline = std::move(result);
  return r;
}

}  // namespace hull::report
