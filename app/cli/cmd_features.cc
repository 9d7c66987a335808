// hullinspect-cli features: the visual front end, images -> features.csv.
#include <cstdio>
#include <filesystem>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "results/front_end_files.h"
#include "survey/survey_io.h"
#include "vision/front_end.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli features BUNDLE [--out FILE] [options]

The visual front end on a version 2 bundle's images (images/): SIFT with
CLAHE, top-bottom matches under the rig's epipolar constraint, matches
between keyframes guided by the navigation (RANSAC: rigid alignment of the
stereo clouds, or the 5-point essential matrix for mono), loop closures
(keyframes far apart in nav order whose footprints on the hull overlap under
the navigation prior, e.g. adjacent tracks of a lawnmower, matched with a
window and tolerances grown by the nav drift between them), tracks with global
landmark ids. Writes FILE (default BUNDLE/features.csv, the version 1
contract, which 'run' and 'adjust' then use) and match-graph.csv beside it.
Prints per-keyframe feature counts and per-pair inlier ratios.

options:
  --out FILE              where to write features.csv
  --force                 overwrite an existing features.csv
  --max-features N        SIFT features per image (default 2000, 0: all)
  --no-clahe              no contrast normalisation before SIFT
  --clahe-clip C          CLAHE clip limit (default 3)
  --epipolar-tolerance PX stereo: distance to the epipolar line (default 2)
  --ratio R               Lowe's ratio, stereo and temporal (default 0.8)
  --window PX             temporal search radius around the prediction (default 40)
  --neighbours N          match each keyframe with the next N (default 2)
  --ransac-threshold PX   RANSAC inlier threshold (default 2)
  --no-loops              no loop closures (neighbours in nav order only)
  --loop-candidates K     loop partners tried per keyframe (default 3)
  --loop-min-overlap F    predicted footprint overlap of a loop pair (default 0.3)
  --loop-min-inliers N    RANSAC inliers to accept a loop pair (default 20)
  --loop-max-window PX    cap of the drift-grown search window (default 200)
  --min-keyframes N       shortest track kept (default 2)
  --no-track-check        keep mono tracks however far off the DVL plane they stand
  --track-check-max-height M   drop short mono tracks this far in front of the DVL plane (default 0.25)
  --track-check-min-height M   ... or this far behind it (negative, default -0.1)
  --no-refine             keep SIFT's pixels (no sub-pixel alignment of each track's patches)
  --threads N             worker threads (default: all cores)
  --quiet
)";

}  // namespace

