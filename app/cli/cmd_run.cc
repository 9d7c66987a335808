// hullinspect-cli run: the headless main job, alignment -> adjustment -> results.
#include <cstdio>
#include <filesystem>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "pipeline/pipeline.h"
#include "results/pipeline_job.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli run BUNDLE --out DIR [options]
       hullinspect-cli run --demo --out DIR [options]

The whole model-assisted pipeline without a display: the initial model pose
(GICP of the DVL returns to the mesh), the model-assisted bundle adjustment,
the mapping (shapes, remeshed hull with deviations, objects, fouling zones)
and the results in DIR. --demo first simulates the embedded demo survey into
DIR/demo-survey and runs on it.

options:
  --mesh PATH          prior mesh (default: the bundle's model_hint)
  --mesh-scale S       scale applied to the mesh on load
  --model NAME         max-mixture (default), all-on-surface or naive
  --sigma0 M --sigma1 M
  --labels RULE        cavity (default) or estimate (see 'adjust --help')
  --compare-models     also run the two other surface models
  --tau M --grow-height M --alpha M --eps M --min-points N
  --peak-fit | --no-peak-fit
                       mapping (see 'map --help')
  --max-iterations N   --threads N
  --max-features N     a version 2 bundle without features.csv: the front
                       end's SIFT features per image (default 2000; see
                       'features --help')
  --covariance M       landmark covariances and sigma of h: full (default),
                       conditional (poses held fixed; cheap) or none
  --force              write into an --out folder that holds files HullInspect
                       did not write (they are kept; none is replaced)
  --quiet

DIR must be new, empty or a results folder HullInspect wrote (checked before
any work, exit 2); it is replaced as a whole, and the user's own files in it
are kept (docs/results-format.md).
)";

}  // namespace

int RunPipeline(const CommandArgs& argv) {
  Args a(argv, {"demo", "compare-models", "quiet", "peak-fit", "no-peak-fit", "force"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"demo",       "mesh",           "mesh-scale",   "model",       "sigma0", "sigma1",
               "labels",     "compare-models", "tau",          "grow-height", "alpha",  "eps",
               "min-points", "max-iterations", "threads",      "covariance",  "quiet",  "out",
               "peak-fit",   "no-peak-fit",    "max-features", "force"});
  if (!a.Has("out") || a.Get("out").empty()) throw UsageError("--out DIR is required");
  const OutputFolder out{a.Get("out"), a.Has("force")};
  CheckResultsFolder(out);
  PipelineSource source;
  source.demo = a.Has("demo");
  if (source.demo) {
    if (!a.positionals().empty()) throw UsageError("--demo takes no bundle argument");
  } else {
    if (a.positionals().size() != 1) throw UsageError("expected one survey bundle (or --demo)");
    source.bundle = a.positionals()[0];
  }
  PipelineOptions o;
  o.adjustment.model = ParseSurfaceModel(a.Get("model", "max-mixture"));
  o.adjustment.sigma0 = a.GetDouble("sigma0", o.adjustment.sigma0);
  o.adjustment.sigma1 = a.GetDouble("sigma1", o.adjustment.sigma1);
  o.adjustment.labels = ParseLabelRule(a.Get("labels", LabelRuleName(o.adjustment.labels)));
  o.adjustment.max_iterations = static_cast<int>(a.GetInt("max-iterations", o.adjustment.max_iterations));
  o.adjustment.num_threads = static_cast<int>(a.GetInt("threads", 0));
  o.adjustment.covariance = ParseCovarianceMethod(a.Get("covariance", "full"));
  o.compare_models = a.Has("compare-models");
  o.mapping.tau = a.GetDouble("tau", o.mapping.tau);
  o.mapping.shape_grow_height = a.GetDouble("grow-height", o.mapping.shape_grow_height);
  o.mapping.alpha = a.GetDouble("alpha", o.mapping.alpha);
  o.mapping.dbscan_eps = a.GetDouble("eps", o.mapping.dbscan_eps);
  o.mapping.dbscan_min_points = static_cast<int>(a.GetInt("min-points", o.mapping.dbscan_min_points));
  if (a.Has("peak-fit") && a.Has("no-peak-fit")) throw UsageError("--peak-fit and --no-peak-fit contradict each other");
  if (a.Has("peak-fit")) o.mapping.peak_fit = true;
  if (a.Has("no-peak-fit")) o.mapping.peak_fit = false;
  o.Check();
  source.front_end.threads = o.adjustment.num_threads;
  source.front_end.detection.max_features =
      static_cast<int>(a.GetInt("max-features", source.front_end.detection.max_features));
  source.front_end.Check();
  source.mesh = a.Get("mesh", "");
  source.mesh_scale = a.GetDouble("mesh-scale", 1.0);
  ConsoleProgress progress(a.Has("quiet"));
  const PipelineRun job = RunPipelineJob(source, o, out, "run", progress);
  progress.Finish();
  const PipelineInputs& in = job.inputs;
  const PipelineResult& r = job.result;
  if (in.front_end) {
    std::printf("front end: %d landmarks, %zu observations from the images (%.1f s)\n", in.front_end->landmarks,
                in.front_end->features.size(), in.front_end->seconds);
  }
  std::printf("alignment: DVL residual RMS %.4f -> %.4f m (%d of 6 directions fixed by the returns)\n",
              r.alignment.residual_rms_before, r.alignment.residual_rms_after, r.alignment.constrained_directions);
  std::printf("%s adjustment: %zu landmarks, lambda=1 for %.1f %%, %.1f s, %s\n",
              SurfaceModelName(r.adjustment.options.model), r.adjustment.landmarks.size(),
              100 * r.adjustment.FractionOnSurface(), r.adjustment.seconds, r.adjustment.termination.c_str());
  if (r.evaluation) std::printf("%s", r.evaluation->ToString().c_str());
  if (r.mapping) {
    std::printf("mapping: %zu shapes, %zu objects detected; remeshed model %s\n", r.mapping->summary.shapes,
                r.mapping->objects.size(), (std::filesystem::path(job.folder) / "mapping" / "model.ply").c_str());
  }
  std::printf("wrote %s\n", job.folder.c_str());
  return kExitOk;
}

}  // namespace hull::cli
