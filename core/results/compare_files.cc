#include "results/compare_files.h"

#include <cmath>
#include <filesystem>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"
#include "results/file_hash.h"
#include "results/mapping_files.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

std::string Path(const std::string& dir, const char* f) { return (fs::path(dir) / f).string(); }

std::string MappingFolder(const std::string& results) {
  const auto f = FindMappingResults(results);
  if (!f) throw InputError({results, 0, 0, ""}, "holds neither mapping results (model.ply) nor a pipeline's mapping/");
  return *f;
}

// The CAD mesh a mapping folder's run recorded (nullptr: none recorded).
const ResultsInput* MeshOf(const MappingResultsOnDisk& r) {
  return r.manifest ? r.manifest->run.Input("mesh") : nullptr;
}

// Both maps against the same CAD, and `mesh` that CAD, where the manifests say.
void CheckSameMesh(const SurveyComparisonRun& run, const MappingResultsOnDisk& a, const MappingResultsOnDisk& b) {
  const ResultsInput* ma = MeshOf(a);
  const ResultsInput* mb = MeshOf(b);
  if (ma && mb && !ma->hash.empty() && ma->hash != mb->hash) {
    throw InputError({Path(run.folder_b, "model.ply"), 0, 0, ""},
                     "was mapped against the mesh " + mb->path + ", but " + Path(run.folder_a, "model.ply") +
                         " against " + ma->path + " (another file): the two surveys cannot be compared on one CAD");
  }
  if (ma && !ma->hash.empty() && fs::exists(run.mesh) && FileHash(run.mesh) != ma->hash) {
    throw InputError({run.mesh, 0, 0, ""}, "is not the CAD mesh " + Path(run.folder_a, "model.ply") +
                                               " was mapped against (" + ma->path + ", another file)");
  }
}

Eigen::Vector3d Vec3(const JsonReader& r, const char* key) {
  const std::vector<double> v = r.Numbers(key, 3);
  return {v[0], v[1], v[2]};
}

ObjectChangeKind ChangeKindOf(const JsonReader& r) {
  const std::string s = r.String("change");
  for (ObjectChangeKind k : {ObjectChangeKind::kNew, ObjectChangeKind::kRemoved, ObjectChangeKind::kGrown,
                             ObjectChangeKind::kShrunk, ObjectChangeKind::kUnchanged}) {
    if (s == ObjectChangeKindName(k)) return k;
  }
  r.Fail(r.Required("change"), "change", "expected new, removed, grown, shrunk or unchanged");
}

void ReadCompareJson(const std::string& dir, SurveyComparison& c) {
  const std::string path = Path(dir, "compare.json");
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader root(doc, path);
  if (root.String("format") != "hull-compare")
    root.Fail(root.Required("format"), "format", "expected \"hull-compare\"");
  if (root.Integer("version") != 2) root.Fail(root.Required("version"), "version", "unsupported; this reader knows 2");
  c.significant_vertices = static_cast<std::size_t>(root.Integer("significant_vertices"));
  c.reach = root.Number("peak_reach");
  const JsonReader reg = root.Object("registration");
  SurveyRegistration& r = c.registration;
  const Json& registered = reg.Required("registered");
  if (!registered.is_bool()) reg.Fail(registered, "registered", "expected true or false");
  r.registered = registered.as_bool();
  r.inliers = static_cast<int>(reg.Integer("peaks_in_common"));
  r.identity_inliers = static_cast<int>(reg.Integer("peaks_in_common_unregistered"));
  r.rms = reg.Number("rms");
  r.rotation = reg.Number("rotation_deg") * M_PI / 180.0;
  r.translation = reg.Number("translation");
  const std::vector<double> x = reg.Numbers("a_from_b", 6);
  r.a_from_b = Pose::FromArray(x.data());
  const Json& items = root.Required("objects");
  if (!items.is_array()) root.Fail(items, "objects", "expected an array");
  for (std::size_t i = 0; i < items.items().size(); ++i) {
    const JsonReader o(items.items()[i], path, "objects[" + std::to_string(i) + "]");
    ObjectChange ch;
    ch.kind = ChangeKindOf(o);
    ch.id_a = o.String("id_a");
    ch.id_b = o.String("id_b");
    ch.centroid = Vec3(o, "centroid");
    ch.height_a = o.Number("height_a");
    ch.height_b = o.Number("height_b");
    ch.change = o.Number("height_change");
    const Json& f = o.Required("from_height_field");
    if (!f.is_bool()) o.Fail(f, "from_height_field", "expected true or false");
    ch.from_height_field = f.as_bool();
    c.objects.push_back(std::move(ch));
  }
}

}  // namespace

