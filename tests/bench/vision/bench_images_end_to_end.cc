// Issue 10's acceptance from pixels: a simulated survey rendered as camera
// images, the visual front end, then the whole pipeline (alignment,
// max-mixture adjustment, mapping) -- against the same survey run from the
// feature tracks the simulator gives. Prints, for both runs:
//   - the front end's tracks against the true scene (wrong matches,
//     triangulation within 2 cm; simulate/image_track_truth.h),
//   - labels against truth and the landmark RMSE in M (adjust/evaluation.h),
//   - every true object >= 6 cm found or not at tau, detected objects that
//     match no true object (false), the cylinder's and the box's max heights.
// Objects are matched after registering the detected objects to the true
// ones (mapping/survey_registration.h): a flat stretch of bottom leaves the
// model pose free along the hull, so the map may sit a few cm to dm from the
// truth in M without any object being wrong.
//
//   bench_images_end_to_end [--preset demo|mono] [--camera-scale S] [--seed N]
//                           [--tau M] [--threads N] [--keep DIR [--reuse]]
// --keep DIR keeps both bundles (DIR/given, DIR/images; the front end's
// features.csv and match-graph.csv written into DIR/images); --reuse then
// starts from them (no rendering, no front end) to score other options.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "base/progress.h"
#include "mapping/survey_registration.h"
#include "pipeline/pipeline.h"
#include "simulate/survey_simulator.h"
#include "support/test_files.h"