int RunFeatures(const CommandArgs& argv) {
  Args a(argv, {"force", "no-clahe", "no-loops", "no-track-check", "no-refine", "quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out",
               "force",
               "max-features",
               "no-clahe",
               "clahe-clip",
               "epipolar-tolerance",
               "ratio",
               "window",
               "neighbours",
               "ransac-threshold",
               "no-loops",
               "loop-candidates",
               "loop-min-overlap",
               "loop-min-inliers",
               "loop-max-window",
               "min-keyframes",
               "no-track-check",
               "track-check-max-height",
               "track-check-min-height",
               "no-refine",
               "threads",
               "quiet"});
  if (a.positionals().size() != 1) throw UsageError("expected one survey bundle");
  const std::string bundle_dir = a.positionals()[0];
  FrontEndOptions o;
  o.detection.max_features = static_cast<int>(a.GetInt("max-features", o.detection.max_features));
  o.detection.clahe = !a.Has("no-clahe");
  o.detection.clahe_clip = a.GetDouble("clahe-clip", o.detection.clahe_clip);
  o.stereo.epipolar_tolerance = a.GetDouble("epipolar-tolerance", o.stereo.epipolar_tolerance);
  o.stereo.ratio = o.temporal.ratio = a.GetDouble("ratio", o.stereo.ratio);
  o.temporal.window = a.GetDouble("window", o.temporal.window);
  o.temporal.neighbours = static_cast<int>(a.GetInt("neighbours", o.temporal.neighbours));
  o.temporal.ransac_threshold = a.GetDouble("ransac-threshold", o.temporal.ransac_threshold);
  o.loops.enabled = !a.Has("no-loops");
  o.loops.candidates = static_cast<int>(a.GetInt("loop-candidates", o.loops.candidates));
  o.loops.min_overlap = a.GetDouble("loop-min-overlap", o.loops.min_overlap);
  o.loops.min_inliers = static_cast<int>(a.GetInt("loop-min-inliers", o.loops.min_inliers));
  o.loops.max_window = a.GetDouble("loop-max-window", o.loops.max_window);
  o.tracks.min_keyframes = static_cast<int>(a.GetInt("min-keyframes", o.tracks.min_keyframes));
  o.tracks.check_dvl_height = !a.Has("no-track-check");
  o.tracks.check_max_height = a.GetDouble("track-check-max-height", o.tracks.check_max_height);
  o.tracks.check_min_height = a.GetDouble("track-check-min-height", o.tracks.check_min_height);
  o.tracks.refine = !a.Has("no-refine");
  o.threads = static_cast<int>(a.GetInt("threads", 0));
  o.Check();
  const std::string out = a.Get("out", (std::filesystem::path(bundle_dir) / "features.csv").string());
  if (std::filesystem::exists(out) && !a.Has("force"))
    throw UsageError(out + " exists; give --out FILE or --force to overwrite it");

  const SurveyBundle bundle = ReadSurveyBundle(bundle_dir);
  ConsoleProgress progress(a.Has("quiet"));
  const FrontEndResult r = RunFrontEnd(bundle, o, progress);
  WriteFrontEndResult(r, bundle.manifest, out);
  progress.Finish();

  std::printf("%-10s %6s %8s %8s %7s %7s\n", "keyframe", "images", "top", "bottom", "stereo", "tracked");
  for (const auto& k : r.keyframes) {
    std::printf("%-10lld %6d %8d %8d %7d %7d\n", static_cast<long long>(k.keyframe),
                static_cast<int>(k.has_top) + static_cast<int>(k.has_bottom), k.top_features, k.bottom_features,
                k.stereo_matches, k.tracked);
  }
  int accepted = 0, sequential = 0;
  double ratio_sum = 0;
  for (const auto& p : r.pairs) {
    if (p.loop) continue;
    ++sequential;
    if (p.accepted) {
      ++accepted;
      ratio_sum += p.InlierRatio();
    }
  }
  std::printf("keyframe pairs: %d matched, %d accepted, mean inlier ratio %.3f\n", sequential, accepted,
              accepted ? ratio_sum / accepted : 0.0);
  for (const auto& p : r.pairs) {
    if (!p.accepted && !p.loop) {
      std::printf("  dropped %lld-%lld (%s): %d putative, %d inliers, %s\n", static_cast<long long>(p.from),
                  static_cast<long long>(p.to), p.stereo ? "rigid" : "essential", p.putative, p.inliers,
                  p.note.c_str());
    }
  }
  if (o.loops.enabled) {
    int loop_inliers = 0;
    for (const auto& p : r.pairs) loop_inliers += p.loop && p.accepted ? p.inliers : 0;
    std::printf("loop closures: overlap predicted for %zu keyframe pairs, %d tried, %d accepted (%d inliers); %.1f s\n",
                r.loop_pairs_considered, r.loop_pairs_tried, r.loop_pairs_accepted, loop_inliers, r.loop_seconds);
  }
  std::printf(
      "%d landmarks, %zu observations; %d merges refused, %d short tracks dropped, %d of %zu mono tracks checked "
      "dropped off the DVL plane; %.1f s\n",
      r.landmarks, r.features.size(), r.refused_merges, r.dropped_tracks, r.tracks_failed_check, r.track_checks.size(),
      r.seconds);
  std::printf(
      "%d duplicate SIFT keypoints, %d tracks repeating another's pixels dropped; %d track members refined to "
      "their reference's patch, %d kept SIFT's pixel\n",
      r.duplicate_keypoints, r.duplicate_tracks, r.refinement.refined, r.refinement.kept);
  std::printf("wrote %s\n", out.c_str());
  return kExitOk;
}

}  // namespace hull::cli
