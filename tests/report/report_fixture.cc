#include "report_fixture.h"

#include <cstdio>
#include <filesystem>

#include "mapping/mapper.h"
#include "pipeline/pipeline.h"
#include "results/mapping_files.h"
#include "results/pipeline_files.h"
#include "simulate/survey_simulator.h"

namespace hull::report::test_data {
namespace fs = std::filesystem;

const DemoRun& Demo() {
  static const DemoRun run = [] {
    DemoRun r;
    r.directory = HI_REPORT_TEST_DIR;
    fs::remove_all(r.directory);
    fs::create_directories(r.directory);
    const std::string bundle_dir = (fs::path(r.directory) / "demo-survey").string();
    NullProgress quiet;
    WriteSimulatedSurvey(SimulateSurvey(SurveyPreset("demo"), quiet), bundle_dir);
    PipelineInputs in = LoadPipelineInputs(bundle_dir);
    PipelineOptions options;
    options.compare_models = true;
    std::fprintf(stderr, "report fixture: running the pipeline and mapping on the demo survey\n");
    auto result = std::make_shared<PipelineResult>(RunPipeline(in, options, quiet));
    auto mapping = std::make_shared<MappingResult>(
        RunMapping(MappingInputFromAdjustment(result->adjustment, in.bundle), in.mesh, MappingOptions{}, quiet));
    r.results = (fs::path(r.directory) / "results").string();
    WritePipelineResult(in, *result, r.results);
    WriteMappingResult(*mapping, (fs::path(r.results) / "mapping").string());

    r.full.bundle_path = in.bundle_path;
    r.full.mesh_path = in.mesh_path;
    r.full.results_path = r.results;
    r.full.bundle = std::make_shared<const SurveyBundle>(std::move(in.bundle));
    r.full.cad = std::make_shared<const TriangleMesh>(std::move(in.mesh));
    r.full.pipeline = result;
    r.full.mapping = mapping;

    r.no_mapping = r.full;
    r.no_mapping.mapping.reset();

    auto one = std::make_shared<PipelineResult>(*result);
    one->baselines.clear();
    one->baseline_evaluations.clear();
    r.one_model = r.full;
    r.one_model.pipeline = one;

    auto untrue = std::make_shared<SurveyBundle>(*r.full.bundle);
    untrue->truth.reset();
    auto no_eval = std::make_shared<PipelineResult>(*result);
    no_eval->evaluation.reset();
    no_eval->baseline_evaluations.clear();
    r.no_truth = r.full;
    r.no_truth.bundle = untrue;
    r.no_truth.pipeline = no_eval;
    return r;
  }();
  return run;
}

}  // namespace hull::report::test_data
