#include "results/mapping_files.h"

#include <cmath>
#include <filesystem>
#include <numeric>
#include <optional>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

Json Vec3(const Eigen::Vector3d& v) { return Json::ArrayOf(std::vector<double>{v.x(), v.y(), v.z()}); }

Json Count(std::size_t n) { return Json(static_cast<std::int64_t>(n)); }

std::string JoinIds(const std::vector<std::int64_t>& ids) {
  std::string s;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i) s += ' ';
    s += std::to_string(ids[i]);
  }
  return s;
}

Json OptionsJson(const MappingOptions& o) {
  Json j = Json::Object();
  j.Set("tau", o.tau);
  j.Set("shape_grow_height", o.shape_grow_height);
  j.Set("shape_seed_across_views", o.shape_seed_across_views);
  j.Set("alpha", o.alpha);
  j.Set("dbscan_eps", o.dbscan_eps);
  j.Set("dbscan_min_points", o.dbscan_min_points);
  j.Set("fusion_radius", o.fusion_radius);
  j.Set("fusion_keep_peaks", o.fusion_keep_peaks);
  j.Set("fusion_support", o.fusion_support);
  j.Set("fusion_peak_band", o.fusion_peak_band);
  j.Set("fusion_along_normal", o.fusion_along_normal);
  j.Set("peak_fit", o.peak_fit);
  j.Set("refine_edge", o.refine_edge);
  j.Set("refine_threshold", o.refine_threshold);
  j.Set("refine_margin", o.refine_margin);
  j.Set("object_min_height", o.object_min_height);
  j.Set("object_min_area", o.object_min_area);
  j.Set("object_min_features", o.object_min_features);
  j.Set("object_min_views", o.object_min_views);
  j.Set("stations", o.stations);
  j.Set("bottom_angle_deg", o.bottom_angle_deg);
  j.Set("inspection_spacing", o.inspection_spacing);
  j.Set("inspection_range", o.inspection_range);
  return j;
}

void WriteObjects(const MappingResult& r, const std::string& dir) {
  Json list = Json::Array();
  for (const DetectedObject& o : r.objects) {
    Json j = Json::Object();
    j.Set("id", o.id);
    j.Set("centroid", Vec3(o.centroid_m));
    j.Set("normal", Vec3(o.normal_m));
    j.Set("distance_from_bow", o.distance_from_bow);
    j.Set("station", o.station);
    j.Set("side", HullSideName(o.side));
    j.Set("area", o.area);
    j.Set("mean_height", o.mean_height);
    j.Set("max_height", o.max_height);
    j.Set("p95_height", o.p95_height);
    if (std::isfinite(o.max_height_sigma)) j.Set("max_height_sigma", o.max_height_sigma);
    j.Set("features", o.num_features);
    j.Set("views", o.num_views);
    j.Set("keyframes", Json::ArrayOf(o.keyframes));
    j.Set("vertices", Json::ArrayOf(o.vertices));  // the footprint's model.ply vertices (survey comparison)
    list.Push(std::move(j));
  }
  WriteFileAtomic(Path(dir, "objects.csv"), ObjectsCsv(r));
  Json root = Json::Object();
  root.Set("format", "hull-mapping-objects");
  root.Set("version", MappingResult::kFormatVersion);
  root.Set("objects", std::move(list));
  WriteFileAtomic(Path(dir, "objects.json"), root.Dump());
}

