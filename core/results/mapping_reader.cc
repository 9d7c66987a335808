// Reading a mapping results folder (results/mapping_files.h): the whole of
// it for the report and the GUI, or the model and objects for the survey
// comparison.
#include <cmath>
#include <filesystem>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"
#include "results/mapping_files.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

Eigen::Vector3d Vec3(const JsonReader& r, const char* key) {
  const std::vector<double> v = r.Numbers(key, 3);
  return {v[0], v[1], v[2]};
}

const Json& Items(const JsonReader& r, const char* key) {
  const Json& items = r.Required(key);
  if (!items.is_array()) r.Fail(items, key, "expected an array");
  return items;
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

// The model as written: no welding, no reorientation; it must carry "deviation".
TriangleMesh ReadModel(const std::string& dir) {
  MeshLoadOptions lo;
  lo.weld = false;
  lo.orient_outward = false;
  const std::string path = Path(dir, "model.ply");
  TriangleMesh model = LoadMesh(path, lo);
  if (!model.FindScalar("deviation"))
    throw InputError({path, 0, 0, "deviation"}, "the model has no per-vertex deviation");
  return model;
}

// The footprint's vertices in model.ply (older results have none).
void ReadFootprint(const JsonReader& r, std::size_t model_vertices, DetectedObject& o) {
  const auto vs = r.OptionalNumbers("vertices", -1);
  if (!vs) return;
  for (const double v : *vs) {
    if (!(v >= 0 && v < static_cast<double>(model_vertices) && v == std::floor(v))) {
      r.Fail(r.Required("vertices"), "vertices",
             "holds " + FormatDouble(v) + ", not a vertex index of model.ply (" + std::to_string(model_vertices) +
                 " vertices)");
    }
    o.vertices.push_back(static_cast<int>(v));
  }
}

// objects.json. complete: every field the writer writes is required (the
// report); otherwise only id, centroid and max_height (the comparison reads
// results written before the other fields existed).
std::vector<DetectedObject> ReadObjectsJson(const std::string& dir, std::size_t model_vertices, bool complete) {
  const std::string path = Path(dir, "objects.json");
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader root(doc, path);
  const Json& items = Items(root, "objects");
  std::vector<DetectedObject> objects;
  for (std::size_t i = 0; i < items.items().size(); ++i) {
    const JsonReader r(items.items()[i], path, "objects[" + std::to_string(i) + "]");
    DetectedObject d;
    d.id = r.String("id");
    d.centroid_m = Vec3(r, "centroid");
    d.max_height = r.Number("max_height");
    if (complete || r.Has("normal")) d.normal_m = Vec3(r, "normal");
    if (complete || r.Has("area")) d.area = r.Number("area");
    if (complete) {
      d.distance_from_bow = r.Number("distance_from_bow");
      d.station = static_cast<int>(r.Integer("station"));
      d.side = SideOf(r, "side");
      d.mean_height = r.Number("mean_height");
      d.p95_height = r.NumberOr("p95_height", d.max_height);  // written since version 1's objects gained it
      d.max_height_sigma = r.NumberOr("max_height_sigma", std::nan(""));
      d.num_features = static_cast<int>(r.Integer("features"));
      d.num_views = static_cast<int>(r.Integer("views"));
      for (double k : r.Numbers("keyframes", -1)) d.keyframes.push_back(static_cast<std::int64_t>(k));
    }
    ReadFootprint(r, model_vertices, d);
    objects.push_back(std::move(d));
  }
  return objects;
}

std::vector<ZoneAssessment> ReadZonesJson(const std::string& dir) {
  const std::string path = Path(dir, "zones.json");
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader root(doc, path);
  const Json& zones = Items(root, "zones");
  std::vector<ZoneAssessment> out;
  for (std::size_t i = 0; i < zones.items().size(); ++i) {
    const JsonReader r(zones.items()[i], path, "zones[" + std::to_string(i) + "]");
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
    out.push_back(std::move(z));
  }
  return out;
}

// mapping.json's options; fields absent from older results read as they were then.
void ReadOptions(const JsonReader& o, MappingOptions& m) {
  m.tau = o.Number("tau");
  // Absent from results written before the hysteresis: each feature was cut at tau.
  m.shape_grow_height = o.NumberOr("shape_grow_height", m.tau);
  // Absent from results written before the peak fit (before the seeds across views): off.
  auto flag = [&](const char* key, bool& value) {
    value = false;
    if (!o.Has(key)) return;
    const Json& v = o.Required(key);
    if (!v.is_bool()) o.Fail(v, key, "expected true or false");
    value = v.as_bool();
  };
  flag("peak_fit", m.peak_fit);
  flag("shape_seed_across_views", m.shape_seed_across_views);
  m.alpha = o.Number("alpha");
  m.dbscan_eps = o.Number("dbscan_eps");
  m.dbscan_min_points = static_cast<int>(o.Integer("dbscan_min_points"));
  m.fusion_radius = o.NumberOr("fusion_radius", m.fusion_radius);
  m.refine_edge = o.NumberOr("refine_edge", m.refine_edge);
  m.refine_threshold = o.NumberOr("refine_threshold", m.refine_threshold);
  m.refine_margin = o.NumberOr("refine_margin", m.refine_margin);
  m.object_min_height = o.NumberOr("object_min_height", m.object_min_height);
  m.object_min_area = o.NumberOr("object_min_area", m.object_min_area);
  // Absent from results written before the support test: those used the area test alone.
  m.object_min_features = static_cast<int>(o.NumberOr("object_min_features", 0));
  m.object_min_views = static_cast<int>(o.NumberOr("object_min_views", m.object_min_views));
  m.stations = static_cast<int>(o.NumberOr("stations", m.stations));
  m.bottom_angle_deg = o.NumberOr("bottom_angle_deg", m.bottom_angle_deg);
  m.inspection_spacing = o.NumberOr("inspection_spacing", m.inspection_spacing);
  m.inspection_range = o.NumberOr("inspection_range", m.inspection_range);
}

void ReadSummary(const JsonReader& s, MappingSummary& sum) {
  auto count = [&](const char* key) { return static_cast<std::size_t>(s.NumberOr(key, 0)); };
  sum.keyframes = count("keyframes");
  sum.keyframes_with_shapes = count("keyframes_with_shapes");
  sum.points = count("points");
  sum.points_clustered = count("points_clustered");
  sum.shapes = count("shapes");
  sum.shape_triangles = count("shape_triangles");
  sum.model_vertices = count("model_vertices");
  sum.model_faces = count("model_faces");
  sum.vertices_fused = count("vertices_fused");
  sum.fusion_hits = count("fusion_hits");
  sum.refined_area = s.NumberOr("refined_area", 0);
  sum.hull_area = s.NumberOr("hull_area", 0);
  sum.inspected_area = s.NumberOr("inspected_area", 0);
  sum.covered_area = s.NumberOr("covered_area", 0);
  if (const auto t = s.OptionalObject("seconds")) sum.seconds.total = t->NumberOr("total", 0);
}

// mapping.json: options, hull axes, inputs and summary.
void ReadMappingJson(const std::string& dir, const TriangleMesh& cad, const Pose& x_gM, MappingResult& m) {
  const std::string path = Path(dir, "mapping.json");
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader root(doc, path);
  if (root.String("format") != "hull-mapping")
    root.Fail(root.Required("format"), "format", "expected \"hull-mapping\"");
  ReadOptions(root.Object("options"), m.options);
  // The hull frame as mapping made it: its axes, the CAD's extremes as bow and stern.
  const JsonReader h = root.Object("hull");
  m.hull = MakeHullFrame(cad, ModelAxes{Vec3(h, "forward"), Vec3(h, "up")}, x_gM, m.options.stations,
                         m.options.bottom_angle_deg);
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
  ReadSummary(root.Object("summary"), m.summary);
}

}  // namespace

