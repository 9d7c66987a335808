#include "geometry/vertex_regions.h"

#include <numeric>

namespace hull {

VertexRegions ConnectedVertexRegions(const TriangleMesh& mesh, const std::function<bool(int)>& keep) {
  const int nv = static_cast<int>(mesh.num_vertices());
  std::vector<int> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      i = parent[static_cast<std::size_t>(i)];
    }
    return i;
  };
  std::vector<char> kept(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) kept[static_cast<std::size_t>(v)] = keep(v);
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = f[static_cast<std::size_t>(k)], b = f[static_cast<std::size_t>((k + 1) % 3)];
      if (kept[static_cast<std::size_t>(a)] && kept[static_cast<std::size_t>(b)]) {
        parent[static_cast<std::size_t>(find(a))] = find(b);
      }
    }
  }
  VertexRegions out;
  out.region_of.assign(static_cast<std::size_t>(nv), -1);
  std::vector<int> region_of_root(static_cast<std::size_t>(nv), -1);
  for (int v = 0; v < nv; ++v) {
    if (!kept[static_cast<std::size_t>(v)]) continue;
    int& r = region_of_root[static_cast<std::size_t>(find(v))];
    if (r < 0) r = out.num_regions++;
    out.region_of[static_cast<std::size_t>(v)] = r;
  }
  return out;
}

}  // namespace hull
