#include "support/test_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace hull::test {
namespace {

std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// Midpoint vertex of edge (a, b), created once per edge.
int Midpoint(TriangleMesh& m, std::unordered_map<std::uint64_t, int>& cache, int a, int b) {
  const auto [it, inserted] = cache.emplace(EdgeKey(a, b), static_cast<int>(m.vertices.size()));
  if (inserted) m.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
  return it->second;
}

}  // namespace

TriangleMesh MakeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  }
  // Two triangles per side, counter-clockwise seen from outside.
  m.faces = {{0, 2, 1}, {1, 2, 3},   // z = lo
             {4, 5, 6}, {5, 7, 6},   // z = hi
             {0, 1, 4}, {1, 5, 4},   // y = lo
             {2, 6, 3}, {3, 6, 7},   // y = hi
             {0, 4, 2}, {2, 4, 6},   // x = lo
             {1, 3, 5}, {3, 7, 5}};  // x = hi
  m.ComputeNormals();
  return m;
}

TriangleMesh MakeIcosphere(double radius, int subdivisions, const Eigen::Vector3d& centre) {
  if (subdivisions < 0) throw std::invalid_argument("MakeIcosphere: subdivisions must be >= 0");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  m.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& v : m.vertices) v.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    m = Subdivide(m);
    for (auto& v : m.vertices) v.normalize();
  }
  for (auto& v : m.vertices) v = centre + radius * v;
  m.ComputeNormals();
  return m;
}

double IcosphereSagitta(const TriangleMesh& sphere, double radius, const Eigen::Vector3d& centre) {
  // The distance from the centre to a face is at least that to its plane.
  double nearest = radius;
  for (const Face& f : sphere.faces) {
    const Eigen::Vector3d& a = sphere.vertices[f[0]];
    const Eigen::Vector3d n = (sphere.vertices[f[1]] - a).cross(sphere.vertices[f[2]] - a).normalized();
    nearest = std::min(nearest, std::abs((a - centre).dot(n)));
  }
  return radius - nearest;
}

TriangleMesh MakeCylinder(double radius, double height, int segments, double z0) {
  if (segments < 3) throw std::invalid_argument("MakeCylinder: segments must be >= 3");
  TriangleMesh m;
  for (int ring = 0; ring < 2; ++ring) {
    for (int i = 0; i < segments; ++i) {
      const double a = 2.0 * M_PI * i / segments;
      m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z0 + ring * height);
    }
  }
  const int bottom = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0, 0, z0);
  const int top = bottom + 1;
  m.vertices.emplace_back(0, 0, z0 + height);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    const int a = i, b = j, c = segments + j, d = segments + i;
    m.faces.push_back({a, b, c});
    m.faces.push_back({a, c, d});
    m.faces.push_back({bottom, b, a});
    m.faces.push_back({top, d, c});
  }
  m.ComputeNormals();
  return m;
}

TriangleMesh MakeGrid(int nx, int ny, double cell, double z0) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("MakeGrid: nx and ny must be >= 1");
  TriangleMesh m;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) m.vertices.emplace_back(i * cell, j * cell, z0);
  }
  const auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  m.ComputeNormals();
  return m;
}

TriangleMesh Subdivide(const TriangleMesh& mesh) {
  TriangleMesh m;
  m.vertices = mesh.vertices;
  m.faces.reserve(mesh.faces.size() * 4);
  std::unordered_map<std::uint64_t, int> cache;
  cache.reserve(mesh.faces.size() * 2);
  for (const Face& f : mesh.faces) {
    const int a = Midpoint(m, cache, f[0], f[1]);
    const int b = Midpoint(m, cache, f[1], f[2]);
    const int c = Midpoint(m, cache, f[2], f[0]);
    m.faces.push_back({f[0], a, c});
    m.faces.push_back({a, f[1], b});
    m.faces.push_back({c, b, f[2]});
    m.faces.push_back({a, b, c});
  }
  m.ComputeNormals();
  return m;
}

}  // namespace hull::test
