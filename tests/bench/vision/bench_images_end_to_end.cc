// Issue 10's acceptance from pixels: a simulated survey rendered as camera
// images, the visual front end, then the whole pipeline (alignment,
// max-mixture adjustment, mapping) -- against the same survey run from the
// feature tracks the simulator gives. Prints, for both runs:
//   - the front end's tracks against the true scene (wrong matches,
//     triangulation within 2 cm; simulate/image_track_truth.h),
//   - labels against truth and the landmark RMSE in M (adjust/evaluation.h),
//   - per true object >= 6 cm (mapping/object_height_check.h): found or not
//     at tau, its max height on the fused model; detected objects that lie
//     on no true object (false); the cylinder's and the box's max heights.
// The model is moved into the true M by the landmarks' fit first: a flat
// stretch of bottom leaves the model pose free along the hull, so the map
// may sit centimetres to decimetres from the truth in M with no object wrong.
//
//   bench_images_end_to_end [--preset demo|mono] [--camera-scale S] [--seed N]
//                           [--tau M] [--threads N] [--min-features N] [--grow-height M]
//                           [--peak-fit | --no-peak-fit]
//                           [--keep DIR [--reuse]]
// --keep DIR keeps both bundles (DIR/given, DIR/images; the front end's
// features.csv and match-graph.csv written into DIR/images); --reuse then
// starts from them (no rendering, no front end) to score other options.
// --min-features N sets MappingOptions::object_min_features (0: the area
// test alone, the detection before small supported objects were kept);
// --grow-height M the level Algorithm 1's hysteresis grows clusters down
// to (MappingOptions::shape_grow_height; a height >= tau turns it off);
// --peak-fit / --no-peak-fit turn MappingOptions::peak_fit on or off.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "adjust/evaluation.h"
#include "base/progress.h"
#include "mapping/mapping_input.h"
#include "mapping/object_height_check.h"
#include "pipeline/pipeline.h"
#include "simulate/survey_simulator.h"
#include "support/test_files.h"

