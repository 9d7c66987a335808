// The per-face view of the photomosaic (photomosaic_internal.h): the edge
// splitting near the cameras, face adjacency, the Potts labelling and the
// feathering weights across view boundaries.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "mosaic/photomosaic_internal.h"

namespace hull {
namespace mosaic_internal {
namespace {

// The kMaxViewsPerVertex views of largest positive weight in acc (ties: the
// lower view), their weights normalised to sum 1.
ViewWeights Strongest(std::map<int, double>& acc) {
  std::vector<std::pair<double, int>> all;
  for (const auto& [v, w] : acc) {
    if (w > 0) all.emplace_back(w, v);
  }
  std::sort(all.begin(), all.end(),
            [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  ViewWeights out;
  double sum = 0;
  for (std::size_t i = 0; i < all.size() && i < kMaxViewsPerVertex; ++i) sum += all[i].first;
  for (std::size_t i = 0; i < all.size() && i < kMaxViewsPerVertex; ++i) {
    out.view[i] = all[i].second;
    out.weight[i] = static_cast<float>(all[i].first / sum);
  }
  return out;
}

}  // namespace

// Splits every edge longer than max_edge of the faces that `near` accepts,
// conformingly: each round bisects the marked edges, a face with one, two
// or three marked edges becomes two, three or four triangles.
void SplitLongEdges(TriangleMesh& m, double max_edge, const std::function<bool(int)>& near) {
  std::vector<char> active(m.num_faces(), 0);
  for (std::size_t f = 0; f < m.num_faces(); ++f) active[f] = near(static_cast<int>(f)) ? 1 : 0;
  const double l2 = max_edge * max_edge;
  for (int round = 0; round < 30; ++round) {
    std::map<std::pair<int, int>, int> mid;  // marked edge -> new vertex
    for (std::size_t f = 0; f < m.num_faces(); ++f) {
      if (!active[f]) continue;
      for (int i = 0; i < 3; ++i) {
        const int a = m.faces[f][i], b = m.faces[f][(i + 1) % 3];
        if ((m.vertices[static_cast<std::size_t>(a)] - m.vertices[static_cast<std::size_t>(b)]).squaredNorm() <= l2) {
          continue;
        }
        const auto key = std::minmax(a, b);
        if (mid.count(key)) continue;
        mid[key] = static_cast<int>(m.vertices.size());
        m.vertices.push_back(0.5 * (m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)]));
      }
    }
    if (mid.empty()) break;
    std::vector<Face> faces;
    std::vector<char> next_active;
    faces.reserve(m.faces.size() + 3 * mid.size());
    for (std::size_t f = 0; f < m.num_faces(); ++f) {
      const Face F = m.faces[f];
      int e[3];
      int marked = 0;
      for (int i = 0; i < 3; ++i) {
        const auto it = mid.find(std::minmax(F[i], F[(i + 1) % 3]));
        e[i] = it == mid.end() ? -1 : it->second;
        marked += e[i] >= 0 ? 1 : 0;
      }
      auto add = [&](int a, int b, int c) {
        faces.push_back({a, b, c});
        next_active.push_back(active[f]);
      };
      if (marked == 0) {
        add(F[0], F[1], F[2]);
      } else if (marked == 3) {
        add(F[0], e[0], e[2]);
        add(e[0], F[1], e[1]);
        add(e[2], e[1], F[2]);
        add(e[0], e[1], e[2]);
      } else if (marked == 1) {
        const int i = e[0] >= 0 ? 0 : e[1] >= 0 ? 1 : 2;  // edge F[i] -> F[i+1]
        add(F[i], e[i], F[(i + 2) % 3]);
        add(e[i], F[(i + 1) % 3], F[(i + 2) % 3]);
      } else {
        const int i = e[0] < 0 ? 0 : e[1] < 0 ? 1 : 2;  // the unmarked edge F[i] -> F[i+1]
        const int a = F[i], b = F[(i + 1) % 3], c = F[(i + 2) % 3];
        const int mbc = e[(i + 1) % 3], mca = e[(i + 2) % 3];
        add(mca, mbc, c);
        add(a, b, mbc);
        add(a, mbc, mca);
      }
    }
    m.faces.swap(faces);
    active.swap(next_active);
  }
  m.vertex_scalars.clear();  // per-vertex values (deviation, fusions) do not survive the split
  m.ComputeNormals();
}

std::vector<std::array<int, 3>> FaceNeighbours(const TriangleMesh& model) {
  const std::size_t nf = model.num_faces();
  std::vector<std::array<int, 3>> nbr(nf, {-1, -1, -1});
  std::vector<std::pair<std::uint64_t, int>> edges;
  edges.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) {
      const auto a = static_cast<std::uint64_t>(model.faces[f][i]),
                 b = static_cast<std::uint64_t>(model.faces[f][(i + 1) % 3]);
      edges.emplace_back(std::min(a, b) << 32 | std::max(a, b), static_cast<int>(f) * 3 + i);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    if (edges[i].first != edges[i + 1].first) continue;
    if (i + 2 < edges.size() && edges[i + 2].first == edges[i].first) continue;  // non-manifold: no neighbours
    if (i > 0 && edges[i - 1].first == edges[i].first) continue;
    const int fa = edges[i].second / 3, ea = edges[i].second % 3, fb = edges[i + 1].second / 3,
              eb = edges[i + 1].second % 3;
    nbr[static_cast<std::size_t>(fa)][static_cast<std::size_t>(ea)] = fb;
    nbr[static_cast<std::size_t>(fb)][static_cast<std::size_t>(eb)] = fa;
  }
  return nbr;
}

std::vector<MosaicFace> ChooseViews(const std::vector<std::vector<Candidate>>& cand,
                                    const std::vector<std::array<int, 3>>& nbr, const MosaicOptions& options) {
  const std::size_t nf = cand.size();
  std::vector<MosaicFace> faces(nf, MosaicFace{});
  std::vector<float> best_score(nf, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    MosaicFace& F = faces[f];
    F.candidates = static_cast<int>(cand[f].size());
    for (const Candidate& c : cand[f]) {
      if (c.score > best_score[f]) best_score[f] = c.score, F.view = c.view;
    }
  }
  for (int it = 0; it < options.label_iterations && options.seam_weight > 0; ++it) {
    std::size_t changed = 0;
    for (std::size_t f = 0; f < nf; ++f) {
      if (cand[f].size() < 2) continue;
      double best = 1e300;
      int label = faces[f].view;
      for (const Candidate& c : cand[f]) {
        double e = -std::log(c.score / best_score[f]);
        for (int n : nbr[f]) {
          if (n >= 0 && faces[static_cast<std::size_t>(n)].view >= 0 &&
              faces[static_cast<std::size_t>(n)].view != c.view) {
            e += options.seam_weight;
          }
        }
        if (e < best - 1e-12) best = e, label = c.view;
      }
      if (label != faces[f].view) ++changed, faces[f].view = label;
    }
    if (changed == 0) break;
  }
  return faces;
}

std::vector<ViewWeights> FeatherWeights(const TriangleMesh& model, const std::vector<MosaicFace>& faces,
                                        const MosaicOptions& options) {
  const std::size_t nf = model.num_faces(), nv = model.num_vertices();
  std::vector<ViewWeights> vw(nv);
  std::vector<std::map<int, double>> acc(nv);
  for (std::size_t f = 0; f < nf; ++f) {
    if (faces[f].view < 0) continue;
    const double a = model.FaceArea(static_cast<int>(f));
    for (int i = 0; i < 3; ++i) acc[static_cast<std::size_t>(model.faces[f][i])][faces[f].view] += a;
  }
  for (std::size_t v = 0; v < nv; ++v) vw[v] = Strongest(acc[v]);
  std::vector<std::vector<int>> ring(nv);
  for (const Face& F : model.faces) {
    for (int i = 0; i < 3; ++i) {
      ring[static_cast<std::size_t>(F[i])].push_back(F[(i + 1) % 3]);
      ring[static_cast<std::size_t>(F[i])].push_back(F[(i + 2) % 3]);
    }
  }
  for (auto& r : ring) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  for (int step = 0; step < options.feather_rings; ++step) {
    std::vector<ViewWeights> next(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      std::map<int, double> sum;
      auto add = [&](const ViewWeights& w) {
        for (int i = 0; i < kMaxViewsPerVertex; ++i) {
          if (w.view[static_cast<std::size_t>(i)] >= 0)
            sum[w.view[static_cast<std::size_t>(i)]] += w.weight[static_cast<std::size_t>(i)];
        }
      };
      add(vw[v]);
      for (int n : ring[v]) add(vw[static_cast<std::size_t>(n)]);
      next[v] = Strongest(sum);
    }
    vw.swap(next);
  }
  return vw;
}

}  // namespace mosaic_internal
}  // namespace hull