namespace {
using namespace hull;
namespace fs = std::filesystem;

double Now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct ObjectScore {
  int required = 0, found = 0, false_objects = 0, detected = 0;
  std::vector<std::string> missed;
  double cylinder_error = std::nan(""), box_error = std::nan("");  // max height - true height
  double worst_error = 0;                                          // over found objects >= 6 cm
};

// A true object's extent across the surface (radius, or the box's half diagonal).
double Extent(const TrueObject& o) {
  return o.kind == ObjectKind::kBox ? 0.5 * std::hypot(o.size.x(), o.size.y()) : o.radius;
}

// A true object is found when a detected object's footprint reaches it (one
// of its vertices within the true object's extent of its centre, across the
// surface); its height on the map is the highest fused vertex of detected
// objects there (adjacent lumps may be one detected object). A detected
// object is false when no true object lies within 10 cm of its footprint.
ObjectScore ScoreObjects(const MappingResult& m, const SurveyTruth& truth, double min_height) {
  ObjectScore s;
  std::vector<DetectedObject> true_as_detected;
  for (const TrueObject& o : truth.objects) {
    DetectedObject d;
    d.id = o.id;
    d.centroid_m = o.center;
    d.normal_m = o.normal;
    d.max_height = o.Height();
    true_as_detected.push_back(d);
  }
  SurveyRegistrationOptions ro;
  ro.match_radius = 0.25;
  const SurveyRegistration reg = RegisterSurveys(true_as_detected, m.objects, ro);
  std::printf("  objects registered to the truth: %s, %d inliers, rms %.3f m, %.2f deg, %.3f m\n",
              reg.registered ? "yes" : "no (identity)", reg.inliers, reg.rms, reg.rotation * 180 / M_PI,
              reg.translation);
  const std::vector<double>* height = m.model.FindScalar("deviation");
  if (!height) {
    std::fprintf(stderr, "the remeshed model has no deviation\n");
    std::exit(1);
  }
  // Distance across the surface from a true object's centre.
  auto across = [](const TrueObject& o, const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - o.center;
    return (d - d.dot(o.normal) * o.normal).norm();
  };
  s.detected = static_cast<int>(m.objects.size());
  std::vector<char> near_truth(m.objects.size(), 0);
  for (const TrueObject& o : truth.objects) {
    std::string found_as;
    double max_height = -1;
    for (std::size_t i = 0; i < m.objects.size(); ++i) {
      bool reaches = false;
      for (const int v : m.objects[i].vertices) {
        const Eigen::Vector3d p = reg.a_from_b * m.model.vertices[static_cast<std::size_t>(v)];
        const double r = across(o, p);
        if (r <= Extent(o) + 0.10) near_truth[i] = 1;
        if (r > Extent(o)) continue;
        reaches = true;
        max_height = std::max(max_height, (*height)[static_cast<std::size_t>(v)]);
      }
      if (reaches) found_as += (found_as.empty() ? "" : "+") + m.objects[i].id;
    }
    const bool found = !found_as.empty();
    const bool required = o.Height() >= min_height;
    const double error = found ? max_height - o.Height() : std::nan("");
    std::printf("    %-9s %-8s true %.3f m  %s", o.id.c_str(), ObjectKindName(o.kind), o.Height(),
                found ? ("found in " + found_as).c_str() : "not found");
    if (found) std::printf(", max %.3f m (%+.3f)", max_height, error);
    std::printf("%s\n", required ? "" : "  (below the required height)");
    if (!required) continue;
    ++s.required;
    if (!found) {
      s.missed.push_back(o.id);
      continue;
    }
    ++s.found;
    s.worst_error = std::max(s.worst_error, std::abs(error));
    if (o.kind == ObjectKind::kCylinder && std::isnan(s.cylinder_error)) s.cylinder_error = error;
    if (o.kind == ObjectKind::kBox && std::isnan(s.box_error)) s.box_error = error;
  }
  for (std::size_t i = 0; i < m.objects.size(); ++i) {
    if (near_truth[i]) continue;
    ++s.false_objects;
    std::printf("    false object %s: max %.3f m, area %.4f m^2, %d features\n", m.objects[i].id.c_str(),
                m.objects[i].max_height, m.objects[i].area, m.objects[i].num_features);
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

RunFigures RunOne(const std::string& bundle_dir, const PipelineOptions& o, double min_height, const char* label) {
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
  const PipelineResult r = RunPipeline(in, o, quiet);
  f.seconds = Now() - t0;
  f.landmarks = r.adjustment.landmarks.size();
  if (!r.evaluation) {
    std::fprintf(stderr, "%s: the bundle has no truth to evaluate against\n", bundle_dir.c_str());
    std::exit(1);
  }
  f.evaluation = *r.evaluation;
  std::printf("%s", f.evaluation.ToString().c_str());
  f.objects = ScoreObjects(*r.mapping, *in.bundle.truth, min_height);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // figures as they come, also into a file
  std::string preset = "demo", keep;
  bool reuse = false;
  double camera_scale = 0.5, tau = 0.06, min_height = 0.06;
  int seed = 1, threads = 2;
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
    } else if (a == "--keep") {
      keep = value();
    } else if (a == "--reuse") {
      reuse = true;
    } else {
      std::fprintf(stderr,
                   "usage: bench_images_end_to_end [--preset demo|mono] [--camera-scale S] [--seed N] [--tau M] "
                   "[--threads N] [--keep DIR [--reuse]]\n");
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
  if (reuse && fs::exists(fs::path(images) / "features.csv")) {
    std::printf("%s: reusing the bundles in %s\n", preset.c_str(), root.c_str());
  } else {
    SurveySimulationOptions so = SurveyPreset(preset);
    so.seed = static_cast<std::uint64_t>(seed);
    so.camera_scale = camera_scale;
    so.images = true;
    NullProgress quiet;
    const double t = Now();
    const SimulatedSurvey s = SimulateSurvey(so, quiet);
    WriteSimulatedSurvey(s, given, false, quiet);
    const double render = Now() - t;
    fs::remove_all(images);
    fs::copy(given, images, fs::copy_options::recursive);
    fs::remove(fs::path(images) / "features.csv");
    std::printf("%s, seed %d, camera scale %.2f (%dx%d): simulated and rendered %d images in %.1f s\n", preset.c_str(),
                seed, camera_scale, s.bundle.manifest.camera.width, s.bundle.manifest.camera.height,
                s.bundle.images ? s.bundle.images->present() : 0, render);
  }

  PipelineOptions o;
  o.adjustment.num_threads = threads;
  o.adjustment.covariance = CovarianceMethod::kNone;  // not what is scored here, and slow on ~10^5 landmarks
  o.mapping.tau = tau;
  const RunFigures a = RunOne(given, o, min_height, "from the simulator's feature tracks");
  const RunFigures b = RunOne(images, o, min_height, "from the images (visual front end)");

  auto row = [](const char* what, const RunFigures& f) {
    std::printf("| %s | %zu | %.2f %% | %.4f m | %.4f m | %d of %d | %d | %+.3f m | %+.3f m | %.3f m | %.0f s |\n",
                what, f.landmarks, 100.0 * f.evaluation.label_agreement, f.evaluation.landmark_rmse,
                f.evaluation.landmark_rmse_hull, f.objects.found, f.objects.required, f.objects.false_objects,
                f.objects.cylinder_error, f.objects.box_error, f.objects.worst_error, f.seconds);
  };
  std::printf("\n%s, tau %.2f m, objects >= %.2f m required:\n", preset.c_str(), tau, min_height);
  std::printf(
      "| tracks | landmarks | labels agree | RMSE in M | RMSE hull | objects found | false | cylinder max - true | "
      "box max - true | worst found object | wall |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
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
