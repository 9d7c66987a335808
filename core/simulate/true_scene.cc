#include "simulate/true_scene.h"

#include <cmath>
#include <filesystem>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

constexpr char kAlbedoModel[] = "hullinspect-procedural-albedo";
constexpr int kAlbedoVersion = 1;
constexpr char kObjectProperty[] = "object";

Json Vec3(const Eigen::Vector3d& v) { return Json::ArrayOf(std::vector<double>{v.x(), v.y(), v.z()}); }

}  // namespace

TriangleMesh TrueSurfaceMesh(const TriangleMesh& cad, const std::vector<TriangleMesh>& object_meshes,
                             std::vector<int>* face_object) {
  TriangleMesh surface = cad;
  if (face_object) face_object->assign(cad.num_faces(), -1);
  for (std::size_t i = 0; i < object_meshes.size(); ++i) {
    surface.Append(object_meshes[i]);
    if (face_object) face_object->resize(surface.num_faces(), static_cast<int>(i));
  }
  return surface;
}

TrueScene::TrueScene(const TriangleMesh& cad, const std::vector<TriangleMesh>& object_meshes,
                     std::vector<TrueObject> objects, SurfaceAlbedo albedo)
    : objects_(std::move(objects)), albedo_(albedo) {
  if (object_meshes.size() != objects_.size()) {
    throw std::invalid_argument("TrueScene: " + std::to_string(object_meshes.size()) + " object meshes for " +
                                std::to_string(objects_.size()) + " objects");
  }
  mesh_ = TrueSurfaceMesh(cad, object_meshes, &face_object_);
  Index();
}

TrueScene::TrueScene(TriangleMesh mesh, std::vector<int> face_object, std::vector<TrueObject> objects,
                     SurfaceAlbedo albedo)
    : mesh_(std::move(mesh)), face_object_(std::move(face_object)), objects_(std::move(objects)), albedo_(albedo) {
  Index();
}

void TrueScene::Index() {
  mesh_.ComputeNormals();
  index_ = std::make_unique<MeshIndex>(mesh_);
  const double crease = std::cos(35.0 * M_PI / 180.0);
  corner_normals_.resize(mesh_.num_faces());
  for (std::size_t f = 0; f < mesh_.num_faces(); ++f) {
    const Eigen::Vector3d& nf = mesh_.face_normals[f];
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int g : index_->FacesOfVertex(mesh_.faces[f][static_cast<std::size_t>(k)])) {
        const Eigen::Vector3d& ng = mesh_.face_normals[static_cast<std::size_t>(g)];
        if (ng.dot(nf) >= crease) sum += mesh_.FaceArea(g) * ng;
      }
      corner_normals_[f][static_cast<std::size_t>(k)] = (sum.norm() > 0 ? sum.normalized() : nf).cast<float>();
    }
  }
  face_frames_.resize(mesh_.num_faces());
  for (std::size_t f = 0; f < mesh_.num_faces(); ++f) {
    const Face& F = mesh_.faces[f];
    const Eigen::Vector3d& a = mesh_.vertices[F[0]];
    const Eigen::Vector3d e1 = mesh_.vertices[F[1]] - a, e2 = mesh_.vertices[F[2]] - a;
    // v = (d22 r.e1 - d12 r.e2) / det, w = (d11 r.e2 - d12 r.e1) / det for r = p - a.
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    FaceFrame& ff = face_frames_[f];
    ff.degenerate = !(std::abs(det) > 0);
    if (ff.degenerate) continue;
    ff.bary_v = (d22 * e1 - d12 * e2) / det;
    ff.bary_w = (d11 * e2 - d12 * e1) / det;
  }
}

Eigen::Vector3f TrueScene::ShadingNormal(int f, const Eigen::Vector3d& p) const {
  const std::size_t i = static_cast<std::size_t>(f);
  const FaceFrame& ff = face_frames_[i];
  if (ff.degenerate) return mesh_.face_normals[i].cast<float>();
  // Barycentric coordinates of p's projection onto the face.
  const Eigen::Vector3d r = p - mesh_.vertices[mesh_.faces[i][0]];
  const float v = static_cast<float>(ff.bary_v.dot(r)), w = static_cast<float>(ff.bary_w.dot(r));
  const auto& c = corner_normals_[i];
  return ((1 - v - w) * c[0] + v * c[1] + w * c[2]).normalized();
}

