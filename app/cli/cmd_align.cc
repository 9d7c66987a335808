// hullinspect-cli align: the initial model pose x_gM from the DVL returns
// (GICP against the mesh; Ozog et al., Section 2.5).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "geometry/mesh_io.h"
#include "registration/model_alignment.h"
#include "results/alignment_file.h"
#include "survey/survey_import.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli align BUNDLE [options]

Aligns the survey's DVL returns (placed by nav.csv's initial poses, with the
depth and IMU measurements folded in, and the instrumented servo angles) to
the CAD mesh by GICP, starting from the bundle's model_pose_guess; without a
guess (or with --no-guess) a coarse search over headings and places on the
hull finds the start. Prints x_gM, the GICP fit and the RMS of the DVL range
residuals (ray-cast range minus measured range) before and after.

A survey of a flat or prismatic stretch (e.g. the bottom of a parallel
midbody) does not fix every direction of x_gM: the alignment keeps the
start's value along the directions the returns do not constrain (see
"constrained directions"), and the coarse search then reports a tie and picks
by convention (heading along the vehicle's, the middle of the tied stretch).

options:
  --mesh PATH        the CAD mesh (default: the bundle's model_hint)
  --mesh-scale S     scale applied to the mesh on load (e.g. 59.4)
  --no-guess         ignore model_pose_guess: run the coarse search
  --out FILE.json    write the result (x_gM, fit, per-beam residuals)
  --quiet            no progress output
)";

std::string PoseText(const Pose& x) {
  const Vector6d v = x.ToVector();
  char buf[200];
  std::snprintf(buf, sizeof(buf), "[%.4f, %.4f, %.4f, %.5f, %.5f, %.5f]  (angles %.3f, %.3f, %.3f deg)", v[0], v[1],
                v[2], v[3], v[4], v[5], v[3] * 180 / M_PI, v[4] * 180 / M_PI, v[5] * 180 / M_PI);
  return buf;
}

}  // namespace

int RunAlign(const CommandArgs& argv) {
  Args a(argv, {"no-guess", "quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"mesh", "mesh-scale", "no-guess", "out", "quiet"});
  if (a.Has("out")) CheckOutputFile(a.Get("out"));
  if (a.positionals().size() != 1) throw UsageError("expected one survey bundle folder");
  const std::string dir = a.positionals()[0];
  const SurveyBundle bundle = OpenSurveyBundle(dir);
  std::string mesh_path = a.Get("mesh", "");
  if (mesh_path.empty()) mesh_path = bundle.ModelHintPath();
  if (mesh_path.empty()) throw UsageError("the bundle has no model_hint: give the mesh with --mesh");
  MeshLoadOptions lo;
  lo.scale = a.GetDouble("mesh-scale", 1.0);
  if (!(lo.scale > 0)) throw UsageError("--mesh-scale must be positive");
  const TriangleMesh mesh = LoadMesh(mesh_path, lo);

  const std::optional<Pose> guess = a.Has("no-guess") ? std::nullopt : ModelPoseGuess(bundle);
  ConsoleProgress progress(a.Has("quiet"));
  const ModelAlignment r = AlignDvlToModel(bundle, mesh, guess, ModelAlignmentOptions{}, progress);
  progress.Finish();

  std::printf("start           %s (%s)\n", PoseText(r.initial_x_gM).c_str(),
              guess ? "model_pose_guess" : "coarse search");
  std::printf("x_gM            %s\n", PoseText(r.x_gM).c_str());
  std::printf("GICP            %s after %d iterations, fitness %.4f m over %zu of %zu returns\n",
              GicpStatusName(r.gicp.status), r.gicp.iterations, r.gicp.fitness, r.gicp.correspondences,
              r.gicp.source_points);
  std::printf("constrained     %d of 6 pose directions (the others keep the start's value)\n",
              r.constrained_directions);
  std::printf("DVL residuals   RMS %.4f m before, %.4f m after (%zu of %zu beams hit the mesh both times)\n",
              r.residual_rms_before, r.residual_rms_after, r.residual_beams, r.dvl_points);
  if (r.coarse.ran) {
    std::printf("coarse search   %zu placements scored, %zu refined, %zu tied", r.coarse.hypotheses, r.coarse.refined,
                r.coarse.tied);
    if (r.coarse.tied > 1) {
      std::printf(" (over %.1f m and %.1f deg: the returns do not fix the placement; picked by convention)",
                  r.coarse.tied_position_spread, r.coarse.tied_heading_spread_deg);
    }
    std::printf("\n");
  }
  if (a.Has("out")) {
    const std::string out = a.Get("out");
    namespace fs = std::filesystem;
    WriteAlignment(r, {fs::absolute(bundle.directory).string(), fs::absolute(mesh_path).string(), lo.scale}, out);
    std::printf("wrote %s\n", out.c_str());
  }
  if (!(r.gicp.status == GicpStatus::kConverged || r.gicp.status == GicpStatus::kMaxIterations)) {
    std::fprintf(stderr, "error: GICP failed (%s)\n", GicpStatusName(r.gicp.status));
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace hull::cli
