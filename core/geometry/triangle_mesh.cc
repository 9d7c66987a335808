#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <unordered_map>

namespace hull {
namespace {

std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// Edge -> faces that use it.
std::unordered_map<std::uint64_t, std::vector<int>> EdgeFaces(const std::vector<Face>& faces) {
  std::unordered_map<std::uint64_t, std::vector<int>> edges;
  edges.reserve(faces.size() * 2);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    for (int k = 0; k < 3; ++k) edges[EdgeKey(faces[f][k], faces[f][(k + 1) % 3])].push_back(f);
  }
  return edges;
}

// True when face f traverses the directed edge a -> b.
bool Traverses(const Face& f, int a, int b) {
  for (int k = 0; k < 3; ++k) {
    if (f[k] == a && f[(k + 1) % 3] == b) return true;
  }
  return false;
}

}  // namespace

void TriangleMesh::ComputeNormals() {
  face_normals.assign(faces.size(), Eigen::Vector3d::Zero());
  vertex_normals.assign(vertices.size(), Eigen::Vector3d::Zero());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& F = faces[f];
    const Eigen::Vector3d n = (vertices[F[1]] - vertices[F[0]]).cross(vertices[F[2]] - vertices[F[0]]);
    for (int k = 0; k < 3; ++k) vertex_normals[F[k]] += n;  // area weighted
    const double len = n.norm();
    face_normals[f] = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
  }
  for (auto& n : vertex_normals) {
    const double len = n.norm();
    n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
  }
}

Eigen::AlignedBox3d TriangleMesh::Bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& v : vertices) box.extend(v);
  return box;
}

double TriangleMesh::FaceArea(int f) const {
  const auto& F = faces[f];
  return 0.5 * (vertices[F[1]] - vertices[F[0]]).cross(vertices[F[2]] - vertices[F[0]]).norm();
}

double TriangleMesh::SurfaceArea() const {
  double a = 0;
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) a += FaceArea(f);
  return a;
}

Eigen::Vector3d TriangleMesh::FaceCentroid(int f) const {
  const auto& F = faces[f];
  return (vertices[F[0]] + vertices[F[1]] + vertices[F[2]]) / 3.0;
}

double TriangleMesh::SignedVolume() const {
  if (vertices.empty()) return 0;
  const Eigen::Vector3d c = Bounds().center();  // reference point: better conditioning
  double v = 0;
  for (const auto& F : faces) {
    v += (vertices[F[0]] - c).dot((vertices[F[1]] - c).cross(vertices[F[2]] - c));
  }
  return v / 6.0;
}

void TriangleMesh::Transform(const Pose& T, double scale) {
  for (auto& v : vertices) v = T * (scale * v);
  if (scale < 0) {
    for (auto& F : faces) std::swap(F[1], F[2]);  // mirror: keep normals outward
  }
  ComputeNormals();
}

std::size_t TriangleMesh::WeldVertices(double tol) {
  const std::size_t n = vertices.size();
  if (n == 0) return 0;
  // Sort by x and merge within tol in a sweep; exact duplicates when tol = 0.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto& A = vertices[a];
    const auto& B = vertices[b];
    if (A.x() != B.x()) return A.x() < B.x();
    if (A.y() != B.y()) return A.y() < B.y();
    return A.z() < B.z();
  });
  std::vector<int> remap(n, -1);
  std::vector<Eigen::Vector3d> out;
  out.reserve(n);
  std::vector<std::vector<double>> scal_out(vertex_scalars.size());
  const double tol2 = tol * tol;
  for (std::size_t i = 0; i < n; ++i) {
    const int a = order[i];
    if (remap[a] >= 0) continue;
    remap[a] = static_cast<int>(out.size());
    out.push_back(vertices[a]);
    for (std::size_t s = 0; s < vertex_scalars.size(); ++s) scal_out[s].push_back(vertex_scalars[s].second[a]);
    for (std::size_t j = i + 1; j < n; ++j) {
      const int b = order[j];
      if (vertices[b].x() - vertices[a].x() > tol) break;
      if (remap[b] < 0 && (vertices[b] - vertices[a]).squaredNorm() <= tol2) remap[b] = remap[a];
    }
  }
  const std::size_t removed = n - out.size();
  vertices = std::move(out);
  for (std::size_t s = 0; s < vertex_scalars.size(); ++s) vertex_scalars[s].second = std::move(scal_out[s]);
  std::vector<Face> kept;
  kept.reserve(faces.size());
  for (auto F : faces) {
    for (int& i : F) i = remap[i];
    if (F[0] != F[1] && F[1] != F[2] && F[0] != F[2]) kept.push_back(F);
  }
  faces = std::move(kept);
  ComputeNormals();
  return removed;
}