SurveyComparisonRun RunSurveyComparison(const std::string& results_a, const std::string& results_b,
                                        const std::string& mesh, double mesh_scale, const SurveyCompareOptions& o,
                                        Progress& progress) {
  o.Check();
  SurveyComparisonRun run;
  run.folder_a = MappingFolder(results_a);
  run.folder_b = MappingFolder(results_b);
  progress.Update(0.0, "reading survey A's results");
  MappingResultsOnDisk a = ReadMappingResultsForCompare(run.folder_a);
  progress.ThrowIfCancelled();
  progress.Update(0.1, "reading survey B's results");
  MappingResultsOnDisk b = ReadMappingResultsForCompare(run.folder_b);
  progress.ThrowIfCancelled();
  run.mesh = mesh.empty() ? a.mesh_path : mesh;
  if (run.mesh.empty()) {
    throw InputError({Path(run.folder_a, "mapping.json"), 0, 0, "inputs.mesh"}, "names no CAD mesh: give the mesh");
  }
  CheckSameMesh(run, a, b);
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

void WriteSurveyComparison(const SurveyComparison& c, const std::string& dir) {
  fs::create_directories(dir);
  MeshSaveOptions ply;
  ply.binary = true;
  SaveMesh(c.model, Path(dir, "model.ply"), ply);
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
  WriteFileAtomic(Path(dir, "objects.csv"), csv.text());
  Json root = Json::Object();
  root.Set("format", "hull-compare");
  root.Set("version", 2);
  root.Set("vertices", static_cast<std::int64_t>(c.model.num_vertices()));
  root.Set("significant_vertices", static_cast<std::int64_t>(c.significant_vertices));
  const SurveyRegistration& r = c.registration;
  Json reg = Json::Object();
  reg.Set("registered", r.registered);
  reg.Set("peaks_in_common", r.inliers);
  reg.Set("peaks_in_common_unregistered", r.identity_inliers);
  reg.Set("rms", r.rms);
  reg.Set("rotation_deg", r.rotation * 180.0 / M_PI);
  reg.Set("translation", r.translation);
  const Vector6d x = r.a_from_b.ToVector();
  reg.Set("a_from_b", Json::ArrayOf(std::vector<double>(x.data(), x.data() + 6)));
  root.Set("registration", std::move(reg));
  root.Set("peak_reach", c.reach);
  root.Set("objects", std::move(list));
  WriteFileAtomic(Path(dir, "compare.json"), root.Dump());
}

void SaveComparisonResults(const SurveyComparisonRun& c, const OutputFolder& out, ResultsRun run) {
  run.AddResults("results_a", c.folder_a);
  run.AddResults("results_b", c.folder_b);
  run.AddFile("mesh", c.mesh);
  WriteResultsFolder(out, run, [&](const std::string& tmp) { WriteSurveyComparison(c.comparison, tmp); });
}

ComparisonOnDisk ReadComparisonResults(const std::string& dir) {
  const std::optional<ResultsManifest> m =
      CheckResultsFiles({Path(dir, "model.ply"), Path(dir, "compare.json")}, "the comparison in " + dir);
  ComparisonOnDisk out;
  MeshLoadOptions lo;  // as written
  lo.weld = false;
  lo.orient_outward = false;
  out.comparison.model = LoadMesh(Path(dir, "model.ply"), lo);
  for (const char* s : {"change", "change_sigma", "change_significant"}) {
    if (!out.comparison.model.FindScalar(s)) {
      throw InputError({Path(dir, "model.ply"), 0, 0, s}, std::string("a comparison's model needs per-vertex ") + s);
    }
  }
  ReadCompareJson(dir, out.comparison);
  if (m) {
    if (const ResultsInput* a = m->run.Input("results_a")) out.folder_a = a->path;
    if (const ResultsInput* b = m->run.Input("results_b")) out.folder_b = b->path;
    if (const ResultsInput* mesh = m->run.Input("mesh")) out.mesh = mesh->path;
  }
  return out;
}

}  // namespace hull
