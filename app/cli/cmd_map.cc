// hullinspect-cli map: model-assisted mapping of an adjusted survey.
#include <cstdio>
#include <filesystem>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "geometry/mesh_io.h"
#include "mapping/mapper.h"
#include "results/adjustment_files.h"
#include "results/mapping_files.h"
#include "survey/survey_import.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli map RESULTS [--out DIR] [options]

Model-assisted mapping (Ozog et al., Section 3) of an adjusted survey: shapes
of foreign structure per keyframe (DBSCAN and alpha shapes), fused into a
locally remeshed copy of the CAD model, detected objects, and the fouling
assessment per hull zone with the IMO MEPC.378(80) rating. RESULTS is the
folder 'hullinspect-cli adjust' wrote; its adjustment.json names the survey
bundle and the mesh. Writes the mapping results (docs/results-format.md).

options:
  --out DIR            output folder (default: RESULTS/mapping)
  --tau M              cluster features with |deviation| > M (default 0)
  --grow-height M      hysteresis: clusters grow through features above M
                       and are kept when they hold one above tau (default
                       0.015; M >= tau: off, each feature cut at tau)
  --no-seed-across-views
                       with the hysteresis, keep only clusters that hold a
                       feature above tau in their own keyframe (default: also
                       those holding a feature that another keyframe's such
                       cluster holds; docs/mapping.md)
  --alpha M            alpha-shape radius (default 0.12)
  --eps M              DBSCAN neighbourhood radius (default 0.10)
  --min-points N       DBSCAN core-point count, the point included (default 3)
  --h-min M            objects: minimum height (default 0.03)
  --min-area M2        objects: minimum footprint area (default 0.01) ...
  --min-features N     ... or, smaller, N shaped features above h_min over it
                       (default 3: finds narrow lumps; 0: the area test alone)
  --min-views N        ... held by the shapes of N keyframes (default 2)
  --refine-edge M      edge length of the refined model (default 0.03)
  --fusion-radius M    fuse vertices within M of the camera (default 5)
  --fusion RULE        normal: a vertex rises to the height --support hits
                       along its normal reach (default); peaks: the same
                       along the camera's rays; mean: the paper's eq. 15
                       (the mean of the camera rays' hits)
  --support N          hits that must reach a height (default 2)
  --peak-band M        hits averaged within M below it (default 0.005)
  --peak-fit           estimate each lump's apex beyond its highest feature
                       by a local quadric fit (--fusion normal only; the
                       default; --no-peak-fit: off)
  --stations N         stations along the hull (default 20)
  --bundle DIR         survey bundle (default: the one adjustment.json names)
  --mesh PATH          prior mesh (default: the one adjustment.json names)
  --mesh-scale S       scale applied to --mesh on load (default: the recorded one)
  --threads N          0: all cores (default)
  --quiet              no progress output
  --force              write into an --out folder that holds files HullInspect
                       did not write (they are kept; none is replaced)
See docs/mapping.md for what the parameters do. The output folder is
replaced as a whole (docs/results-format.md). RESULTS must hold one run's
adjustment (its files unchanged since), and --bundle the survey it was
computed from (exit 3 otherwise, naming both).
)";

}  // namespace