namespace {
using namespace hull;
namespace fs = std::filesystem;

double Now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct ObjectScore {
  int required = 0, found = 0, false_objects = 0, within_1cm = 0;
  double cylinder_error = std::nan(""), box_error = std::nan("");  // model max - true max
  double worst_error = 0;                                          // over found objects >= min_height
};

// Per true object (mapping/object_height_check.h: the fused model's height
// field over each true footprint, the model moved into the true M by the
// landmarks' fit): found when a detected object has a vertex in its region;
// a detected object in no true object's region is false.
ObjectScore ScoreObjects(const PipelineInputs& in, const PipelineResult& r, const SimulatedSurvey& sim,
                         double min_height) {
  const MappingResult& m = *r.mapping;
  const MeshIndex cad(sim.cad);
  const std::vector<ObjectHeightCheck> checks = CheckObjectHeights(
      m.model, m.objects, MappingInputFromAdjustment(r.adjustment, in.bundle), GaugeFitToTruth(in.bundle, r.adjustment),
      sim.bundle.truth->objects, sim.object_meshes, cad, &m.keyframes);
  std::printf("%s", ObjectHeightTable(checks, min_height, 0.01).c_str());
  const FoundObjects found = CountFoundObjects(checks, m.objects, min_height);
  std::printf("objects of at least %.2f m: %s", min_height, found.ToString().c_str());
  ObjectScore s;
  s.required = found.required;
  s.found = found.found;
  s.false_objects = static_cast<int>(found.false_objects.size());
  for (const ObjectHeightCheck& c : checks) {
    if (c.height < min_height || c.detected_as.empty()) continue;
    s.within_1cm += std::abs(c.error()) <= 0.01;
    s.worst_error = std::max(s.worst_error, std::abs(c.error()));
    if (c.kind == ObjectKind::kCylinder && std::isnan(s.cylinder_error)) s.cylinder_error = c.error();
    if (c.kind == ObjectKind::kBox && std::isnan(s.box_error)) s.box_error = c.error();
  }
  const std::set<std::string> false_ids(found.false_objects.begin(), found.false_objects.end());
  for (const DetectedObject& d : m.objects) {
    if (!false_ids.count(d.id)) continue;
    std::printf("    false object %s: max %.3f m, area %.4f m^2, %d features\n", d.id.c_str(), d.max_height, d.area,
                d.num_features);
  }
  return s;
}

struct RunFigures {
  double seconds = 0, front_end_seconds = 0;
  std::size_t landmarks = 0;
  AdjustmentEvaluation evaluation;
  ObjectScore objects;
  std::optional<ImageTrackTruth> tracks;
};

RunFigures RunOne(const std::string& bundle_dir, const PipelineOptions& o, const SimulatedSurvey& sim,
                  double min_height, const char* label, bool reuse) {
  std::printf("\n== %s (%s)\n", label, bundle_dir.c_str());
  RunFigures f;
  NullProgress quiet;
  const double t0 = Now();
  FrontEndOptions fe;
  fe.threads = o.adjustment.num_threads;
  const PipelineInputs in = LoadPipelineInputs(bundle_dir, "", 1.0, &quiet, fe);
  if (in.front_end) {
    f.front_end_seconds = in.front_end->seconds;
    WriteFrontEndResult(*in.front_end, in.bundle.manifest, (fs::path(bundle_dir) / "features.csv").string());
  }
  f.tracks = in.image_tracks;
  if (f.tracks) std::printf("%s", f.tracks->ToString().c_str());
  const std::string adjustment = bundle_dir + "-adjustment";
  PipelineResult r;
  if (reuse && fs::exists(adjustment)) {
    std::printf("adjustment reused from %s: mapping only\n", adjustment.c_str());
    r.adjustment = ReadAdjustmentResult(adjustment);
    if (in.bundle.truth) r.evaluation = EvaluateAdjustment(in.bundle, in.mesh, r.adjustment);
    r.mapping = RunMappingStep(in, r.adjustment, o.mapping, quiet);
  } else {
    r = RunPipeline(in, o, quiet);
    WriteAdjustmentResult(r.adjustment, adjustment);
  }
  f.seconds = Now() - t0;
  f.landmarks = r.adjustment.landmarks.size();
  if (!r.evaluation) {
    std::fprintf(stderr, "%s: the bundle has no truth to evaluate against\n", bundle_dir.c_str());
    std::exit(1);
  }
  f.evaluation = *r.evaluation;
  std::printf("%s", f.evaluation.ToString().c_str());
  f.objects = ScoreObjects(in, r, sim, min_height);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // figures as they come, also into a file
  std::string preset = "demo", keep;
  bool reuse = false;
  double camera_scale = 0.5, tau = 0.06, min_height = 0.06;
  int seed = 1, threads = 2, min_features = -1;
  double grow_height = -1;
  int peak_fit = -1;  // -1: MappingOptions' default
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--preset") {
      preset = value();
    } else if (a == "--camera-scale") {
      camera_scale = std::atof(value().c_str());
    } else if (a == "--seed") {
      seed = std::atoi(value().c_str());
    } else if (a == "--tau") {
      tau = std::atof(value().c_str());
    } else if (a == "--threads") {
      threads = std::atoi(value().c_str());
    } else if (a == "--min-features") {
      min_features = std::atoi(value().c_str());
    } else if (a == "--keep") {
      keep = value();
    } else if (a == "--grow-height") {
      grow_height = std::atof(value().c_str());
    } else if (a == "--peak-fit") {
      peak_fit = 1;
    } else if (a == "--no-peak-fit") {
      peak_fit = 0;
    } else if (a == "--reuse") {
      reuse = true;
    } else {
      std::fprintf(
          stderr,
          "usage: bench_images_end_to_end [--preset demo|mono] [--camera-scale S] [--seed N] [--tau M] "
          "[--threads N] [--min-features N] [--grow-height M] [--peak-fit | --no-peak-fit] [--keep DIR [--reuse]]\n");
      return 2;
    }
  }
  const testing::ScratchDir scratch("bench_images_e2e");
  const std::string root = keep.empty() ? scratch.path() : keep;
  fs::create_directories(root);
  const std::string given = (fs::path(root) / "given").string(), images = (fs::path(root) / "images").string();

  if (reuse && keep.empty()) {
    std::fprintf(stderr, "--reuse needs --keep DIR\n");
    return 2;
  }
  SurveySimulationOptions so = SurveyPreset(preset);
  so.seed = static_cast<std::uint64_t>(seed);
  so.camera_scale = camera_scale;
  so.images = true;
  NullProgress quiet;
  double t = Now();
  const SimulatedSurvey sim = SimulateSurvey(so, quiet);  // seconds; the truth's object meshes for the scoring
  if (reuse && fs::exists(fs::path(images) / "features.csv")) {
    std::printf("%s: reusing the bundles in %s\n", preset.c_str(), root.c_str());
  } else {
    WriteSimulatedSurvey(sim, given, false, quiet);
    fs::remove_all(images);
    fs::copy(given, images, fs::copy_options::recursive);
    fs::remove(fs::path(images) / "features.csv");
    std::printf("%s, seed %d, camera scale %.2f (%dx%d): simulated and rendered %d images in %.1f s\n", preset.c_str(),
                seed, camera_scale, sim.bundle.manifest.camera.width, sim.bundle.manifest.camera.height,
                sim.bundle.images ? sim.bundle.images->present() : 0, Now() - t);
  }

  PipelineOptions o;
  o.adjustment.num_threads = threads;
  o.adjustment.covariance = CovarianceMethod::kNone;  // not what is scored here, and slow on ~10^5 landmarks
  o.mapping.tau = tau;
  if (min_features >= 0) o.mapping.object_min_features = min_features;
  if (grow_height >= 0) o.mapping.shape_grow_height = grow_height;
  if (peak_fit >= 0) o.mapping.peak_fit = peak_fit == 1;
  const RunFigures a = RunOne(given, o, sim, min_height, "from the simulator's feature tracks", reuse);
  const RunFigures b = RunOne(images, o, sim, min_height, "from the images (visual front end)", reuse);

  auto row = [](const char* what, const RunFigures& f) {
    std::printf("| %s | %zu | %.2f %% | %.4f m | %.4f m | %d of %d | %d | %d | %+.3f m | %+.3f m | %.3f m | %.0f s |\n",
                what, f.landmarks, 100.0 * f.evaluation.label_agreement, f.evaluation.landmark_rmse,
                f.evaluation.landmark_rmse_hull, f.objects.found, f.objects.required, f.objects.false_objects,
                f.objects.within_1cm, f.objects.cylinder_error, f.objects.box_error, f.objects.worst_error, f.seconds);
  };
  std::printf("\n%s, tau %.2f m, objects >= %.2f m required:\n", preset.c_str(), tau, min_height);
  std::printf(
      "| tracks | landmarks | labels agree | RMSE in M | RMSE hull | objects found | false | max within 1 cm | "
      "cylinder max - true | box max - true | worst found object | wall |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  row("given", a);
  row("from images", b);
  if (b.tracks) {
    std::printf(
        "front end: %.1f s; wrong matches %.2f %% of observations; %.2f %% of tracks triangulate within %.0f cm\n",
        b.front_end_seconds, 100.0 * b.tracks->WrongObservationFraction(),
        100.0 * b.tracks->TriangulatedWithinFraction(), 100.0 * b.tracks->tolerance);
  }
  std::printf("RMSE ratio (images / given): %.2f\n", b.evaluation.landmark_rmse / a.evaluation.landmark_rmse);
  return 0;
}
