// The true surface of a simulated survey -- the CAD hull plus the foreign
// objects, in the model frame M -- with its albedo: what the underwater
// renderer images, and what reconstructions and photomosaics are scored
// against. Written to a bundle as truth/scene.ply (triangles in M, a vertex
// property "object": -1 on the hull, i on truth/objects.json's object i) and
// truth/albedo.json (the albedo's seed and hull axes: SurfaceAlbedo rebuilt
// from it gives the same value at every point).
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/triangle_mesh.h"
#include "simulate/surface_albedo.h"
#include "survey/survey.h"

namespace hull {

// The hull with every object mesh appended (each keeps its own vertices);
// face_object (if not null) gets -1 for hull faces and i for object i's.
TriangleMesh TrueSurfaceMesh(const TriangleMesh& cad, const std::vector<TriangleMesh>& object_meshes,
                             std::vector<int>* face_object);

class TrueScene {
 public:
  // object_meshes[i] is the mesh of objects[i].
  TrueScene(const TriangleMesh& cad, const std::vector<TriangleMesh>& object_meshes, std::vector<TrueObject> objects,
            SurfaceAlbedo albedo);
  TrueScene(const TrueScene&) = delete;
  TrueScene& operator=(const TrueScene&) = delete;

  // Reads truth/scene.ply and truth/albedo.json of the bundle (objects from
  // its truth/objects.json). Throws InputError naming the file.
  static std::unique_ptr<TrueScene> Load(const SurveyBundle& bundle);
  // Writes truth/scene.ply and truth/albedo.json into the bundle folder.
  void Write(const std::string& bundle_dir) const;

  const TriangleMesh& mesh() const { return mesh_; }
  const MeshIndex& index() const { return *index_; }
  const std::vector<TrueObject>& objects() const { return objects_; }
  const SurfaceAlbedo& albedo() const { return albedo_; }

  // The object face f belongs to (nullptr: the hull), and its index (-1).
  const TrueObject* ObjectOfFace(int f) const {
    const int i = face_object_[static_cast<std::size_t>(f)];
    return i < 0 ? nullptr : &objects_[static_cast<std::size_t>(i)];
  }
  int ObjectIndexOfFace(int f) const { return face_object_[static_cast<std::size_t>(f)]; }

  // The shading normal at point p of face f: each corner's normal averaged
  // over the faces around it within 35 degrees of f (creases such as a
  // cylinder's rim stay sharp), interpolated over the face.
  Eigen::Vector3f ShadingNormal(int f, const Eigen::Vector3d& p) const;

  // The albedo at a point on (or within centimetres of) the surface, on the
  // closest face; footprint as in SurfaceAlbedo (0: full detail).
  float AlbedoAt(const Eigen::Vector3d& p, double footprint = 0) const;

 private:
  TrueScene(TriangleMesh mesh, std::vector<int> face_object, std::vector<TrueObject> objects, SurfaceAlbedo albedo);
  void Index();  // builds index_, corner_normals_ and face_frames_

  TriangleMesh mesh_;
  std::vector<int> face_object_;
  std::vector<TrueObject> objects_;
  SurfaceAlbedo albedo_;
  std::unique_ptr<MeshIndex> index_;
  std::vector<std::array<Eigen::Vector3f, 3>> corner_normals_;
  // Per face: barycentric coordinates (v, w) of a point p's projection are
  // (bary_v . (p - a), bary_w . (p - a)), a the face's first corner (zero
  // vectors for a degenerate face, which takes its face normal).
  struct FaceFrame {
    Eigen::Vector3d bary_v, bary_w;
    bool degenerate = false;
  };
  std::vector<FaceFrame> face_frames_;
};

}  // namespace hull