MappingResult ReadMappingResult(const std::string& dir, const TriangleMesh& cad, const Pose& x_gM) {
  CheckResultsFiles(
      {Path(dir, "mapping.json"), Path(dir, "model.ply"), Path(dir, "objects.json"), Path(dir, "zones.json")},
      "the mapping in " + dir);
  MappingResult m;
  ReadMappingJson(dir, cad, x_gM, m);
  m.model = ReadModel(dir);
  m.objects = ReadObjectsJson(dir, m.model.num_vertices(), true);
  m.zones = ReadZonesJson(dir);
  return m;
}

std::optional<std::string> FindMappingResults(const std::string& results) {
  if (fs::exists(fs::path(results) / "model.ply")) return results;
  if (fs::exists(fs::path(results) / "mapping" / "model.ply")) return (fs::path(results) / "mapping").string();
  return std::nullopt;
}

MappingResultsOnDisk ReadMappingResultsForCompare(const std::string& dir) {
  MappingResultsOnDisk out;
  out.manifest = CheckResultsFiles({Path(dir, "model.ply"), Path(dir, "objects.json"), Path(dir, "mapping.json")},
                                   "the mapping in " + dir);
  out.model = ReadModel(dir);
  out.objects = ReadObjectsJson(dir, out.model.num_vertices(), false);
  const std::string jpath = Path(dir, "mapping.json");
  if (fs::exists(jpath)) {
    const Json jdoc = Json::Parse(ReadFileToString(jpath), jpath);
    const JsonReader j(jdoc, jpath);
    if (const auto in = j.OptionalObject("inputs")) out.mesh_path = in->OptionalString("mesh").value_or("");
  }
  return out;
}

}  // namespace hull
