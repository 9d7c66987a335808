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
//                           [--tau M] [--threads N] [--min-features N] [--max-features N]
//                           [--grow-height M]
//                           [--peak-fit | --no-peak-fit]
//                           [--keep DIR [--reuse]] [--trace OBJECT [--trace-above M]]
// --keep DIR keeps both bundles (DIR/given, DIR/images; the front end's
// features.csv and match-graph.csv written into DIR/images); --reuse then
// starts from them (no rendering, no front end) to score other options;
// with DIR/images/features.csv and DIR/images-adjustment deleted it runs the
// front end and the adjustment again on the kept images (--max-features).
// --max-features N sets the front end's SIFT features per image
// (DetectionOptions::max_features; 0: all) for the run from the images.
// --min-features N sets MappingOptions::object_min_features (0: the area
// test alone, the detection before small supported objects were kept);
// --grow-height M the level Algorithm 1's hysteresis grows clusters down
// to (MappingOptions::shape_grow_height; a height >= tau turns it off);
// --peak-fit / --no-peak-fit turn MappingOptions::peak_fit on or off.
// --trace OBJECT prints, for the run from the images, every landmark over
// that true object standing more than --trace-above M (default 0.01 m)
// above the object's true max: its track (keyframe, pixel), each pixel cast
// from the TRUE camera onto the true scene (what it shows), the track's true
// point reprojected into each true camera, the adjusted point's residual
// with the adjusted camera, and how far a 2 px step of the pixel moves the
// hit (a jump: the pixel sits on an occlusion boundary). Before that it
// prints the object's three highest landmarks per keyframe that observed
// them (their Algorithm 1 label, the shape that holds them and the points
// above the hysteresis level within eps on the image plane), the model
// vertices within 6 cm of them (height, distance, fusions), and the model's
// highest vertex in the object's region with the true surface under it and
// the landmarks around it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "adjust/adjust_result.h"
#include "adjust/evaluation.h"
#include "base/progress.h"
#include "mapping/mapping_input.h"
#include "mapping/object_height_check.h"
#include "pipeline/pipeline.h"
#include "results/adjustment_files.h"
#include "results/front_end_files.h"
#include "simulate/image_track_truth.h"
#include "simulate/survey_simulator.h"
#include "simulate/true_scene.h"
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

struct TraceRequest {
  std::string object;  // empty: none
  double above = 0.01;
  // Algorithm 1's parameters and results, for the seeds' clusters.
  double tau = 0.06, eps = 0.10, grow_height = 0.015;
  const std::vector<KeyframeShapes>* shapes = nullptr;
};