void WriteZones(const MappingResult& r, const std::string& dir) {
  Json list = Json::Array();
  for (const ZoneAssessment& z : r.zones) {
    Json j = Json::Object();
    j.Set("station", z.station);
    j.Set("side", HullSideName(z.side));
    j.Set("from_bow", z.from_bow);
    j.Set("to_bow", z.to_bow);
    j.Set("hull_area", z.hull_area);
    j.Set("inspected_area", z.inspected_area);
    j.Set("covered_area", z.covered_area);
    j.Set("cover_percent", z.cover_percent);
    j.Set("objects", z.objects);
    j.Set("mean_height", z.mean_height);
    j.Set("max_height", z.max_height);
    j.Set("rating", FoulingRatingName(z.rating));
    j.Set("note", z.note);
    list.Push(std::move(j));
  }
  WriteFileAtomic(Path(dir, "zones.csv"), ZonesCsv(r));
  Json root = Json::Object();
  root.Set("format", "hull-mapping-zones");
  root.Set("version", MappingResult::kFormatVersion);
  root.Set("rating_scale",
           "IMO MEPC.378(80): 0-1 below 1 % macrofouling cover (slime and microfouling are "
           "invisible to geometry), 2 for 1-15 %, 3 for 16-40 %, 4 for 41-100 %");
  root.Set("zones", std::move(list));
  WriteFileAtomic(Path(dir, "zones.json"), root.Dump());
}

void WriteShapes(const MappingResult& r, const std::string& dir) {
  CsvWriter csv({"keyframe", "shape", "cluster", "vertices", "triangles", "area", "mean_deviation", "max_deviation"});
  for (const KeyframeShapes& k : r.keyframes) {
    for (std::size_t s = 0; s < k.shapes.size(); ++s) {
      const DetectedShape& sh = k.shapes[s];
      double sum = 0, mx = -1e300;
      for (const double d : sh.deviation) {
        sum += d;
        mx = std::max(mx, d);
      }
      csv.Add(k.id).Add(static_cast<int>(s)).Add(sh.cluster).Add(static_cast<int>(sh.points.size()));
      csv.Add(static_cast<int>(sh.triangles.size())).Add(sh.area);
      csv.Add(sh.deviation.empty() ? 0.0 : sum / static_cast<double>(sh.deviation.size()));
      csv.Add(sh.deviation.empty() ? 0.0 : mx);
      csv.EndRow();
    }
  }
  WriteFileAtomic(Path(dir, "shapes.csv"), csv.text());
}

void WriteSummary(const MappingResult& r, const std::string& dir) {
  const MappingSummary& s = r.summary;
  Json root = Json::Object();
  root.Set("format", "hull-mapping");
  root.Set("version", MappingResult::kFormatVersion);
  Json inputs = Json::Object();
  inputs.Set("source", s.source);
  for (const auto& [k, v] : r.inputs) inputs.Set(k, v);
  root.Set("inputs", std::move(inputs));
  root.Set("options", OptionsJson(r.options));
  Json hull = Json::Object();
  hull.Set("forward", Vec3(r.hull.forward()));
  hull.Set("up", Vec3(r.hull.up()));
  hull.Set("port", Vec3(r.hull.port()));
  hull.Set("length", r.hull.length());
  hull.Set("stations", r.hull.stations());
  root.Set("hull", std::move(hull));
  Json sum = Json::Object();
  sum.Set("keyframes", Count(s.keyframes));
  sum.Set("keyframes_with_shapes", Count(s.keyframes_with_shapes));
  sum.Set("points", Count(s.points));
  sum.Set("points_clustered", Count(s.points_clustered));
  sum.Set("shapes", Count(s.shapes));
  sum.Set("shape_triangles", Count(s.shape_triangles));
  sum.Set("model_vertices", Count(s.model_vertices));
  sum.Set("model_faces", Count(s.model_faces));
  sum.Set("vertices_fused", Count(s.vertices_fused));
  sum.Set("peaks_fitted", Count(s.peaks_fitted));
  sum.Set("peaks_placed", Count(s.peaks_placed));
  sum.Set("peak_features", Count(s.peak_features));
  sum.Set("peak_features_raised", Count(s.peak_features_raised));
  sum.Set("fusion_hits", Count(s.fusion_hits));
  sum.Set("region_cells", Count(s.region_cells));
  sum.Set("refined_area", s.refined_area);
  sum.Set("refinement_reused", s.refinement_reused);
  sum.Set("objects", Count(r.objects.size()));
  sum.Set("hull_area", s.hull_area);
  sum.Set("inspected_area", s.inspected_area);
  sum.Set("covered_area", s.covered_area);
  Json t = Json::Object();
  t.Set("shapes", s.seconds.shapes);
  t.Set("region", s.seconds.region);
  t.Set("refinement", s.seconds.refinement);
  t.Set("fusion", s.seconds.fusion);
  t.Set("deviation", s.seconds.deviation);
  t.Set("inspection", s.seconds.inspection);
  t.Set("objects", s.seconds.objects);
  t.Set("total", s.seconds.total);
  sum.Set("seconds", std::move(t));
  root.Set("summary", std::move(sum));
  Json files = Json::Object();
  files.Set("model", "model.ply");
  files.Set("model_obj", "model.obj");
  files.Set("model_stl", "model.stl");
  files.Set("objects", "objects.csv");
  files.Set("objects_json", "objects.json");
  files.Set("zones", "zones.csv");
  files.Set("zones_json", "zones.json");
  files.Set("shapes", "shapes.csv");
  root.Set("files", std::move(files));
  WriteFileAtomic(Path(dir, "mapping.json"), root.Dump());
}

}  // namespace

