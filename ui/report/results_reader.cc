#include "ui/report/results_reader.h"

#include <cmath>

#include <filesystem>

#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"

namespace hull::report {
namespace fs = std::filesystem;
namespace {

Pose PoseOf(const JsonReader& r, const char* key) {
  const std::vector<double> v = r.Numbers(key, 6);
  return Pose::FromArray(v.data());
}

// alignment.json keeps the alignment's outcome, not its per-beam residuals
// (the adjustment's dvl_residuals.csv has those).
ModelAlignment ReadAlignment(const std::string& path) {
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader r(doc, path);
  if (r.String("format") != "hull-alignment") r.Fail(r.Required("format"), "format", "expected \"hull-alignment\"");
  ModelAlignment a;
  a.x_gM = PoseOf(r, "x_gM");
  a.initial_x_gM = PoseOf(r, "initial_x_gM");
  if (const Json* c = doc.Get("gicp_converged")) a.gicp.converged = c->as_bool();
  a.gicp.fitness = r.NumberOr("gicp_fitness", 0);
  a.constrained_directions = static_cast<int>(r.NumberOr("constrained_directions", 0));
  a.dvl_points = static_cast<std::size_t>(r.NumberOr("dvl_points", 0));
  a.residual_rms_before = r.NumberOr("residual_rms_before", 0);
  a.residual_rms_after = r.NumberOr("residual_rms_after", 0);
  return a;
}

HullSide SideOf(const JsonReader& r, const char* key) {
  const std::string s = r.String(key);
  for (HullSide side : {HullSide::kBottom, HullSide::kPort, HullSide::kStarboard, HullSide::kNone}) {
    if (s == HullSideName(side)) return side;
  }
  r.Fail(r.Required(key), key, "expected bottom, port, starboard or none");
}

FoulingRating RatingOf(const JsonReader& r, const char* key) {
  const std::string s = r.String(key);
  for (FoulingRating x : {FoulingRating::kUninspected, FoulingRating::kZeroToOne, FoulingRating::kLight,
                          FoulingRating::kMedium, FoulingRating::kHeavy}) {
    if (s == FoulingRatingName(x)) return x;
  }
  r.Fail(r.Required(key), key, "expected uninspected, 0-1, 2, 3 or 4");
}

Eigen::Vector3d Vec3(const JsonReader& r, const char* key) {
  const std::vector<double> v = r.Numbers(key, 3);
  return {v[0], v[1], v[2]};
}

const Json& Items(const JsonReader& r, const char* key) {
  const Json& items = r.Required(key);
  if (!items.is_array()) r.Fail(items, key, "expected an array");
  return items;
}

// What the report needs of a folder WriteMappingResult wrote: options, hull
// axes, the fused model with its "deviation" and "fusions", the objects, the
// zones and the summary (Algorithm 1's per-keyframe shapes are not read).
MappingResult ReadMapping(const fs::path& dir, const TriangleMesh& cad, const AdjustmentResult& adjustment) {
  MappingResult m;
  const std::string mpath = (dir / "mapping.json").string();
  const Json mdoc = Json::Parse(ReadFileToString(mpath), mpath);
  const JsonReader root(mdoc, mpath);
  if (root.String("format") != "hull-mapping")
    root.Fail(root.Required("format"), "format", "expected \"hull-mapping\"");
  const JsonReader o = root.Object("options");
  m.options.tau = o.Number("tau");
  // Absent from results written before the hysteresis: each feature was cut at tau.
  m.options.shape_grow_height = o.NumberOr("shape_grow_height", m.options.tau);
  // Absent from results written before the peak fit (before the seeds
  // across views): off.
  auto flag = [&](const char* key, bool& value) {
    value = false;
    if (!o.Has(key)) return;
    const Json& v = o.Required(key);
    if (!v.is_bool()) o.Fail(v, key, "expected true or false");
    value = v.as_bool();
  };
  flag("peak_fit", m.options.peak_fit);
  flag("shape_seed_across_views", m.options.shape_seed_across_views);
  m.options.alpha = o.Number("alpha");
  m.options.dbscan_eps = o.Number("dbscan_eps");
  m.options.dbscan_min_points = static_cast<int>(o.Integer("dbscan_min_points"));
  m.options.fusion_radius = o.NumberOr("fusion_radius", m.options.fusion_radius);
  m.options.refine_edge = o.NumberOr("refine_edge", m.options.refine_edge);
  m.options.refine_threshold = o.NumberOr("refine_threshold", m.options.refine_threshold);
  m.options.refine_margin = o.NumberOr("refine_margin", m.options.refine_margin);
  m.options.object_min_height = o.NumberOr("object_min_height", m.options.object_min_height);
  m.options.object_min_area = o.NumberOr("object_min_area", m.options.object_min_area);
  // Absent from results written before the support test: those used the area test alone.
  m.options.object_min_features = static_cast<int>(o.NumberOr("object_min_features", 0));
  m.options.object_min_views = static_cast<int>(o.NumberOr("object_min_views", m.options.object_min_views));
  m.options.stations = static_cast<int>(o.NumberOr("stations", m.options.stations));
  m.options.bottom_angle_deg = o.NumberOr("bottom_angle_deg", m.options.bottom_angle_deg);
  m.options.inspection_spacing = o.NumberOr("inspection_spacing", m.options.inspection_spacing);
  m.options.inspection_range = o.NumberOr("inspection_range", m.options.inspection_range);
  // The hull frame as mapping made it: its axes, the CAD's extremes as bow and stern.
  const JsonReader h = root.Object("hull");
  m.hull = MakeHullFrame(cad, ModelAxes{Vec3(h, "forward"), Vec3(h, "up")}, Pose::FromVector(adjustment.x_gM),
                         m.options.stations, m.options.bottom_angle_deg);
  if (const auto in = root.OptionalObject("inputs")) {
    for (const auto& [k, v] : in->value().members()) {
      if (!v.is_string()) continue;
      if (k == "source") {
        m.summary.source = v.as_string();
      } else {
        m.inputs.emplace_back(k, v.as_string());
      }
    }
  }
  const JsonReader s = root.Object("summary");
  MappingSummary& sum = m.summary;
  sum.keyframes = static_cast<std::size_t>(s.NumberOr("keyframes", 0));
  sum.keyframes_with_shapes = static_cast<std::size_t>(s.NumberOr("keyframes_with_shapes", 0));
  sum.points = static_cast<std::size_t>(s.NumberOr("points", 0));
  sum.points_clustered = static_cast<std::size_t>(s.NumberOr("points_clustered", 0));
  sum.shapes = static_cast<std::size_t>(s.NumberOr("shapes", 0));
  sum.shape_triangles = static_cast<std::size_t>(s.NumberOr("shape_triangles", 0));
  sum.model_vertices = static_cast<std::size_t>(s.NumberOr("model_vertices", 0));
  sum.model_faces = static_cast<std::size_t>(s.NumberOr("model_faces", 0));
  sum.vertices_fused = static_cast<std::size_t>(s.NumberOr("vertices_fused", 0));
  sum.fusion_hits = static_cast<std::size_t>(s.NumberOr("fusion_hits", 0));
  sum.refined_area = s.NumberOr("refined_area", 0);
  sum.hull_area = s.NumberOr("hull_area", 0);
  sum.inspected_area = s.NumberOr("inspected_area", 0);
  sum.covered_area = s.NumberOr("covered_area", 0);
  if (const auto t = s.OptionalObject("seconds")) sum.seconds.total = t->NumberOr("total", 0);

  MeshLoadOptions lo;  // as written: no welding, no reorientation
  lo.weld = false;
  lo.orient_outward = false;
  m.model = LoadMesh((dir / "model.ply").string(), lo);
  if (!m.model.FindScalar("deviation")) {
    throw InputError({(dir / "model.ply").string(), 0, 0, "deviation"}, "the model has no per-vertex deviation");
  }

  const std::string opath = (dir / "objects.json").string();
  const Json odoc = Json::Parse(ReadFileToString(opath), opath);
  const JsonReader oroot(odoc, opath);
  const Json& objects = Items(oroot, "objects");
  for (std::size_t i = 0; i < objects.items().size(); ++i) {
    const JsonReader r(objects.items()[i], opath, "objects[" + std::to_string(i) + "]");
    DetectedObject d;
    d.id = r.String("id");
    d.centroid_m = Vec3(r, "centroid");
    d.normal_m = Vec3(r, "normal");
    d.distance_from_bow = r.Number("distance_from_bow");
    d.station = static_cast<int>(r.Integer("station"));
    d.side = SideOf(r, "side");
    d.area = r.Number("area");
    d.mean_height = r.Number("mean_height");
    d.max_height = r.Number("max_height");
    d.p95_height = r.NumberOr("p95_height", d.max_height);  // written since version 1's objects gained it
    d.max_height_sigma = r.NumberOr("max_height_sigma", std::nan(""));
    d.num_features = static_cast<int>(r.Integer("features"));
    d.num_views = static_cast<int>(r.Integer("views"));
    for (double k : r.Numbers("keyframes", -1)) d.keyframes.push_back(static_cast<std::int64_t>(k));
    m.objects.push_back(std::move(d));
  }

  const std::string zpath = (dir / "zones.json").string();
  const Json zdoc = Json::Parse(ReadFileToString(zpath), zpath);
  const JsonReader zroot(zdoc, zpath);
  const Json& zones = Items(zroot, "zones");
  for (std::size_t i = 0; i < zones.items().size(); ++i) {
    const JsonReader r(zones.items()[i], zpath, "zones[" + std::to_string(i) + "]");
    ZoneAssessment z;
    z.station = static_cast<int>(r.Integer("station"));
    z.side = SideOf(r, "side");
    z.from_bow = r.Number("from_bow");
    z.to_bow = r.Number("to_bow");
    z.hull_area = r.Number("hull_area");
    z.inspected_area = r.Number("inspected_area");
    z.covered_area = r.Number("covered_area");
    z.cover_percent = r.Number("cover_percent");
    z.objects = static_cast<int>(r.Integer("objects"));
    z.mean_height = r.Number("mean_height");
    z.max_height = r.Number("max_height");
    z.rating = RatingOf(r, "rating");
    z.note = r.OptionalString("note").value_or("");
    m.zones.push_back(std::move(z));
  }
  return m;
}

}  // namespace

ReportInputs ReadReportInputs(const std::string& results_dir) {
  const std::string summary_path = (fs::path(results_dir) / "summary.json").string();
  const Json summary_doc = Json::Parse(ReadFileToString(summary_path), summary_path);
  const JsonReader summary(summary_doc, summary_path);
  if (summary.String("format") != "hull-pipeline") {
    summary.Fail(summary.Required("format"), "format", "expected \"hull-pipeline\"");
  }
  PipelineInputs in =
      LoadPipelineInputs(summary.String("bundle"), summary.String("mesh"), summary.NumberOr("mesh_scale", 1.0));

  auto result = std::make_shared<PipelineResult>();
  result->alignment = ReadAlignment((fs::path(results_dir) / "alignment.json").string());
  result->adjustment = ReadAdjustmentResult((fs::path(results_dir) / "adjustment").string());
  for (SurfaceModel m : {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture}) {
    const fs::path dir = fs::path(results_dir) / ("adjustment-" + std::string(SurfaceModelName(m)));
    if (m != result->adjustment.options.model && fs::is_directory(dir)) {
      result->baselines.push_back(ReadAdjustmentResult(dir.string()));
    }
  }
  if (in.bundle.truth) {
    result->evaluation = EvaluateAdjustment(in.bundle, in.mesh, result->adjustment);
    for (const AdjustmentResult& b : result->baselines) {
      result->baseline_evaluations.push_back(EvaluateAdjustment(in.bundle, in.mesh, b));
    }
  }

  ReportInputs r;
  const fs::path mapping = fs::path(results_dir) / "mapping";
  if (fs::is_regular_file(mapping / "mapping.json")) {
    r.mapping = std::make_shared<const MappingResult>(ReadMapping(mapping, in.mesh, result->adjustment));
  }
  const fs::path mosaic = fs::path(results_dir) / "mosaic" / "mosaic.ply";
  if (fs::is_regular_file(mosaic)) {
    MeshLoadOptions o;
    o.weld = false;  // the colours stay with their vertices
    o.orient_outward = false;
    auto mesh = std::make_shared<TriangleMesh>(LoadMesh(mosaic.string(), o));
    for (const char* c : {"red", "green", "blue"}) {
      if (!mesh->FindScalar(c))
        throw InputError({mosaic.string(), 0, 0, c}, "a photomosaic needs per-vertex " + std::string(c));
    }
    r.mosaic = std::move(mesh);
    r.mosaic_path = fs::absolute(mosaic).string();
  }
  r.bundle_path = in.bundle_path;
  r.mesh_path = in.mesh_path;
  r.results_path = fs::absolute(results_dir).string();
  r.bundle = std::make_shared<const SurveyBundle>(std::move(in.bundle));
  r.cad = std::make_shared<const TriangleMesh>(std::move(in.mesh));
  r.pipeline = std::move(result);
  return r;
}

}  // namespace hull::report