int RunMap(const CommandArgs& argv) {
  Args a(argv, {"quiet", "help", "peak-fit", "no-peak-fit", "no-seed-across-views", "force"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out",        "tau",      "grow-height",  "alpha",     "eps",         "min-points",
               "h-min",      "min-area", "min-features", "min-views", "refine-edge", "fusion-radius",
               "fusion",     "support",  "peak-band",    "stations",  "bundle",      "mesh",
               "mesh-scale", "threads",  "quiet",        "peak-fit",  "no-peak-fit", "no-seed-across-views",
               "force"});
  if (a.positionals().size() != 1) throw UsageError("expected one adjustment results folder");
  const std::string results = a.positionals()[0];
  const OutputFolder out{a.Get("out", (std::filesystem::path(results) / "mapping").string()), a.Has("force")};
  CheckResultsFolder(out);
  MappingOptions o;
  o.tau = a.GetDouble("tau", o.tau);
  o.shape_grow_height = a.GetDouble("grow-height", o.shape_grow_height);
  o.shape_seed_across_views = !a.Has("no-seed-across-views");
  o.alpha = a.GetDouble("alpha", o.alpha);
  o.dbscan_eps = a.GetDouble("eps", o.dbscan_eps);
  o.dbscan_min_points = static_cast<int>(a.GetInt("min-points", o.dbscan_min_points));
  o.object_min_height = a.GetDouble("h-min", o.object_min_height);
  o.object_min_area = a.GetDouble("min-area", o.object_min_area);
  o.object_min_features = static_cast<int>(a.GetInt("min-features", o.object_min_features));
  o.object_min_views = static_cast<int>(a.GetInt("min-views", o.object_min_views));
  o.refine_edge = a.GetDouble("refine-edge", o.refine_edge);
  o.fusion_radius = a.GetDouble("fusion-radius", o.fusion_radius);
  const std::string rule = a.Get("fusion", "normal");
  if (rule != "normal" && rule != "peaks" && rule != "mean") {
    throw UsageError("--fusion: expected 'normal', 'peaks' or 'mean', got '" + rule + "'");
  }
  o.fusion_keep_peaks = rule != "mean";
  o.fusion_along_normal = rule == "normal";
  o.fusion_support = static_cast<int>(a.GetInt("support", o.fusion_support));
  o.fusion_peak_band = a.GetDouble("peak-band", o.fusion_peak_band);
  if (a.Has("peak-fit") && a.Has("no-peak-fit")) throw UsageError("--peak-fit and --no-peak-fit contradict each other");
  if (a.Has("peak-fit")) o.peak_fit = true;
  if (a.Has("no-peak-fit")) o.peak_fit = false;
  o.stations = static_cast<int>(a.GetInt("stations", o.stations));
  o.num_threads = static_cast<int>(a.GetInt("threads", 0));
  o.Check();

  const AdjustmentResult adjustment = ReadAdjustmentResult(results);
  const std::string bundle_path = a.Get("bundle", adjustment.bundle_path);
  if (bundle_path.empty()) throw UsageError("adjustment.json names no survey bundle: give --bundle");
  const SurveyBundle bundle = OpenSurveyBundle(bundle_path);
  CheckBundleOfResults((std::filesystem::path(results) / "adjustment.json").string(), bundle.directory);
  const std::string mesh_path = a.Get("mesh", adjustment.mesh_path);
  if (mesh_path.empty()) throw UsageError("adjustment.json names no mesh: give --mesh");
  MeshLoadOptions lo;
  lo.scale = a.GetDouble("mesh-scale", a.Has("mesh") ? 1.0 : adjustment.mesh_scale);
  TriangleMesh cad = LoadMesh(mesh_path, lo);

  ConsoleProgress progress(a.Has("quiet"));
  MappingResult r = RunMapping(MappingInputFromAdjustment(adjustment, bundle), std::move(cad), o, progress);
  progress.Finish();
  namespace fs = std::filesystem;
  r.inputs = {{"adjustment", fs::absolute(results).string()},
              {"bundle", fs::absolute(bundle_path).string()},
              {"mesh", fs::absolute(mesh_path).string()}};
  SaveMappingResults(r, out, NewResultsRun("map"));

  const MappingSummary& s = r.summary;
  std::printf("%zu keyframes: %zu shapes (%zu triangles) from %zu of %zu features with |d| > %.3g m\n", s.keyframes,
              s.shapes, s.shape_triangles, s.points_clustered, s.points, o.tau);
  std::printf("model: %zu vertices, %zu faces (%.2f m^2 refined to %.3g m edges), %zu vertices fused\n",
              s.model_vertices, s.model_faces, s.refined_area, o.refine_edge, s.vertices_fused);
  if (o.object_min_features > 0) {
    std::printf("%zu objects (h > %.3g m over >= %.3g m^2, or held by %d+ features from %d+ keyframes):\n",
                r.objects.size(), o.object_min_height, o.object_min_area, o.object_min_features, o.object_min_views);
  } else {
    std::printf("%zu objects (h > %.3g m over >= %.3g m^2):\n", r.objects.size(), o.object_min_height,
                o.object_min_area);
  }
  for (const auto& obj : r.objects) {
    std::printf(
        "  %-7s %7.2f m from the bow, station %2d %-9s  %.3f m^2, height mean %.3f max %.3f m, %d features, "
        "%d views\n",
        obj.id.c_str(), obj.distance_from_bow, obj.station, HullSideName(obj.side), obj.area, obj.mean_height,
        obj.max_height, obj.num_features, obj.num_views);
  }
  int inspected = 0, fouled = 0;
  for (const auto& z : r.zones) {
    if (z.rating == FoulingRating::kUninspected) continue;
    ++inspected;
    if (z.rating != FoulingRating::kZeroToOne) {
      ++fouled;
      std::printf("  zone station %2d %-9s rating %s: %.1f %% of %.1f m^2 inspected covered\n", z.station,
                  HullSideName(z.side), FoulingRatingName(z.rating), z.cover_percent, z.inspected_area);
    }
  }
  std::printf("zones: %d inspected (%.1f of %.1f m^2), %d with macrofouling, %zu uninspected\n", inspected,
              s.inspected_area, s.hull_area, fouled, r.zones.size() - static_cast<std::size_t>(inspected));
  std::printf("%.2f s (shapes %.2f, refinement %.2f, fusion %.2f, inspection %.2f)\nwrote %s\n", s.seconds.total,
              s.seconds.shapes, s.seconds.refinement, s.seconds.fusion, s.seconds.inspection, out.path.c_str());
  return kExitOk;
}

}  // namespace hull::cli
