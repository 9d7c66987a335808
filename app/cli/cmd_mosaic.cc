// hullinspect-cli mosaic: the 3-D photomosaic of a pipeline's remeshed model.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "geometry/mesh_io.h"
#include "mosaic/mosaic_io.h"
#include "results/adjustment_files.h"
#include "results/mosaic_files.h"
#include "simulate/true_scene.h"
#include "survey/survey_import.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli mosaic RESULTS [--out DIR] [options]

The 3-D photomosaic (Ozog et al., Fig. 23): the remeshed model of RESULTS
textured from the survey's camera images with the adjusted poses, servo
angles, camera extrinsic and model pose. Per face the best unoccluded view
(Embree visibility; score cos(incidence)/distance^2, smoothed so that
neighbouring faces keep one view), the strobe, water and vignetting undone
by the rig's photometric model plus a gain per image from the overlaps,
feathered seams, one texture atlas. RESULTS is the folder 'run' wrote
(adjustment/ and mapping/model.ply) or one 'adjust' wrote with 'map' run
into it; the survey bundle (version 2, with images/) is the one
adjustment.json names. When the bundle has truth (truth/scene.ply and
truth/albedo.json) every face is scored against the true albedo.

Writes mosaic.obj, mosaic.mtl, mosaic_atlas.png (the textured model),
mosaic.ply (per-vertex colour), mosaic.json (summary) and mosaic_faces.csv
(per face: view, score, error); see docs/results-format.md.

options:
  --out DIR            output folder (default: RESULTS/mosaic, where 'export'
                       finds it for glTF); replaced as a whole
  --bundle DIR         survey bundle (default: the one adjustment.json names)
  --texel M            atlas texel size (default 0.004)
  --max-range M        farthest view of a face (default 5)
  --max-incidence DEG  most oblique view of a face (default 75)
  --seam-weight W      cost of a seam edge against -ln(score ratio) (default 0.5;
                       0: the best view per face)
  --feather N          one-rings over which views blend at seams (default 2;
                       0: hard seams)
  --normalise MODE     none (raw pixels), model (the photometric model) or
                       gains (model and a gain per image; default)
  --attenuation C      the water's attenuation, 1/m (default 0.3)
  --backscatter B      the water's backscatter, 1/(m sr) (default 0.0015)
  --no-truth           do not score against the bundle's truth
  --threads N          0: all cores (default)
  --quiet              no progress output
  --force              write into an --out folder that holds files HullInspect
                       did not write (they are kept; none is replaced)

RESULTS must hold one run's adjustment and a model mapped from it (their
files unchanged since), and the bundle must be the survey it was adjusted
from.

exit codes: 0 written, 2 bad command line (also: RESULTS does not exist,
--out names a file or a folder of files HullInspect did not write), 3
RESULTS or the bundle unreadable, a mixed RESULTS folder, or a bundle that
is not RESULTS' survey (both named), 130 cancelled.
)";

}  // namespace

int RunMosaic(const CommandArgs& argv) {
  Args a(argv, {"quiet", "help", "no-truth", "force"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out", "bundle", "texel", "max-range", "max-incidence", "seam-weight", "feather", "normalise",
               "attenuation", "backscatter", "no-truth", "threads", "quiet", "force"});
  if (a.positionals().size() != 1) throw UsageError("expected one results folder");
  namespace fs = std::filesystem;
  const std::string results = a.positionals()[0];
  std::error_code ec;
  if (!fs::exists(results, ec)) throw UsageError("RESULTS '" + results + "': no such folder");
  const OutputFolder out{a.Get("out", (fs::path(results) / "mosaic").string()), a.Has("force")};
  CheckResultsFolder(out);

  MosaicOptions o;
  o.texel_size = a.GetDouble("texel", o.texel_size);
  o.max_range = a.GetDouble("max-range", o.max_range);
  o.max_incidence_deg = a.GetDouble("max-incidence", o.max_incidence_deg);
  o.seam_weight = a.GetDouble("seam-weight", o.seam_weight);
  o.feather_rings = static_cast<int>(a.GetInt("feather", o.feather_rings));
  const std::string mode = a.Get("normalise", "gains");
  if (mode == "none") {
    o.normalisation = MosaicNormalisation::kNone;
  } else if (mode == "model") {
    o.normalisation = MosaicNormalisation::kModel;
  } else if (mode == "gains") {
    o.normalisation = MosaicNormalisation::kModelAndGains;
  } else {
    throw UsageError("--normalise expects none, model or gains, got '" + mode + "'");
  }
  o.photometry.attenuation = a.GetDouble("attenuation", o.photometry.attenuation);
  o.photometry.backscatter = a.GetDouble("backscatter", o.photometry.backscatter);
  o.num_threads = static_cast<int>(a.GetInt("threads", 0));
  o.Check();

  const MosaicSources src = LocateMosaicSources(results);
  const AdjustmentResult adjustment = ReadAdjustmentResult(src.adjustment_dir);
  const std::string bundle_path = a.Get("bundle", adjustment.bundle_path);
  if (bundle_path.empty()) throw UsageError("adjustment.json names no survey bundle: give --bundle");
  const SurveyBundle bundle = OpenSurveyBundle(bundle_path);
  CheckBundleOfResults((fs::path(src.adjustment_dir) / "adjustment.json").string(), bundle.directory);
  MeshLoadOptions lo;  // the model as the mapping wrote it
  lo.weld = false;
  lo.orient_outward = false;
  TriangleMesh model = LoadMesh(src.model_path, lo);
  std::unique_ptr<TrueScene> truth;
  if (!a.Has("no-truth") && fs::exists(fs::path(bundle.directory) / "truth" / "albedo.json", ec)) {
    truth = TrueScene::Load(bundle);
  }

  ConsoleProgress progress(a.Has("quiet"));
  MosaicResult r =
      BuildMosaic(MosaicInputFromAdjustment(adjustment, bundle, std::move(model)), o, progress, truth.get());
  progress.Finish();
  r.inputs = {{"adjustment", fs::absolute(src.adjustment_dir).string()},
              {"model", fs::absolute(src.model_path).string()},
              {"bundle", fs::absolute(bundle_path).string()}};
  SaveMosaicResults(r, out, NewResultsRun("mosaic"));

  const MosaicSummary& s = r.summary;
  std::printf("%zu of %zu faces textured (%.2f m^2) from %zu of %zu images; %zu seam edges of %zu\n", s.faces_textured,
              s.faces, s.textured_area, s.views_used, r.views.size(), s.seam_edges, s.interior_edges);
  std::printf("atlas %dx%d at %.4g m per texel (%.0f %% filled); normalisation %s, gains %.3f..%.3f (median %.3f)\n",
              r.atlas.cols, r.atlas.rows, s.texel_size, 100 * s.atlas_fill, MosaicNormalisationName(r.normalisation),
              s.gain_min, s.gain_max, s.gain_median);
  if (s.faces_scored > 0) {
    std::printf(
        "against the true albedo (%zu faces): |error| median %.4f, p95 %.4f; error of face means median %.4f, "
        "p95 %.4f\n",
        s.faces_scored, s.error_median, s.error_p95, s.mean_error_median, s.mean_error_p95);
  }
  std::printf("%.2f s (visibility %.2f, labelling %.2f, gains %.2f, texturing %.2f, scoring %.2f)\nwrote %s\n",
              s.seconds.total, s.seconds.visibility, s.seconds.labelling, s.seconds.gains, s.seconds.texturing,
              s.seconds.scoring, out.path.c_str());
  return kExitOk;
}

}  // namespace hull::cli