float TrueScene::AlbedoAt(const Eigen::Vector3d& p, double footprint) const {
  const ClosestPoint c = index_->Closest(p);
  if (c.face < 0) return 0;
  return albedo_.At(c.point.cast<float>(), ShadingNormal(c.face, c.point), ObjectOfFace(c.face),
                    static_cast<float>(footprint));
}

void TrueScene::Write(const std::string& bundle_dir) const {
  const fs::path truth = fs::path(bundle_dir) / "truth";
  fs::create_directories(truth);
  TriangleMesh out = mesh_;
  std::vector<double> object(mesh_.num_vertices(), -1.0);
  for (std::size_t f = 0; f < mesh_.num_faces(); ++f) {
    for (int v : mesh_.faces[f]) object[static_cast<std::size_t>(v)] = face_object_[f];
  }
  out.vertex_scalars.clear();
  out.SetScalar(kObjectProperty, std::move(object));
  MeshSaveOptions mo;
  mo.binary = true;
  mo.double_precision = true;
  SaveMesh(out, (truth / "scene.ply").string(), mo);
  Json root = Json::Object();
  root.Set("model", kAlbedoModel);
  root.Set("version", kAlbedoVersion);
  root.Set("seed", static_cast<std::int64_t>(albedo_.seed()));
  root.Set("forward", Vec3(albedo_.forward()));
  root.Set("up", Vec3(albedo_.up()));
  root.Set("faces", "scene.ply vertex property 'object': -1 hull, i: truth/objects.json objects[i]");
  WriteFileAtomic((truth / "albedo.json").string(), root.Dump());
}

std::unique_ptr<TrueScene> TrueScene::Load(const SurveyBundle& bundle) {
  const fs::path truth = fs::path(bundle.directory) / "truth";
  const std::string albedo_path = (truth / "albedo.json").string();
  const Json doc = Json::Parse(ReadFileToString(albedo_path), albedo_path);
  const JsonReader r(doc, albedo_path);
  if (r.String("model") != kAlbedoModel) {
    r.Fail(r.Required("model"), "model", std::string("expected \"") + kAlbedoModel + "\"");
  }
  if (r.Integer("version") != kAlbedoVersion) {
    r.Fail(r.Required("version"), "version", "unsupported albedo version; this reader knows version 1");
  }
  const std::int64_t seed = r.Integer("seed");
  if (seed < 0) r.Fail(r.Required("seed"), "seed", "expected a non-negative integer");
  const std::vector<double> f = r.Numbers("forward", 3), u = r.Numbers("up", 3);
  const Eigen::Vector3d forward(f[0], f[1], f[2]), up(u[0], u[1], u[2]);
  if (forward.norm() < 1e-9 || up.norm() < 1e-9 || std::abs(forward.normalized().dot(up.normalized())) > 0.99) {
    r.Fail(r.Required("up"), "up", "expected non-zero forward and up axes, not parallel");
  }

  const std::string scene_path = (truth / "scene.ply").string();
  MeshLoadOptions lo;
  lo.weld = false;
  lo.orient_outward = false;
  TriangleMesh mesh = LoadMesh(scene_path, lo);
  const std::vector<double>* object = mesh.FindScalar(kObjectProperty);
  if (!object) throw InputError({scene_path, 0, 0, kObjectProperty}, "no vertex property 'object'");
  const std::vector<TrueObject> objects = bundle.truth ? bundle.truth->objects : std::vector<TrueObject>{};
  std::vector<int> face_object(mesh.num_faces(), -1);
  for (std::size_t i = 0; i < mesh.num_faces(); ++i) {
    const double o = (*object)[static_cast<std::size_t>(mesh.faces[i][0])];
    if (!(o == std::floor(o) && o >= -1 && o < static_cast<double>(objects.size()))) {
      throw InputError({scene_path, 0, 0, kObjectProperty}, "face " + std::to_string(i) + " names object " +
                                                                FormatDouble(o) + "; truth/objects.json has " +
                                                                std::to_string(objects.size()) + " objects");
    }
    face_object[i] = static_cast<int>(o);
  }
  return std::unique_ptr<TrueScene>(new TrueScene(std::move(mesh), std::move(face_object), objects,
                                                  SurfaceAlbedo(static_cast<std::uint64_t>(seed), forward, up)));
}

}  // namespace hull
