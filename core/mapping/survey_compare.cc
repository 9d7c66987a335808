#include "mapping/survey_compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "base/atomic_directory.h"
#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_index.h"
#include "geometry/mesh_io.h"
#include "geometry/point_index.h"

namespace hull {
namespace {

// Matched objects whose footprints differ by more than this factor are
// compared over the smaller footprint (CompareSurveys).
constexpr double kMergedAreaRatio = 1.5;

namespace fs = std::filesystem;

const std::vector<double>& Deviation(const TriangleMesh& m, const char* which) {
  const std::vector<double>* d = m.FindScalar("deviation");
  if (!d || d->size() != m.num_vertices()) {
    throw std::invalid_argument(std::string("CompareSurveys: model ") + which + " has no per-vertex deviation");
  }
  return *d;
}

double SigmaAt(const std::vector<double>* sigma, std::size_t i) {
  return sigma && i < sigma->size() ? (*sigma)[i] : std::numeric_limits<double>::quiet_NaN();
}

Eigen::Vector3d Vec3(const JsonReader& r, const char* key) {
  const std::vector<double> v = r.Numbers(key, 3);
  return {v[0], v[1], v[2]};
}

}  // namespace

void SurveyCompareOptions::Check() const {
  if (!(std::isfinite(match_radius) && match_radius > 0)) throw OptionError("match_radius", "must be positive (m)");
  if (!(std::isfinite(change_threshold) && change_threshold > 0)) {
    throw OptionError("change_threshold", "must be positive (m)");
  }
  if (!(std::isfinite(significance_k) && significance_k > 0)) throw OptionError("significance_k", "must be positive");
  if (!(std::isfinite(max_misplacement) && max_misplacement > 0)) {
    throw OptionError("max_misplacement", "must be positive (m)");
  }
}

const char* ObjectChangeKindName(ObjectChangeKind k) {
  switch (k) {
    case ObjectChangeKind::kNew:
      return "new";
    case ObjectChangeKind::kRemoved:
      return "removed";
    case ObjectChangeKind::kGrown:
      return "grown";
    case ObjectChangeKind::kShrunk:
      return "shrunk";
    case ObjectChangeKind::kUnchanged:
      return "unchanged";
  }
  return "?";
}

SurveyComparison CompareSurveys(const TriangleMesh& cad, const TriangleMesh& model_a,
                                const std::vector<DetectedObject>& objects_a, const TriangleMesh& model_b,
                                const std::vector<DetectedObject>& objects_b, const SurveyCompareOptions& o) {
  NullProgress progress;
  return CompareSurveys(cad, model_a, objects_a, model_b, objects_b, o, progress);
}

SurveyComparison CompareSurveys(const TriangleMesh& cad, const TriangleMesh& model_a,
                                const std::vector<DetectedObject>& objects_a, const TriangleMesh& model_b,
                                const std::vector<DetectedObject>& objects_b, const SurveyCompareOptions& o,
                                Progress& progress) {
  o.Check();
  const std::vector<double>& dev_a = Deviation(model_a, "A");
  const std::vector<double>& dev_b = Deviation(model_b, "B");
  const std::vector<double>* sigma_a = model_a.FindScalar("sigma");
  const std::vector<double>* sigma_b = model_b.FindScalar("sigma");
  TriangleMesh cad_copy = cad;
  cad_copy.ComputeNormals();
  const MeshIndex index(cad_copy);

  // A's height field, keyed by where each vertex stands on the CAD.
  std::vector<Eigen::Vector3d> feet_a(model_a.num_vertices());
  constexpr std::size_t kChunk = 4096;
  const double total = static_cast<double>(model_a.num_vertices() + model_b.num_vertices()) + 1.0;
  progress.Update(0.0, "placing survey A's model on the CAD");
  for (std::size_t i = 0; i < feet_a.size(); ++i) {
    if (i % kChunk == 0) {
      progress.ThrowIfCancelled();
      progress.Update(static_cast<double>(i) / total, "placing survey A's model on the CAD");
    }
    feet_a[i] = index.Closest(model_a.vertices[i]).point;
  }
  const PointIndex a_index(feet_a);

  SurveyComparison out;
  if (o.register_surveys) {
    SurveyRegistrationOptions ro;
    ro.match_radius = o.match_radius;
    ro.max_offset = o.max_misplacement;
    out.registration = RegisterSurveys(objects_a, objects_b, ro);
  }
  const Pose& x_ab = out.registration.a_from_b;  // B's map placed on A's
  out.model = model_b;
  const std::size_t nb = model_b.num_vertices();
  std::vector<double> change(nb), sigma(nb), significant(nb, 0.0);
  std::vector<Eigen::Vector3d> feet_b(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    if (i % kChunk == 0) {
      progress.ThrowIfCancelled();
      progress.Update(static_cast<double>(feet_a.size() + i) / total, "measuring the change on survey B's model");
    }
    const Eigen::Vector3d foot = index.Closest(x_ab * model_b.vertices[i]).point;
    feet_b[i] = foot;
    const auto nearest = a_index.NearestOne(foot);
    const std::size_t j = static_cast<std::size_t>(std::max(0, nearest.first));
    change[i] = dev_b[i] - dev_a[j];
    const double sa = SigmaAt(sigma_a, j), sb = SigmaAt(sigma_b, i);
    sigma[i] = std::sqrt(sa * sa + sb * sb);
    if (std::isfinite(sigma[i]) && std::abs(change[i]) > o.significance_k * sigma[i]) {
      significant[i] = 1;
      ++out.significant_vertices;
    }
  }
  out.model.SetScalar("change", change);
  out.model.SetScalar("change_sigma", sigma);
  out.model.SetScalar("change_significant", significant);
  const PointIndex b_index(feet_b);
  // The highest height of a model over an object's footprint (the disc of
  // its area about p on A's placement, at most match_radius; a vertex no
  // shape was fused into stands at its CAD height, 0); where the model has
  // no vertex that close (a coarse stretch nothing was fused into), its
  // nearest vertex's. For an object only one map detected, the disc is
  // widened by twice the registration's centroid residual: that is how far
  // the other map's view of the same lump may stand (a grown lump that only
  // B detected, small, otherwise read the flat hull beside A's peak and came
  // out "new").
  const double misplacement = 2 * out.registration.rms;
  auto height_near = [&](const PointIndex& at, const std::vector<double>& dev, const Eigen::Vector3d& p, double area,
                         bool unmatched) {
    const double r =
        std::clamp(std::sqrt(std::max(area, 0.0) / M_PI) + (unmatched ? misplacement : 0.0), 0.05, o.match_radius);
    double h = -std::numeric_limits<double>::infinity();
    for (const auto& hit : at.Within(p, r)) h = std::max(h, dev[static_cast<std::size_t>(hit.first)]);
    if (std::isfinite(h)) return h;
    const int nearest = at.NearestOne(p).first;
    return nearest >= 0 ? dev[static_cast<std::size_t>(nearest)] : 0.0;
  };
  auto classify = [&](double delta) {
    return delta >= o.change_threshold    ? ObjectChangeKind::kGrown
           : delta <= -o.change_threshold ? ObjectChangeKind::kShrunk
                                          : ObjectChangeKind::kUnchanged;
  };

  // Objects: closest pairs first, within match_radius.
  struct Pair {
    double d;
    std::size_t a, b;
  };
  std::vector<Pair> pairs;
  for (std::size_t a = 0; a < objects_a.size(); ++a) {
    for (std::size_t b = 0; b < objects_b.size(); ++b) {
      const double d = (objects_a[a].centroid_m - x_ab * objects_b[b].centroid_m).norm();
      if (d <= o.match_radius) pairs.push_back({d, a, b});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
    if (x.d != y.d) return x.d < y.d;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  std::vector<int> match_of_b(objects_b.size(), -1);
  std::vector<char> a_used(objects_a.size(), 0);
  for (const Pair& p : pairs) {
    if (a_used[p.a] || match_of_b[p.b] >= 0) continue;
    a_used[p.a] = 1;
    match_of_b[p.b] = static_cast<int>(p.a);
  }
  std::vector<ObjectChange> added;
  for (std::size_t b = 0; b < objects_b.size(); ++b) {
    const DetectedObject& ob = objects_b[b];
    ObjectChange c;
    c.id_b = ob.id;
    c.centroid = ob.centroid_m;
    c.height_b = ob.max_height;
    if (match_of_b[b] < 0) {
      const double h_a = height_near(a_index, dev_a, x_ab * ob.centroid_m, ob.area, true);
      if (h_a >= o.change_threshold) {  // there in A too, below A's detection
        c.from_height_field = true;
        c.height_a = h_a;
        c.change = c.height_b - c.height_a;
        c.kind = classify(c.change);
        out.objects.push_back(c);
        continue;
      }
      c.kind = ObjectChangeKind::kNew;
      c.change = c.height_b;
      added.push_back(c);
      continue;
    }
    const DetectedObject& oa = objects_a[static_cast<std::size_t>(match_of_b[b])];
    c.id_a = oa.id;
    c.height_a = oa.max_height;
    if (std::max(oa.area, ob.area) > kMergedAreaRatio * std::min(oa.area, ob.area)) {
      // One map joined what the other split (touching lumps): the larger
      // object's max may stand on a neighbour, so both maps' heights are
      // taken over the smaller object's footprint.
      const bool a_smaller = oa.area <= ob.area;
      const Eigen::Vector3d at = a_smaller ? oa.centroid_m : Eigen::Vector3d(x_ab * ob.centroid_m);
      const double area = std::min(oa.area, ob.area);
      c.height_a = height_near(a_index, dev_a, at, area, false);
      c.height_b = height_near(b_index, dev_b, at, area, false);
      c.from_height_field = true;
    }
    c.change = c.height_b - c.height_a;
    c.kind = classify(c.change);
    out.objects.push_back(c);
  }
  out.objects.insert(out.objects.end(), added.begin(), added.end());
  for (std::size_t a = 0; a < objects_a.size(); ++a) {
    if (a_used[a]) continue;
    ObjectChange c;
    c.kind = ObjectChangeKind::kRemoved;
    c.id_a = objects_a[a].id;
    c.centroid = objects_a[a].centroid_m;
    c.height_a = objects_a[a].max_height;
    c.change = -c.height_a;
    const double h_b = height_near(b_index, dev_b, objects_a[a].centroid_m, objects_a[a].area, true);
    if (h_b >= o.change_threshold) {  // still there in B, below B's detection
      c.from_height_field = true;
      c.height_b = h_b;
      c.change = c.height_b - c.height_a;
      c.kind = classify(c.change);
    }
    out.objects.push_back(c);
  }
  progress.Update(1.0, "compared: " + std::to_string(out.objects.size()) + " objects");
  return out;
}

MappingResultsOnDisk ReadMappingResultsForCompare(const std::string& dir) {
  MappingResultsOnDisk out;
  const fs::path d(dir);
  MeshLoadOptions lo;  // as written: no welding, no reorientation
  lo.weld = false;
  lo.orient_outward = false;
  const std::string mpath = (d / "model.ply").string();
  out.model = LoadMesh(mpath, lo);
  if (!out.model.FindScalar("deviation")) {
    throw InputError({mpath, 0, 0, "deviation"}, "the model has no per-vertex deviation");
  }
  const std::string opath = (d / "objects.json").string();
  const Json odoc = Json::Parse(ReadFileToString(opath), opath);
  const JsonReader root(odoc, opath);
  const Json& items = root.Required("objects");
  if (!items.is_array()) root.Fail(items, "objects", "expected an array");
  for (std::size_t i = 0; i < items.items().size(); ++i) {
    const JsonReader r(items.items()[i], opath, "objects[" + std::to_string(i) + "]");
    DetectedObject o;
    o.id = r.String("id");
    o.centroid_m = Vec3(r, "centroid");
    o.max_height = r.Number("max_height");
    if (r.Has("normal")) o.normal_m = Vec3(r, "normal");  // what registration uses
    if (r.Has("area")) o.area = r.Number("area");         // the footprint looked up in the other map
    out.objects.push_back(std::move(o));
  }
  const std::string jpath = (d / "mapping.json").string();
  if (fs::exists(jpath)) {
    const Json jdoc = Json::Parse(ReadFileToString(jpath), jpath);
    const JsonReader j(jdoc, jpath);
    if (const auto in = j.OptionalObject("inputs")) out.mesh_path = in->OptionalString("mesh").value_or("");
  }
  return out;
}

std::optional<std::string> FindMappingResults(const std::string& results) {
  if (fs::exists(fs::path(results) / "model.ply")) return results;
  if (fs::exists(fs::path(results) / "mapping" / "model.ply")) return (fs::path(results) / "mapping").string();
  return std::nullopt;
}

SurveyComparisonRun RunSurveyComparison(const std::string& results_a, const std::string& results_b,
                                        const std::string& mesh, double mesh_scale, const SurveyCompareOptions& o,
                                        Progress& progress) {
  o.Check();
  SurveyComparisonRun run;
  auto folder = [](const std::string& results) {
    const auto f = FindMappingResults(results);
    if (!f) {
      throw InputError({results, 0, 0, ""}, "holds neither mapping results (model.ply) nor a pipeline's mapping/");
    }
    return *f;
  };
  run.folder_a = folder(results_a);
  run.folder_b = folder(results_b);
  progress.Update(0.0, "reading survey A's results");
  MappingResultsOnDisk a = ReadMappingResultsForCompare(run.folder_a);
  progress.ThrowIfCancelled();
  progress.Update(0.1, "reading survey B's results");
  MappingResultsOnDisk b = ReadMappingResultsForCompare(run.folder_b);
  progress.ThrowIfCancelled();
  run.mesh = mesh.empty() ? a.mesh_path : mesh;
  if (run.mesh.empty()) {
    throw InputError({(fs::path(run.folder_a) / "mapping.json").string(), 0, 0, "inputs.mesh"},
                     "names no CAD mesh: give the mesh");
  }
  progress.Update(0.2, "loading the CAD mesh");
  MeshLoadOptions lo;
  lo.scale = mesh_scale;
  const TriangleMesh cad = LoadMesh(run.mesh, lo);
  progress.ThrowIfCancelled();
  SubProgress sub(progress, 0.3, 1.0);
  run.comparison = CompareSurveys(cad, a.model, a.objects, b.model, b.objects, o, sub);
  run.objects_a = std::move(a.objects);
  run.objects_b = std::move(b.objects);
  return run;
}

void WriteSurveyComparison(const SurveyComparison& c, const std::string& final_dir) {
  WriteDirectoryAtomic(final_dir, [&](const std::string& dir) {
    MeshSaveOptions ply;
    ply.binary = true;
    SaveMesh(c.model, (fs::path(dir) / "model.ply").string(), ply);
    CsvWriter csv(
        {"change", "id_a", "id_b", "x", "y", "z", "height_a", "height_b", "height_change", "from_height_field"});
    Json list = Json::Array();
    for (const ObjectChange& o : c.objects) {
      csv.Add(ObjectChangeKindName(o.kind)).Add(o.id_a).Add(o.id_b);
      for (int k = 0; k < 3; ++k) csv.Add(o.centroid[k]);
      csv.Add(o.height_a).Add(o.height_b).Add(o.change);
      csv.Add(o.from_height_field ? 1 : 0);
      csv.EndRow();
      Json j = Json::Object();
      j.Set("change", ObjectChangeKindName(o.kind));
      j.Set("id_a", o.id_a);
      j.Set("id_b", o.id_b);
      j.Set("centroid", Json::ArrayOf(std::vector<double>{o.centroid.x(), o.centroid.y(), o.centroid.z()}));
      j.Set("height_a", o.height_a);
      j.Set("height_b", o.height_b);
      j.Set("height_change", o.change);
      j.Set("from_height_field", o.from_height_field);
      list.Push(std::move(j));
    }
    WriteFileAtomic((fs::path(dir) / "objects.csv").string(), csv.text());
    Json root = Json::Object();
    root.Set("format", "hull-compare");
    root.Set("version", 1);
    root.Set("vertices", static_cast<std::int64_t>(c.model.num_vertices()));
    root.Set("significant_vertices", static_cast<std::int64_t>(c.significant_vertices));
    const SurveyRegistration& r = c.registration;
    Json reg = Json::Object();
    reg.Set("registered", r.registered);
    reg.Set("objects_in_common", r.inliers);
    reg.Set("objects_in_common_unregistered", r.identity_inliers);
    reg.Set("rms", r.rms);
    reg.Set("rotation_deg", r.rotation * 180.0 / M_PI);
    reg.Set("translation", r.translation);
    const Vector6d x = r.a_from_b.ToVector();
    reg.Set("a_from_b", Json::ArrayOf(std::vector<double>(x.data(), x.data() + 6)));
    root.Set("registration", std::move(reg));
    root.Set("objects", std::move(list));
    WriteFileAtomic((fs::path(dir) / "compare.json").string(), root.Dump());
  });
}

}  // namespace hull
