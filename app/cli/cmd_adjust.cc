// hullinspect-cli adjust: model-assisted bundle adjustment of a survey.
#include <cstdio>
#include <filesystem>

#include "adjust/evaluation.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "pipeline/pipeline.h"
#include "results/adjustment_files.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli adjust BUNDLE --out DIR [options]

Model-assisted bundle adjustment (Ozog et al.): vehicle poses, servo angles,
camera extrinsic, model pose and landmarks, with a surface constraint on every
landmark. Writes the results folder (docs/results-format.md).

options:
  --mesh PATH          prior mesh (default: the bundle's model_hint)
  --mesh-scale S       scale applied to the mesh on load
  --model NAME         max-mixture (default), all-on-surface or naive
  --sigma0 M           off-model sigma (default 1.0)
  --sigma1 M           on-model sigma (default 0.02)
  --labels RULE        the max-mixture's E-step: cavity (default; a landmark
                       on the model is judged again by its estimate without
                       its own surface factor, docs/adjustment.md) or
                       estimate (the paper's: by its current estimate)
  --lookup NAME        closest-face (default) or nearest-vertex (the paper's)
  --max-iterations N   Levenberg-Marquardt iterations (default 100)
  --threads N          0: all cores (default)
  --linear-solver S    sparse-schur (default) or iterative-schur (less memory, slower)
  --covariance M       landmark covariances and sigma of h: full (default;
                       Schur complement), full-qr (the same by Ceres' sparse
                       QR; slower), conditional (poses held fixed; cheap)
                       or none
  --no-servo           hold the servo angles at their measurements
  --no-extrinsic       hold the camera extrinsic at its nominal value
  --no-dvl             leave out the DVL raycast factors
  --no-align           start from the bundle's model_pose_guess as it is
                       (default: refine it by GICP of the DVL returns, or
                       search for it when the bundle has none)
  --evaluate           compare with the bundle's truth/ and print the figures
  --verbose            print Ceres' per-iteration log
  --quiet              no progress output
  --force              write into an --out folder that holds files HullInspect
                       did not write (they are kept; none is replaced)
The initial model pose (and the prior of eq. 8) is the GICP alignment of the
DVL returns to the mesh (see 'align').

The same input and options write the same files (wall times go to
timing.json): byte for byte with --threads 1, and to far below the survey's
noise with more threads (Ceres sums in thread order). The bundle is
validated first (docs/validation.md); an adjustment whose cost runs away
stops with exit 3, naming the likely input. DIR is checked before any work
(exit 2 when it cannot be written, or holds files HullInspect did not write
and --force is not given); it is replaced as a whole: a run that fails or is
killed leaves the previous folder whole, and results made from the previous
adjustment inside it (a mapping/) go with it (docs/results-format.md).
)";

}  // namespace

int RunAdjust(const CommandArgs& argv) {
  Args a(argv, {"no-servo", "no-extrinsic", "no-dvl", "no-align", "evaluate", "verbose", "quiet", "force"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly(
      {"mesh",           "mesh-scale",         "model",         "sigma0",     "sigma1",  "labels",   "lookup",
       "max-iterations", "function-tolerance", "linear-solver", "covariance", "threads", "no-servo", "no-extrinsic",
       "no-dvl",         "no-align",           "evaluate",      "verbose",    "quiet",   "out",      "force"});
  if (a.positionals().size() != 1) throw UsageError("expected one survey bundle");
  const OutputFolder out{a.Get("out"), a.Has("force")};
  if (out.path.empty()) throw UsageError("--out DIR is required");
  CheckResultsFolder(out);
  AdjustmentOptions o;
  o.model = ParseSurfaceModel(a.Get("model", "max-mixture"));
  o.sigma0 = a.GetDouble("sigma0", o.sigma0);
  o.sigma1 = a.GetDouble("sigma1", o.sigma1);
  o.labels = ParseLabelRule(a.Get("labels", LabelRuleName(o.labels)));
  const std::string lookup = a.Get("lookup", "closest-face");
  if (lookup != "closest-face" && lookup != "nearest-vertex") {
    throw UsageError("--lookup expects closest-face or nearest-vertex");
  }
  o.lookup = lookup == "closest-face" ? SurfaceLookup::kClosestFace : SurfaceLookup::kNearestVertex;
  o.max_iterations = static_cast<int>(a.GetInt("max-iterations", o.max_iterations));
  o.function_tolerance = a.GetDouble("function-tolerance", o.function_tolerance);
  if (a.Has("linear-solver")) {
    const std::string ls = a.Get("linear-solver");
    if (ls == "sparse-schur")
      o.linear_solver = AdjustmentOptions::LinearSolver::kSparseSchur;
    else if (ls == "iterative-schur")
      o.linear_solver = AdjustmentOptions::LinearSolver::kIterativeSchur;
    else
      throw UsageError("--linear-solver expects sparse-schur or iterative-schur");
  }
  o.covariance = ParseCovarianceMethod(a.Get("covariance", "full"));
  o.num_threads = static_cast<int>(a.GetInt("threads", 0));
  o.estimate_servo = !a.Has("no-servo");
  o.estimate_extrinsic = !a.Has("no-extrinsic");
  o.use_dvl = !a.Has("no-dvl");
  o.verbose = a.Has("verbose");
  o.Check();

  const PipelineInputs in = LoadPipelineInputs(a.positionals()[0], a.Get("mesh", ""), a.GetDouble("mesh-scale", 1.0));
  ConsoleProgress progress(a.Has("quiet"));
  Pose x_gM0;
  if (a.Has("no-align")) {
    if (!in.bundle.manifest.model_pose_guess) {
      throw InputError({in.bundle_path + "/survey.json", 0, 0, "model_pose_guess"},
                       "--no-align needs a model_pose_guess in the bundle");
    }
    x_gM0 = Pose::FromVector(*in.bundle.manifest.model_pose_guess);
  } else {
    SubProgress p(progress, 0, 0.1);
    const ModelAlignment al = RunAlignment(in, PipelineOptions(), p);
    x_gM0 = al.x_gM;
    std::printf("alignment: DVL residual RMS %.4f -> %.4f m\n", al.residual_rms_before, al.residual_rms_after);
  }
  SubProgress p(progress, a.Has("no-align") ? 0 : 0.1, 1.0);
  const AdjustmentResult r = RunAdjustmentStep(in, x_gM0, o, p);
  progress.Finish();
  SaveAdjustmentResults(r, out, NewResultsRun("adjust"));
  std::printf("%s: %zu iterations, cost %.6g -> %.6g, %.2f s (solver %.2f s), lambda=1 for %.1f %% of %zu landmarks\n",
              SurfaceModelName(o.model),
              r.iterations.empty() ? 0 : static_cast<std::size_t>(r.iterations.back().iteration), r.initial_cost,
              r.final_cost, r.seconds, r.solver_seconds, 100 * r.FractionOnSurface(), r.landmarks.size());
  std::printf("termination: %s\nwrote %s\n", r.termination.c_str(), out.path.c_str());
  if (a.Has("evaluate") && in.bundle.truth) {
    std::printf("%s", EvaluateAdjustment(in.bundle, in.mesh, r).ToString().c_str());
  }
  return kExitOk;
}

}  // namespace hull::cli
