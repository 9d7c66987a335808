// The only translation unit that instantiates CGAL's Surface_mesh and
// isotropic remeshing.
#include "mapping/mesh_refinement.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hull {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using FaceIndex = SurfaceMesh::Face_index;

// The coarse pass's edge length, in target edges.
constexpr double kCoarseFactor = 8.0;

K::Point_3 P(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d V(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

SurfaceMesh ToSurfaceMesh(const TriangleMesh& m) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vs;
  vs.reserve(m.num_vertices());
  for (const auto& v : m.vertices) vs.push_back(sm.add_vertex(P(v)));
  bool manifold = true;
  for (const Face& f : m.faces) {
    if (sm.add_face(vs[static_cast<std::size_t>(f[0])], vs[static_cast<std::size_t>(f[1])],
                    vs[static_cast<std::size_t>(f[2])]) == SurfaceMesh::null_face()) {
      manifold = false;
      break;
    }
  }
  if (manifold) return sm;
  // A non-manifold CAD mesh: let CGAL duplicate what it must.
  std::vector<K::Point_3> points;
  for (const auto& v : m.vertices) points.push_back(P(v));
  std::vector<std::vector<std::size_t>> polygons;
  for (const Face& f : m.faces) {
    polygons.push_back(
        {static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]), static_cast<std::size_t>(f[2])});
  }
  PMP::orient_polygon_soup(points, polygons);
  SurfaceMesh repaired;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, repaired);
  return repaired;
}

TriangleMesh FromSurfaceMesh(SurfaceMesh& sm) {
  sm.collect_garbage();
  TriangleMesh m;
  m.vertices.reserve(sm.number_of_vertices());
  for (const auto v : sm.vertices()) m.vertices.push_back(V(sm.point(v)));
  m.faces.reserve(sm.number_of_faces());
  for (const auto f : sm.faces()) {
    Face face{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) face[static_cast<std::size_t>(k)] = static_cast<int>(v.idx());
      ++k;
    }
    if (k == 3) m.faces.push_back(face);
  }
  m.ComputeNormals();
  return m;
}

// Distance from p to the triangle (a, b, c) (Ericson, Real-Time Collision
// Detection, 5.1.5).
double PointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// CAD faces within half a cell diagonal of a region cell's centre: from the
// closest face, a walk over faces sharing a vertex.
std::vector<char> CadFacesInRegion(const TriangleMesh& cad, const MeshIndex& index, const RefinementRegion& region) {
  std::vector<char> selected(cad.num_faces(), 0);
  const double reach = 0.5 * std::sqrt(3.0) * region.cell() * (1 + 1e-9);
  std::vector<int> queue, seen;
  for (const Eigen::Vector3d& c : region.CellCentres()) {
    const ClosestPoint cp = index.Closest(c);
    if (cp.face < 0 || cp.distance > reach) continue;
    queue.assign(1, cp.face);
    seen.assign(1, cp.face);
    selected[static_cast<std::size_t>(cp.face)] = 1;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (const int v : cad.faces[static_cast<std::size_t>(queue[q])]) {
        for (const int g : index.FacesOfVertex(v)) {
          if (std::find(seen.begin(), seen.end(), g) != seen.end()) continue;
          seen.push_back(g);
          const Face& G = cad.faces[static_cast<std::size_t>(g)];
          if (PointTriangleDistance(c, cad.vertices[static_cast<std::size_t>(G[0])],
                                    cad.vertices[static_cast<std::size_t>(G[1])],
                                    cad.vertices[static_cast<std::size_t>(G[2])]) <= reach) {
            selected[static_cast<std::size_t>(g)] = 1;
            queue.push_back(g);
          }
        }
      }
    }
  }
  return selected;
}

// Faces of sm (no larger than max_edge) that pass through a region cell,
// tested on a barycentric grid of half a cell.
std::vector<FaceIndex> SurfaceFacesInRegion(const SurfaceMesh& sm, const RefinementRegion& region, double max_edge) {
  std::vector<FaceIndex> out;
  const double step = 0.5 * region.cell();
  for (const auto f : sm.faces()) {
    Eigen::Vector3d p[3];
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) p[k] = V(sm.point(v));
      ++k;
    }
    if (k != 3) continue;
    const double longest = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
    if (longest > max_edge) continue;
    const int m = std::max(1, static_cast<int>(std::ceil(longest / step)));
    bool inside = false;
    for (int i = 0; i <= m && !inside; ++i) {
      for (int j = 0; i + j <= m && !inside; ++j) {
        inside = region.Contains(p[0] + (p[1] - p[0]) * (static_cast<double>(i) / m) +
                                 (p[2] - p[0]) * (static_cast<double>(j) / m));
      }
    }
    if (inside) out.push_back(f);
  }
  return out;
}

double FacesArea(const SurfaceMesh& sm, const std::vector<FaceIndex>& faces) {
  double area = 0;
  for (const auto f : faces) {
    Eigen::Vector3d p[3];
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) p[k] = V(sm.point(v));
      ++k;
    }
    area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  }
  return area;
}

}  // namespace

RefinedMesh RefineMesh(const TriangleMesh& cad, const MeshIndex& cad_index, const RefinementRegion& region,
                       double target_edge) {
  if (!(target_edge > 0)) throw std::invalid_argument("RefineMesh: target_edge must be positive");
  RefinedMesh out;
  out.region = region;
  out.edge = target_edge;
  if (region.empty()) {
    out.mesh.vertices = cad.vertices;
    out.mesh.faces = cad.faces;
    out.mesh.ComputeNormals();
    return out;
  }
  SurfaceMesh sm = ToSurfaceMesh(cad);
  const double coarse = kCoarseFactor * target_edge;
  // Pass 1: the CAD faces the region touches, to the coarse edge.
  {
    const std::vector<char> selected = CadFacesInRegion(cad, cad_index, region);
    std::vector<FaceIndex> faces;
    for (std::size_t f = 0; f < selected.size(); ++f) {
      if (selected[f] && f < sm.number_of_faces()) faces.push_back(FaceIndex(static_cast<SurfaceMesh::size_type>(f)));
    }
    if (!faces.empty()) {
      PMP::isotropic_remeshing(faces, coarse, sm, PMP::parameters::number_of_iterations(2).protect_constraints(false));
      sm.collect_garbage();
    }
  }
  // Pass 2: the coarse faces the region touches, to the target edge.
  const std::vector<FaceIndex> faces = SurfaceFacesInRegion(sm, region, 2.0 * coarse);
  out.refined_area = FacesArea(sm, faces);
  const std::size_t before = sm.number_of_faces();
  if (!faces.empty()) {
    PMP::isotropic_remeshing(faces, target_edge, sm,
                             PMP::parameters::number_of_iterations(3).protect_constraints(false));
  }
  const std::size_t after = sm.number_of_faces();
  out.refined_faces = static_cast<int>(after + faces.size() - before);
  out.mesh = FromSurfaceMesh(sm);
  // The remeshing's edge collapses and flips cut the CAD's curvature (the
  // coarse pass by up to centimetres); put every vertex back on the CAD.
  for (Eigen::Vector3d& v : out.mesh.vertices) v = cad_index.Closest(v).point;
  out.mesh.ComputeNormals();
  return out;
}

}  // namespace hull