std::string ObjectsCsv(const MappingResult& r) {
  CsvWriter csv({"id", "x", "y", "z", "nx", "ny", "nz", "distance_from_bow", "station", "side", "area", "mean_height",
                 "max_height", "features", "views", "keyframes", "p95_height", "max_height_sigma"});
  for (const DetectedObject& o : r.objects) {
    csv.Add(o.id);
    for (int k = 0; k < 3; ++k) csv.Add(o.centroid_m[k]);
    for (int k = 0; k < 3; ++k) csv.Add(o.normal_m[k]);
    csv.Add(o.distance_from_bow).Add(o.station).Add(HullSideName(o.side)).Add(o.area).Add(o.mean_height);
    csv.Add(o.max_height).Add(o.num_features).Add(o.num_views).Add(JoinIds(o.keyframes)).Add(o.p95_height);
    csv.AddOptional(std::isfinite(o.max_height_sigma) ? std::optional<double>(o.max_height_sigma) : std::nullopt);
    csv.EndRow();
  }
  return csv.Take();
}

std::string ZonesCsv(const MappingResult& r) {
  CsvWriter csv({"station", "side", "from_bow", "to_bow", "hull_area", "inspected_area", "covered_area",
                 "cover_percent", "objects", "mean_height", "max_height", "rating", "note"});
  for (const ZoneAssessment& z : r.zones) {
    csv.Add(z.station).Add(HullSideName(z.side)).Add(z.from_bow).Add(z.to_bow).Add(z.hull_area);
    csv.Add(z.inspected_area).Add(z.covered_area).Add(z.cover_percent).Add(z.objects).Add(z.mean_height);
    csv.Add(z.max_height).Add(FoulingRatingName(z.rating)).Add(z.note);
    csv.EndRow();
  }
  return csv.Take();
}

void WriteMappingResult(const MappingResult& r, const std::string& dir) {
  fs::create_directories(dir);
  MeshSaveOptions ply;
  ply.binary = true;
  SaveMesh(r.model, Path(dir, "model.ply"), ply);
  SaveMesh(r.model, Path(dir, "model.obj"));
  SaveMesh(r.model, Path(dir, "model.stl"));
  WriteObjects(r, dir);
  WriteZones(r, dir);
  WriteShapes(r, dir);
  WriteSummary(r, dir);
}

void SaveMappingResults(const MappingResult& r, const OutputFolder& out, ResultsRun run) {
  for (const auto& [role, path] : r.inputs) {
    if (role == "bundle") {
      run.AddSurvey(role, path);
    } else if (role == "mesh") {
      run.AddFile(role, path);
    } else if (role == "adjustment") {
      run.AddResults(role, path);
    }
  }
  WriteResultsFolder(out, run, [&](const std::string& tmp) { WriteMappingResult(r, tmp); });
}

void WriteObjectsCsv(const MappingResult& r, const std::string& path) { WriteFileAtomic(path, ObjectsCsv(r)); }

void WriteZonesCsv(const MappingResult& r, const std::string& path) { WriteFileAtomic(path, ZonesCsv(r)); }

}  // namespace hull
