// hullinspect-cli compare: change between two surveys of one hull.
#include <cmath>
#include <cstdio>

#include "base/progress.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "results/compare_files.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli compare RESULTS_A RESULTS_B --out DIR [options]

Change between two surveys of the same hull, both mapped against the same
CAD mesh: the per-vertex change in height on survey B's model (B's deviation
minus A's at the same CAD point, significant where |change| > k sigma with
sigma from both results' per-vertex sigmas), and the detected objects
compared at their peaks (each object's highest vertex and other local
maxima: both maps' highest heights near each peak) and classed new,
removed, grown, shrunk or unchanged, one row per pair of objects and kind.
RESULTS_A/B: mapping results folders ('hullinspect-cli map') or pipeline
results folders ('hullinspect-cli run', their mapping/ is used). Writes
DIR/model.ply (scalars change, change_sigma, change_significant),
DIR/objects.csv and DIR/compare.json; DIR is replaced as a whole.

The two adjustments may place the CAD model differently along the surface
(a flat bottom leaves it free there), so B's map is first registered to A's
by the objects' tops (highest vertices) the two have in common (a RANSAC over
pairs of tops; at least 3 needed, else none, and each peak's heights are read
within --match-radius): compare.json's "registration" says how.

options:
  --out DIR            output folder (required)
  --mesh PATH          the CAD mesh (default: the one A's mapping.json names)
  --mesh-scale S       scale applied to --mesh on load (default 1)
  --peak-spacing M     local maxima of one map closer than M are one peak; the
                       registration matches tops within M (default 0.1)
  --peak-reach M       both maps' heights at a peak are their highest within M
                       of it, plus twice the registration's rms (default 0.05)
  --match-radius M     the widest such disc (default 0.3)
  --change M           grown / shrunk where a peak's height changes by M, new /
                       removed where the other map stands lower (default 0.03)
  --k K                significance factor (default 1.96)
  --max-misplacement M the most one top may lie apart between the two maps
                       before registration (default 5)
  --no-register        compare in M as the two results have it
  --quiet              accepted, as by every command (compare prints no progress)
  --force              write into an --out folder that holds files HullInspect
                       did not write (they are kept; none is replaced)

A and B must each hold one run's mapping (their files unchanged since),
mapped against the same CAD mesh, and --mesh must be that mesh, where their
manifests record it (exit 3 otherwise, naming the files).
)";

void CheckMappingFolder(const std::string& results) {
  if (!FindMappingResults(results)) {
    throw UsageError("'" + results + "' holds neither mapping results nor a pipeline's mapping/");
  }
}

}  // namespace

int RunCompare(const CommandArgs& argv) {
  Args a(argv, {"help", "no-register", "force", "quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out", "mesh", "mesh-scale", "peak-spacing", "peak-reach", "match-radius", "change", "k",
               "max-misplacement", "no-register", "force", "quiet"});
  if (a.positionals().size() != 2) throw UsageError("expected two results folders, A and B");
  if (!a.Has("out")) throw UsageError("--out DIR is required");
  const OutputFolder out{a.Get("out"), a.Has("force")};
  CheckResultsFolder(out);
  SurveyCompareOptions o;
  o.peak_spacing = a.GetDouble("peak-spacing", o.peak_spacing);
  o.peak_reach = a.GetDouble("peak-reach", o.peak_reach);
  o.match_radius = a.GetDouble("match-radius", o.match_radius);
  o.change_threshold = a.GetDouble("change", o.change_threshold);
  o.significance_k = a.GetDouble("k", o.significance_k);
  o.max_misplacement = a.GetDouble("max-misplacement", o.max_misplacement);
  o.register_surveys = !a.Has("no-register");
  o.Check();
  CheckMappingFolder(a.positionals()[0]);
  CheckMappingFolder(a.positionals()[1]);
  NullProgress quiet;
  const SurveyComparisonRun run = RunSurveyComparison(a.positionals()[0], a.positionals()[1], a.Get("mesh", ""),
                                                      a.GetDouble("mesh-scale", 1.0), o, quiet);
  SaveComparisonResults(run, out, NewResultsRun("compare"));
  const SurveyComparison& c = run.comparison;
  const SurveyRegistration& r = c.registration;
  if (r.registered) {
    std::printf("B registered to A by %d objects' tops in common (%d without): %.2f deg, %.3f m, rms %.3f m\n",
                r.inliers, r.identity_inliers, r.rotation * 180.0 / M_PI, r.translation, r.rms);
  } else {
    std::printf("B not registered to A (%d objects' tops in common as they stand)\n", r.identity_inliers);
  }
  std::printf("%zu of %zu vertices changed significantly; heights read within %.3f m of each peak\n",
              c.significant_vertices, c.model.num_vertices(), c.reach);
  std::printf("%-10s %-8s %-8s %9s %9s %9s\n", "change", "A", "B", "height A", "height B", "change");
  for (const ObjectChange& x : c.objects) {
    const char* note = x.from_height_field ? "  (from the other's height field)" : "";
    std::printf("%-10s %-8s %-8s %9.3f %9.3f %+9.3f%s\n", ObjectChangeKindName(x.kind),
                x.id_a.empty() ? "-" : x.id_a.c_str(), x.id_b.empty() ? "-" : x.id_b.c_str(), x.height_a, x.height_b,
                x.change, note);
  }
  return kExitOk;
}

}  // namespace hull::cli
