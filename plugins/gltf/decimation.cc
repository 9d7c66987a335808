#include "gltf/decimation.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <cstdio>
#include <vector>

namespace hull::gltf {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

}  // namespace

DecimationResult Decimate(plugin::MeshData& m, std::size_t max_triangles, double max_error) {
  DecimationResult r;
  const std::size_t before = m.num_triangles();
  if (max_triangles == 0 || before <= max_triangles) return r;
  Mesh mesh;
  std::vector<Mesh::VertexHandle> handles;
  handles.reserve(m.num_vertices());
  OpenMesh::VPropHandleT<int> original;  // the input index of each vertex
  mesh.add_property(original);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    handles.push_back(mesh.add_vertex(Mesh::Point(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2])));
    mesh.property(original, handles.back()) = static_cast<int>(v);
  }
  std::size_t refused = 0;
  for (std::size_t t = 0; t < before; ++t) {
    const auto& tri = m.triangles;
    refused += !mesh.add_face(handles[tri[3 * t]], handles[tri[3 * t + 1]], handles[tri[3 * t + 2]]).is_valid();
  }
  if (refused > 0) {
    r.note = "not decimated: " + std::to_string(refused) + " triangles make it no 2-manifold";
    return r;
  }
  mesh.update_face_normals();
  OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
  decimater.add(quadric);
  decimater.add(flipping);
  decimater.module(quadric).set_max_err(max_error * max_error, false);  // squared distance; still the priority
  decimater.initialize();
  decimater.decimate_to_faces(0, max_triangles);
  mesh.garbage_collection();

  plugin::MeshData out;
  out.positions.reserve(3 * mesh.n_vertices());
  std::vector<int> kept;  // input index per output vertex
  for (const auto v : mesh.vertices()) {
    const Mesh::Point& p = mesh.point(v);
    out.positions.insert(out.positions.end(), {p[0], p[1], p[2]});
    kept.push_back(mesh.property(original, v));
  }
  for (const auto f : mesh.faces()) {
    for (const auto v : mesh.fv_range(f)) out.triangles.push_back(v.idx());
  }
  for (const auto& [name, values] : m.vertex_scalars) {
    std::vector<double> picked;
    picked.reserve(kept.size());
    for (int i : kept) picked.push_back(values[static_cast<std::size_t>(i)]);
    out.vertex_scalars.emplace_back(name, std::move(picked));
  }
  m = std::move(out);
  char buf[160];
  std::snprintf(buf, sizeof buf, "%zu of %zu triangles kept (OpenMesh quadric decimation, error <= %g m)",
                m.num_triangles(), before, max_error);
  r.done = true;
  r.note = buf;
  return r;
}

}  // namespace hull::gltf