// The landmarks over one true object that stand more than `above` over its
// true max, traced to their tracks against the true scene (see --trace).
void TraceObject(const PipelineInputs& in, const MappingInput& input, const ObjectHeightCheck& c,
                 const TrueObject& object, const TriangleMesh& model, const Pose& model_to_true,
                 const std::vector<KeyframeShapes>& shapes, const MappingOptions& mo, const TraceRequest& req) {
  const SurveyBundle& b = in.bundle;
  if (!b.truth || b.directory.empty()) return;
  const std::unique_ptr<TrueScene> scene = TrueScene::Load(b);
  const MeshIndex cad(in.mesh);
  const CameraRig& rig = b.manifest.camera;
  const Pose true_Mg = Pose::FromVector(b.truth->x_gM).Inverse();
  std::unordered_map<std::int64_t, std::size_t> pose_of;
  for (std::size_t i = 0; i < b.truth->poses.size(); ++i) pose_of[b.truth->poses[i].keyframe] = i;
  std::unordered_map<std::int64_t, const TrueLandmark*> truth;
  for (const TrueLandmark& l : b.truth->landmarks) truth[l.landmark] = &l;
  std::unordered_map<std::int64_t, std::vector<const FeatureObservation*>> obs;
  for (const FeatureObservation& f : b.features) obs[f.landmark].push_back(&f);
  std::unordered_map<std::int64_t, const MappingKeyframe*> adjusted_kf;
  for (const MappingKeyframe& k : input.keyframes) adjusted_kf[k.id] = &k;
  const Pose Mg = input.x_gM.Inverse();
  auto what = [&](const RayHit& h) -> std::string {
    if (!h.hit) return "nothing";
    const TrueObject* o = scene->ObjectOfFace(h.face);
    return o ? o->id : std::string("hull");
  };
  std::printf("trace %s (true max %.3f m): landmarks above %.3f m\n", c.id.c_str(), c.true_max, c.true_max + req.above);
  // The landmarks whose true point lies on the object, by true height: how
  // near its top the features reach, and where the adjustment put them.
  {
    std::unordered_map<std::int64_t, double> adjusted_h;
    for (const MappingLandmark& l : input.landmarks) adjusted_h[l.id] = l.deviation;
    std::vector<std::pair<double, std::int64_t>> on;
    for (const TrueLandmark& l : b.truth->landmarks)
      if (l.object == c.id && adjusted_h.count(l.landmark)) on.emplace_back(l.deviation, l.landmark);
    std::sort(on.rbegin(), on.rend());
    std::printf("  %zu landmarks truly on it; the highest by true h (true, adjusted):", on.size());
    for (std::size_t i = 0; i < std::min<std::size_t>(8, on.size()); ++i)
      std::printf(" %.3f/%.3f", on[i].first, adjusted_h[on[i].second]);
    std::printf("\n");
    // Its features above tau (the seeds of Algorithm 1): per keyframe that
    // saw one, the cluster it fell in and its neighbours in DBSCAN's metric.
    for (const auto& [true_h, id] : on) {
      if (!(adjusted_h[id] > req.tau)) continue;
      std::printf("  seed landmark %lld (true h %.3f, adjusted %.3f):\n", static_cast<long long>(id), true_h,
                  adjusted_h[id]);
      for (const KeyframeShapes& ks : *req.shapes) {
        const ShapePoint* seed = nullptr;
        for (const ShapePoint& p : ks.points)
          if (input.landmarks[static_cast<std::size_t>(p.landmark)].id == id) seed = &p;
        if (!seed) continue;
        int above_low = 0, above_tau = 0, clustered = 0;
        for (const ShapePoint& p : ks.points) {
          const Eigen::Vector3d a(seed->p_c.x(), seed->p_c.y(), std::abs(seed->deviation));
          const Eigen::Vector3d q(p.p_c.x(), p.p_c.y(), std::abs(p.deviation));
          if (&p == seed || (a - q).norm() > req.eps) continue;
          above_low += std::abs(p.deviation) > req.grow_height;
          above_tau += std::abs(p.deviation) > req.tau;
          clustered += p.cluster >= 0;
        }
        int in_shape = 0;
        for (const DetectedShape& s : ks.shapes)
          for (const int pi : s.points) in_shape += &ks.points[static_cast<std::size_t>(pi)] == seed;
        std::printf(
            "    kf %5lld: cluster %d%s; within eps: %d above the grow level, %d above tau, %d clustered; %zu "
            "observed\n",
            static_cast<long long>(ks.id), seed->cluster, in_shape ? " (a shape vertex)" : "", above_low, above_tau,
            clustered, ks.points.size());
      }
    }
  }
  // The region's highest landmarks, per keyframe that observed them: their
  // label in Algorithm 1 (cluster, noise, below tau), the shape that holds
  // them and the clustered points around them on the image plane.
  for (std::size_t t = 0; t < std::min<std::size_t>(3, c.landmarks.size()); ++t) {
    const int li = c.landmarks[t];
    std::printf("  top landmark %d (adjusted h %.3f m) per keyframe:\n", li,
                input.landmarks[static_cast<std::size_t>(li)].deviation);
    {
      const Eigen::Vector3d q = input.x_gM.Inverse() * input.landmarks[static_cast<std::size_t>(li)].p_g;
      const std::vector<double>* dev = model.FindScalar("deviation");
      const std::vector<double>* fus = model.FindScalar("fusions");
      std::printf("    model vertices within 0.06 m:");
      for (std::size_t v = 0; dev && fus && v < model.num_vertices(); ++v) {
        const Eigen::Vector3d d = model_to_true * model.vertices[v] - model_to_true * q;
        const double across = (d - d.dot(object.normal) * object.normal).norm();
        if (across <= 0.06) std::printf(" %.3f@%.3f(%g)", (*dev)[v], across, (*fus)[v]);
      }
      std::printf("\n");
    }
    for (const KeyframeShapes& k : shapes) {
      const auto it =
          std::find_if(k.points.begin(), k.points.end(), [&](const ShapePoint& p) { return p.landmark == li; });
      if (it == k.points.end()) continue;
      std::string in_shape = "no shape";
      for (const DetectedShape& s : k.shapes) {
        const auto v = std::find(s.points.begin(), s.points.end(), static_cast<int>(it - k.points.begin()));
        if (v == s.points.end()) continue;
        int corner_of = 0;
        const int local = static_cast<int>(v - s.points.begin());
        for (const Face& f : s.triangles) corner_of += f[0] == local || f[1] == local || f[2] == local;
        double top = 0;
        for (const double d : s.deviation) top = std::max(top, std::abs(d));
        in_shape = "shape of cluster " + std::to_string(s.cluster) + " (" + std::to_string(s.points.size()) +
                   " vertices, " + std::to_string(s.triangles.size()) + " triangles, corner of " +
                   std::to_string(corner_of) + ", top " + std::to_string(top) + ")";
      }
      std::printf("    kf %lld: label %d, px (%.0f, %.0f), depth %.2f, %s; within eps (|d|@distance[label]):",
                  static_cast<long long>(k.id), it->cluster, it->pixel.x(), it->pixel.y(), it->p_c.z(),
                  in_shape.c_str());
      int low = 0;  // below the hysteresis level
      for (const ShapePoint& q : k.points) {
        if (&q == &*it || (q.p_c.head<2>() - it->p_c.head<2>()).norm() > mo.dbscan_eps) continue;
        if (std::abs(q.deviation) <= std::min(mo.tau, mo.shape_grow_height)) {
          ++low;
          continue;
        }
        std::printf(" %.3f@%.3f[%d]", std::abs(q.deviation), (q.p_c.head<2>() - it->p_c.head<2>()).norm(), q.cluster);
      }
      std::printf(" and %d below the level\n", low);
    }
  }
  const double reach = 0.5 * std::hypot(object.size.x(), object.size.y()) + object.radius + 0.15;
  auto lateral = [&](const Eigen::Vector3d& p_true_M) {
    const Eigen::Vector3d d = p_true_M - object.center;
    return (d - d.dot(object.normal) * object.normal).norm();
  };
  // The model's highest vertex in the region, and the landmarks near it.
  if (c.model_max_vertex >= 0) {
    const std::size_t v = static_cast<std::size_t>(c.model_max_vertex);
    const Eigen::Vector3d p = model.vertices[v];
    const Eigen::Vector3d p_true = model_to_true * p;
    const RayHit below = scene->index().Raycast(p_true + 0.5 * object.normal, -object.normal);
    std::printf(
        "  its highest model vertex %zu: h %.4f m, %g fusions, the true surface there %s at h %.4f m, %.3f m "
        "from the centre; landmarks within 0.06 m across the normal (h@distance):",
        v, c.model_max, model.FindScalar("fusions") ? (*model.FindScalar("fusions"))[v] : std::nan(""),
        what(below).c_str(), below.hit ? cad.SignedDistance(below.point) : std::nan(""), lateral(p_true));
    for (std::size_t l = 0; l < input.landmarks.size(); ++l) {
      const Eigen::Vector3d d = model_to_true * (input.x_gM.Inverse() * input.landmarks[l].p_g) - p_true;
      const double across = (d - d.dot(object.normal) * object.normal).norm();
      if (across <= 0.06) std::printf(" %.3f@%.3f", input.landmarks[l].deviation, across);
    }
    std::printf("\n");
  }
  // The model's highest vertices near the object (not only in its region),
  // and the landmarks near them: what the fusion may have moved them with.
  const std::vector<double>* deviation = model.FindScalar("deviation");
  const std::vector<double>* fusions = model.FindScalar("fusions");
  std::vector<std::pair<double, std::size_t>> near_vertices;
  std::vector<int> near_landmarks;
  for (std::size_t v = 0; deviation && v < model.num_vertices(); ++v) {
    if (lateral(model_to_true * model.vertices[v]) <= reach && (*deviation)[v] > c.true_max + req.above)
      near_vertices.emplace_back((*deviation)[v], v);
  }
  std::sort(near_vertices.rbegin(), near_vertices.rend());
  for (std::size_t i = 0; i < std::min<std::size_t>(5, near_vertices.size()); ++i) {
    const std::size_t v = near_vertices[i].second;
    const Eigen::Vector3d p = model_to_true * model.vertices[v];
    std::printf("  model vertex %zu: h %.3f m, %.3f m from the centre across the normal, %.0f fusions\n", v,
                near_vertices[i].first, lateral(p), fusions ? (*fusions)[v] : std::nan(""));
    for (std::size_t l = 0; l < input.landmarks.size(); ++l) {
      const Eigen::Vector3d q = model_to_true * (input.x_gM.Inverse() * input.landmarks[l].p_g);
      if ((q - p).norm() > 0.05 || input.landmarks[l].deviation < c.true_max + req.above) continue;
      if (std::find(near_landmarks.begin(), near_landmarks.end(), static_cast<int>(l)) == near_landmarks.end())
        near_landmarks.push_back(static_cast<int>(l));
      std::printf("    landmark %lld within %.3f m of it: adjusted h %.3f m, %.3f m from the centre\n",
                  static_cast<long long>(input.landmarks[l].id), (q - p).norm(), input.landmarks[l].deviation,
                  lateral(q));
    }
  }
  // The region's landmarks above the limit (highest first), then those
  // next to the highest vertices.
  std::vector<int> listed;
  for (const int li : c.landmarks) {
    if (input.landmarks[static_cast<std::size_t>(li)].deviation <= c.true_max + req.above) break;
    listed.push_back(li);
  }
  for (const int li : near_landmarks)
    if (std::find(listed.begin(), listed.end(), li) == listed.end()) listed.push_back(li);
  for (const int li : listed) {
    const MappingLandmark& l = input.landmarks[static_cast<std::size_t>(li)];
    const auto t = truth.find(l.id);
    const Eigen::Vector3d adjusted_M = model_to_true * (Mg * l.p_g);
    const Eigen::Vector3d true_M = t != truth.end() ? true_Mg * t->second->p : Eigen::Vector3d::Constant(std::nan(""));
    std::printf(
        "  landmark %lld: adjusted h %.3f m; true point on %s, h %.3f m, %.3f m from the adjusted one; %zu views\n",
        static_cast<long long>(l.id), l.deviation,
        t != truth.end() ? (t->second->object.empty() ? "hull" : t->second->object.c_str()) : "?",
        t != truth.end() ? t->second->deviation : std::nan(""), (adjusted_M - true_M).norm(), obs[l.id].size());
    std::vector<Eigen::Vector3d> dirs;
    for (const FeatureObservation* f : obs[l.id]) {
      const auto p = pose_of.find(f->keyframe);
      if (p == pose_of.end()) continue;
      const Pose cam = TrueCameraPoseFromTruth(b, p->second, false);
      const Eigen::Vector3d d = cam.rotation() * rig.top.Unproject(f->top).normalized();
      const RayHit h = scene->index().Raycast(cam.translation(), d);
      // The hit's jump under a 2 px step of the pixel (largest over 8 directions).
      double jump = 0;
      for (int a = 0; a < 8; ++a) {
        const Eigen::Vector2d uv = f->top + 2.0 * Eigen::Vector2d(std::cos(a * M_PI / 4), std::sin(a * M_PI / 4));
        const RayHit g = scene->index().Raycast(cam.translation(), cam.rotation() * rig.top.Unproject(uv).normalized());
        if (g.hit && h.hit) jump = std::max(jump, std::abs(g.range - h.range));
      }
      const Eigen::Vector3d tc = cam.Inverse() * true_M;
      const double true_reprojection = (rig.top.Project(tc) - f->top).norm();
      // Is the true point visible from this camera?
      const Eigen::Vector3d to = true_M - cam.translation();
      const RayHit v = scene->index().Raycast(cam.translation(), to.normalized());
      const bool visible = v.hit && v.range > to.norm() - 0.005;
      double adjusted_residual = std::nan("");
      if (auto k = adjusted_kf.find(f->keyframe); k != adjusted_kf.end())
        adjusted_residual = (rig.top.Project(k->second->x_g_cT.Inverse() * l.p_g) - f->top).norm();
      dirs.push_back(to.normalized());
      std::printf(
          "    kf %5lld px (%7.2f, %7.2f)%s: pixel shows %s at h %.3f m, %.3f m from the true point, depth %.3f m, "
          "jump at 2 px %.3f m; true point reprojects %.2f px off%s; adjusted residual %.2f px\n",
          static_cast<long long>(f->keyframe), f->top.x(), f->top.y(), f->has_bottom ? " +bottom" : "", what(h).c_str(),
          h.hit ? cad.SignedDistance(h.point) : std::nan(""), h.hit ? (h.point - true_M).norm() : std::nan(""), h.range,
          jump, true_reprojection, visible ? "" : " (occluded)", adjusted_residual);
    }
    double angle = 0;
    for (std::size_t a = 0; a < dirs.size(); ++a)
      for (std::size_t e = a + 1; e < dirs.size(); ++e)
        angle = std::max(angle, std::acos(std::clamp(dirs[a].dot(dirs[e]), -1.0, 1.0)));
    std::printf("    largest true triangulation angle %.1f deg\n", angle * 180 / M_PI);
  }
}