OrientationReport TriangleMesh::CheckTopology() const {
  OrientationReport r;
  const auto edges = EdgeFaces(faces);
  for (const auto& [key, fs] : edges) {
    if (fs.size() == 1) ++r.boundary_edges;
    if (fs.size() > 2) ++r.non_manifold_edges;
  }
  r.closed = !faces.empty() && r.boundary_edges == 0 && r.non_manifold_edges == 0;
  return r;
}

OrientationReport TriangleMesh::OrientOutward() {
  OrientationReport report = CheckTopology();
  const auto edges = EdgeFaces(faces);
  const int nf = static_cast<int>(faces.size());
  std::vector<int> component(nf, -1);
  std::vector<char> flipped(nf, 0);
  int ncomp = 0;
  for (int seed = 0; seed < nf; ++seed) {
    if (component[seed] >= 0) continue;
    std::vector<int> members;
    std::queue<int> queue;
    queue.push(seed);
    component[seed] = ncomp;
    bool comp_closed = true;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      members.push_back(f);
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][k], b = faces[f][(k + 1) % 3];
        const auto& fs = edges.at(EdgeKey(a, b));
        if (fs.size() != 2) {
          comp_closed = false;
          continue;  // boundary or non-manifold: do not propagate across
        }
        const int g = fs[0] == f ? fs[1] : fs[0];
        if (component[g] >= 0) continue;
        component[g] = ncomp;
        // Consistent winding: g must traverse the shared edge as b -> a.
        if (Traverses(faces[g], a, b)) {
          std::swap(faces[g][1], faces[g][2]);
          flipped[g] ^= 1;
        }
        queue.push(g);
      }
    }
    // Outward test for this component.
    double score = 0;
    if (comp_closed) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int f : members) c += vertices[faces[f][0]];
      c /= static_cast<double>(members.size());
      for (int f : members) {
        const auto& F = faces[f];
        score += (vertices[F[0]] - c).dot((vertices[F[1]] - c).cross(vertices[F[2]] - c));
      }
    } else {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      double area = 0;
      for (int f : members) {
        const double a = FaceArea(f);
        c += a * FaceCentroid(f);
        area += a;
      }
      if (area > 0) c /= area;
      for (int f : members) {
        const auto& F = faces[f];
        const Eigen::Vector3d n = (vertices[F[1]] - vertices[F[0]]).cross(vertices[F[2]] - vertices[F[0]]);
        score += n.dot(FaceCentroid(f) - c);
      }
    }
    if (score < 0) {
      if (members.size() * 2 > static_cast<std::size_t>(nf)) report.was_inside_out = true;
      for (int f : members) {
        std::swap(faces[f][1], faces[f][2]);
        flipped[f] ^= 1;
      }
    }
    ++ncomp;
  }
  report.components = ncomp;
  report.faces_flipped = static_cast<int>(std::count(flipped.begin(), flipped.end(), 1));
  ComputeNormals();
  return report;
}

const std::vector<double>* TriangleMesh::FindScalar(const std::string& name) const {
  for (const auto& [n, v] : vertex_scalars) {
    if (n == name) return &v;
  }
  return nullptr;
}

void TriangleMesh::SetScalar(const std::string& name, std::vector<double> values) {
  for (auto& [n, v] : vertex_scalars) {
    if (n == name) {
      v = std::move(values);
      return;
    }
  }
  vertex_scalars.emplace_back(name, std::move(values));
}

void TriangleMesh::Append(const TriangleMesh& other) {
  const int offset = static_cast<int>(vertices.size());
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  for (auto& [name, values] : vertex_scalars) {
    if (const auto* o = other.FindScalar(name)) {
      values.insert(values.end(), o->begin(), o->end());
      scalars.emplace_back(name, std::move(values));
    }
  }
  vertex_scalars = std::move(scalars);
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (Face F : other.faces) {
    for (int& i : F) i += offset;
    faces.push_back(F);
  }
  ComputeNormals();
}

}  // namespace hull