// Per true object (mapping/object_height_check.h: the fused model's height
// field over each true footprint, the model moved into the true M by the
// landmarks' fit): found when a detected object has a vertex in its region;
// a detected object in no true object's region is false.
ObjectScore ScoreObjects(const PipelineInputs& in, const PipelineResult& r, const SimulatedSurvey& sim,
                         double min_height, const TraceRequest& trace) {
  const MappingResult& m = *r.mapping;
  const MeshIndex cad(sim.cad);
  const MappingInput input = MappingInputFromAdjustment(r.adjustment, in.bundle);
  const Pose model_to_true = GaugeFitToTruth(in.bundle, r.adjustment);
  const std::vector<ObjectHeightCheck> checks = CheckObjectHeights(
      m.model, m.objects, input, model_to_true, sim.bundle.truth->objects, sim.object_meshes, cad, &m.keyframes);
  if (!trace.object.empty() && in.bundle.features_from_images) {
    TraceRequest req = trace;
    req.tau = r.mapping->options.tau;
    req.eps = r.mapping->options.dbscan_eps;
    req.grow_height = r.mapping->options.shape_grow_height;
    req.shapes = &m.keyframes;
    for (const ObjectHeightCheck& c : checks) {
      if (c.id != trace.object) continue;
      for (const TrueObject& o : sim.bundle.truth->objects)
        if (o.id == c.id) TraceObject(in, input, c, o, m.model, model_to_true, m.keyframes, m.options, req);
    }
  }
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
    std::printf("    false object %s: max %.3f m, area %.4f m^2, %d features, %.2f m from the bow\n", d.id.c_str(),
                d.max_height, d.area, d.num_features, d.distance_from_bow);
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
                  double min_height, const char* label, bool reuse, const TraceRequest& trace, int max_features) {
  std::printf("\n== %s (%s)\n", label, bundle_dir.c_str());
  RunFigures f;
  NullProgress quiet;
  const double t0 = Now();
  FrontEndOptions fe;
  fe.threads = o.adjustment.num_threads;
  if (max_features >= 0) fe.detection.max_features = max_features;
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
  f.objects = ScoreObjects(in, r, sim, min_height, trace);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // figures as they come, also into a file
  std::string preset = "demo", keep;
  bool reuse = false;
  double camera_scale = 0.5, tau = 0.06, min_height = 0.06;
  int seed = 1, threads = 2, min_features = -1, max_features = -1;
  double grow_height = -1;
  TraceRequest trace;
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
    } else if (a == "--max-features") {
      max_features = std::atoi(value().c_str());
    } else if (a == "--keep") {
      keep = value();
    } else if (a == "--grow-height") {
      grow_height = std::atof(value().c_str());
    } else if (a == "--trace") {
      trace.object = value();
    } else if (a == "--trace-above") {
      trace.above = std::atof(value().c_str());
    } else if (a == "--peak-fit") {
      peak_fit = 1;
    } else if (a == "--no-peak-fit") {
      peak_fit = 0;
    } else if (a == "--reuse") {
      reuse = true;
    } else {
      std::fprintf(stderr,
                   "usage: bench_images_end_to_end [--preset demo|mono] [--camera-scale S] [--seed N] [--tau M] "
                   "[--threads N] [--min-features N] [--max-features N] [--grow-height M] "
                   "[--peak-fit | --no-peak-fit] "
                   "[--keep DIR [--reuse]] [--trace OBJECT [--trace-above M]]\n");
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
  if (reuse && fs::exists(fs::path(images) / "survey.json")) {
    // A kept images bundle without features.csv gets the front end again.
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
  const RunFigures a = RunOne(given, o, sim, min_height, "from the simulator's feature tracks", reuse, trace, -1);
  const RunFigures b =
      RunOne(images, o, sim, min_height, "from the images (visual front end)", reuse, trace, max_features);

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
