#include "mapping/shape_fusion.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <tuple>

#include "geometry/point_index.h"
#include "mapping/shape_raycast.h"

namespace hull {
namespace {

// Keyframes whose hits are gathered in parallel before being applied in order.
constexpr std::size_t kChunk = 128;

struct Hit {
  int vertex;
  Eigen::Vector3d p;
};

// Lines 8-10 for one vertex, shared by both versions so that they compute
// bit-identical points: the vertex must be within the fusion radius and face
// the camera; the ray from the camera centre through it, in the camera
// frame, is cast by `cast` (FirstShapeHit or ShapeFootprint::Hit).
template <typename Cast>
bool RayThroughVertex(const Pose& cam, const Pose& cam_inv, const Eigen::Vector3d& v, const Eigen::Vector3d& normal,
                      double radius2, Cast&& cast, Eigen::Vector3d* p) {
  const Eigen::Vector3d d = v - cam.translation();
  if (!(d.squaredNorm() <= radius2)) return false;
  if (!(normal.dot(d) < 0)) return false;  // faces away from the camera
  const Eigen::Vector3d dir = cam_inv * v;
  const ShapeHit h = cast(dir);
  if (!h.hit) return false;
  *p = cam * (h.t * dir);
  return true;
}

// The same for the fusion along the vertex normal: the segment from the
// vertex's normal line `reach` outside the vertex to `reach` inside it, in
// the camera frame, is cast by `cast` (FirstShapeHitOnSegment or
// ShapeFootprint::SegmentHit); the first hit from outside is the line's
// outermost point on the shape (what the camera sees of it).
template <typename Cast>
bool NormalThroughVertex(const Pose& cam, const Pose& cam_inv, const Eigen::Vector3d& v, const Eigen::Vector3d& normal,
                         double radius2, double reach, Cast&& cast, Eigen::Vector3d* p) {
  const Eigen::Vector3d d = v - cam.translation();
  if (!(d.squaredNorm() <= radius2)) return false;
  if (!(normal.dot(d) < 0)) return false;  // faces away from the camera
  const Eigen::Vector3d n_c = cam_inv.Rotate(normal);
  const Eigen::Vector3d outer = cam_inv * v + reach * n_c;
  const Eigen::Vector3d dir = -n_c;
  const ShapeHit h = cast(outer, dir, 2 * reach);
  if (!h.hit) return false;
  *p = cam * (outer + h.t * dir);
  return true;
}

// Bounding sphere (in the camera frame) of a shape's vertices.
void ShapeSphere(const DetectedShape& s, Eigen::Vector3d* centre, double* radius) {
  Eigen::AlignedBox3d box;
  for (const auto& v : s.vertices_c) box.extend(v);
  *centre = box.center();
  *radius = 0;
  for (const auto& v : s.vertices_c) *radius = std::max(*radius, (v - *centre).norm());
}

FusionResult Finish(const TriangleMesh& prior, const std::vector<std::vector<Eigen::Vector3d>>& hits,
                    const FusionRule& rule, std::size_t total) {
  FusionResult r;
  r.vertices = prior.vertices;
  r.count.assign(prior.num_vertices(), 0);
  r.support.assign(prior.num_vertices(), 0);
  r.hits = total;
  tbb::parallel_for(std::size_t(0), hits.size(), [&](std::size_t i) {
    if (hits[i].empty()) return;
    r.count[i] = static_cast<int>(hits[i].size());
    r.vertices[i] = CombineHits(hits[i], prior.vertices[i], prior.vertex_normals[i], rule, &r.support[i]);
  });
  return r;
}

}  // namespace

Eigen::Vector3d CombineHits(const std::vector<Eigen::Vector3d>& hits, const Eigen::Vector3d& prior,
                            const Eigen::Vector3d& normal, const FusionRule& rule, int* support) {
  *support = 0;
  if (hits.empty()) return prior;
  if (!rule.keep_peaks) {
    MovingAverage a;
    for (const auto& p : hits) a.Add(p);
    *support = a.n;
    return a.value;
  }
  const int k = std::max(1, rule.support);
  if (static_cast<int>(hits.size()) < k) return prior;
  std::vector<double> h(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) h[i] = (hits[i] - prior).dot(normal);
  std::vector<double> sorted = h;
  std::nth_element(sorted.begin(), sorted.begin() + (k - 1), sorted.end(), std::greater<double>());
  const double hk = sorted[static_cast<std::size_t>(k - 1)];
  MovingAverage a;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (h[i] < hk - rule.band) continue;
    ++*support;
    if (h[i] <= hk) a.Add(hits[i]);
  }
  return a.value;
}

int SnapVerticesToFeatures(TriangleMesh& prior, const PointIndex& prior_index, const MeshIndex& cad,
                           const std::vector<KeyframeShapes>& shapes, const Pose& x_Mg, int support, double min_height,
                           double max_move, const std::vector<Eigen::Vector3d>& apex_feet,
                           std::vector<int>* apex_vertex, const std::vector<PeakFeature>& peaks,
                           std::vector<int>* peak_vertex) {
  // Per landmark: the keyframes whose shapes hold it, its deviation and
  // position (in g).
  struct Feature {
    int keyframes = 0;
    double deviation = 0;
    Eigen::Vector3d p_g = Eigen::Vector3d::Zero();
  };
  std::map<int, Feature> features;
  for (const KeyframeShapes& ks : shapes) {
    for (const DetectedShape& sh : ks.shapes) {
      for (std::size_t j = 0; j < sh.points.size(); ++j) {
        if (!(sh.deviation[j] > min_height)) continue;
        Feature& f = features[ks.points[static_cast<std::size_t>(sh.points[j])].landmark];
        ++f.keyframes;
        f.deviation = sh.deviation[j];
        f.p_g = sh.vertices_g[j];
      }
    }
  }
  // (-deviation, landmark, peak feature or -1): highest first.
  std::vector<std::tuple<double, int, int>> order;
  for (const auto& [l, f] : features) {
    if (f.keyframes >= support) order.emplace_back(-f.deviation, l, -1);
  }
  for (std::size_t i = 0; i < peaks.size(); ++i)
    order.emplace_back(-peaks[i].deviation, peaks[i].landmark, static_cast<int>(i));
  std::sort(order.begin(), order.end());
  // Faces per vertex (CSR).
  const std::size_t nv = prior.num_vertices();
  std::vector<int> start(nv + 1, 0), faces_of;
  for (const Face& f : prior.faces) {
    for (const int v : f) ++start[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  faces_of.assign(static_cast<std::size_t>(start[nv]), 0);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < prior.num_faces(); ++f) {
      for (const int v : prior.faces[f])
        faces_of[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(f);
    }
  }
  auto normal = [&](int f) {
    const Face& F = prior.faces[static_cast<std::size_t>(f)];
    const Eigen::Vector3d& a = prior.vertices[static_cast<std::size_t>(F[0])];
    return Eigen::Vector3d(
        (prior.vertices[static_cast<std::size_t>(F[1])] - a).cross(prior.vertices[static_cast<std::size_t>(F[2])] - a));
  };
  const double cos_max_turn = std::cos(M_PI / 4);
  std::vector<char> moved(nv, 0);
  int count = 0;
  // Moves the vertex nearest `foot` onto it; returns it, or -1.
  auto snap = [&](const Eigen::Vector3d& foot) -> int {
    const auto [v, d2] = prior_index.NearestOne(foot);  // squared distance
    if (v < 0 || moved[static_cast<std::size_t>(v)] || !(d2 <= max_move * max_move)) return -1;
    const std::size_t vi = static_cast<std::size_t>(v);
    const Eigen::Vector3d old = prior.vertices[vi];
    std::vector<Eigen::Vector3d> before;
    for (int k = start[vi]; k < start[vi + 1]; ++k) before.push_back(normal(faces_of[static_cast<std::size_t>(k)]));
    prior.vertices[vi] = foot;
    bool ok = true;
    for (int k = start[vi]; k < start[vi + 1] && ok; ++k) {
      const Eigen::Vector3d& b = before[static_cast<std::size_t>(k - start[vi])];
      const Eigen::Vector3d a = normal(faces_of[static_cast<std::size_t>(k)]);
      ok = a.dot(b) > cos_max_turn * a.norm() * b.norm();
    }
    if (!ok) {
      prior.vertices[vi] = old;
      return -1;
    }
    moved[vi] = 1;
    ++count;
    return v;
  };
  if (apex_vertex) apex_vertex->assign(apex_feet.size(), -1);
  for (std::size_t i = 0; i < apex_feet.size(); ++i) {
    const int v = snap(apex_feet[i]);
    if (apex_vertex) (*apex_vertex)[i] = v;
  }
  if (peak_vertex) peak_vertex->assign(peaks.size(), -1);
  for (const auto& [neg_deviation, l, peak] : order) {
    (void)neg_deviation;
    if (peak < 0) {
      snap(cad.Closest(x_Mg * features.at(l).p_g).point);
      continue;
    }
    const int v = snap(peaks[static_cast<std::size_t>(peak)].foot);
    if (peak_vertex) (*peak_vertex)[static_cast<std::size_t>(peak)] = v;
  }
  prior.ComputeNormals();
  return count;
}

std::vector<PeakFeature> FindPeakFeatures(const std::vector<KeyframeShapes>& shapes,
                                          const std::vector<Eigen::Vector3d>& landmarks_M,
                                          const std::vector<double>& deviation, const MeshIndex& cad, double tau,
                                          double min_height, double eps, int support) {
  // Per landmark standing above min_height: the keyframes where it is a
  // point to cluster above tau (a seed), and those whose shapes hold it.
  std::map<int, std::pair<int, int>> views;
  for (const KeyframeShapes& ks : shapes) {
    std::vector<char> in_shape(ks.points.size(), 0);
    for (const DetectedShape& sh : ks.shapes) {
      for (const int pi : sh.points) in_shape[static_cast<std::size_t>(pi)] = 1;
    }
    for (std::size_t i = 0; i < ks.points.size(); ++i) {
      const ShapePoint& p = ks.points[i];
      if (!(p.deviation > min_height)) continue;
      auto& [seen, shaped] = views[p.landmark];
      seen += p.deviation > tau;
      shaped += in_shape[i];
    }
  }
  // The features the fusion reaches (shape vertices in `support` keyframes),
  // by their feet: the level the shapes reach around a candidate.
  std::vector<Eigen::Vector3d> supported_feet;
  std::vector<double> supported_height;
  for (const auto& [l, v] : views) {
    if (v.second < support) continue;
    supported_feet.push_back(cad.Closest(landmarks_M[static_cast<std::size_t>(l)]).point);
    supported_height.push_back(deviation[static_cast<std::size_t>(l)]);
  }
  std::unique_ptr<PointIndex> supported;
  if (!supported_feet.empty()) supported = std::make_unique<PointIndex>(supported_feet);
  std::vector<PeakFeature> candidates;
  for (const auto& [l, v] : views) {
    if (v.first < support || v.second >= support) continue;
    const Eigen::Vector3d foot = cad.Closest(landmarks_M[static_cast<std::size_t>(l)]).point;
    // It must stand above every supported feature within eps: a peak the
    // shapes missed, not a flank feature below what they reach.
    double level = -std::numeric_limits<double>::infinity();
    if (supported) {
      for (const auto& [k, d2] : supported->Within(foot, eps, false)) {
        (void)d2;
        level = std::max(level, supported_height[static_cast<std::size_t>(k)]);
      }
    }
    if (!(deviation[static_cast<std::size_t>(l)] > level)) continue;
    PeakFeature f;
    f.landmark = l;
    f.deviation = deviation[static_cast<std::size_t>(l)];
    f.foot = foot;
    f.views = v.first;
    f.shape_views = v.second;
    candidates.push_back(f);
  }
  // Confirmed by the nearest other candidate within eps (feet on the CAD).
  std::vector<PeakFeature> out;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double best = eps * eps;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      const double d2 = (candidates[j].foot - candidates[i].foot).squaredNorm();
      if (j == i || !(d2 <= best)) continue;
      best = d2;
      candidates[i].confirmed_by = candidates[j].landmark;
    }
    if (candidates[i].confirmed_by >= 0) out.push_back(candidates[i]);
  }
  std::sort(out.begin(), out.end(), [](const PeakFeature& a, const PeakFeature& b) {
    return a.deviation != b.deviation ? a.deviation > b.deviation : a.landmark < b.landmark;
  });
  return out;
}

int RaisePeakFeatures(const TriangleMesh& prior, const std::vector<PeakFeature>& peaks,
                      const std::vector<int>& peak_vertex, double min_height, FusionResult& fused,
                      std::vector<char>* raised) {
  if (raised) raised->assign(peaks.size(), 0);
  // The fusion's height of a vertex along its prior normal (0: not fused).
  auto height = [&](std::size_t v) {
    return fused.support[v] > 0 ? (fused.vertices[v] - prior.vertices[v]).dot(prior.vertex_normals[v]) : 0.0;
  };
  // Judged on the fusion's result alone, before any vertex rises, so that the
  // peaks do not depend on each other's order.
  std::vector<char> joins(peaks.size(), 0);
  std::map<int, std::size_t> peak_at;  // vertex -> peak (SnapVerticesToFeatures moves each vertex once)
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    if (peak_vertex[i] >= 0) peak_at[peak_vertex[i]] = i;
  }
  for (const Face& f : prior.faces) {
    for (const int v : f) {
      const auto it = peak_at.find(v);
      if (it == peak_at.end()) continue;
      for (const int n : f) {
        if (n != v && height(static_cast<std::size_t>(n)) > min_height) joins[it->second] = 1;
      }
    }
  }
  int count = 0;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const int v = peak_vertex[i];
    if (v < 0 || !joins[i]) continue;
    const std::size_t vi = static_cast<std::size_t>(v);
    if (!(height(vi) < peaks[i].deviation)) continue;
    fused.vertices[vi] = prior.vertices[vi] + peaks[i].deviation * prior.vertex_normals[vi];
    fused.support[vi] = std::max(fused.support[vi], peaks[i].views);
    fused.count[vi] = std::max(fused.count[vi], peaks[i].views);
    if (raised) (*raised)[i] = 1;
    ++count;
  }
  return count;
}

FusionResult FuseShapes(const TriangleMesh& prior, const PointConeTree& tree, const std::vector<Pose>& x_M_cT,
                        const std::vector<KeyframeShapes>& shapes, double radius, const FusionRule& rule,
                        Progress& progress) {
  std::vector<std::vector<Eigen::Vector3d>> per_vertex(prior.num_vertices());
  std::size_t total = 0;
  const double radius2 = radius * radius;
  std::vector<std::vector<Hit>> hits(kChunk);
  for (std::size_t begin = 0; begin < shapes.size(); begin += kChunk) {
    progress.ThrowIfCancelled();
    const std::size_t end = std::min(shapes.size(), begin + kChunk);
    tbb::parallel_for(std::size_t(begin), end, [&](std::size_t k) {
      std::vector<Hit>& out = hits[k - begin];
      out.clear();
      const KeyframeShapes& ks = shapes[k];
      const Pose& cam = x_M_cT[static_cast<std::size_t>(ks.keyframe)];
      const Pose inv = cam.Inverse();
      for (const DetectedShape& s : ks.shapes) {
        const ShapeFootprint fp(s);
        const std::size_t first = out.size();
        if (rule.along_normal) {
          // A vertex whose normal segment meets the shape lies within the
          // reach of a point of it.
          const double reach = NormalReach(s);
          Eigen::Vector3d centre;
          double r = 0;
          ShapeSphere(s, &centre, &r);
          const double ball = (r + reach) * (1 + 1e-9) + 1e-9;
          const Eigen::Vector3d none = Eigen::Vector3d::UnitZ();
          tree.Query(cam * centre, ball, none, 0, 1, false, [&](int i) {
            Eigen::Vector3d p;
            if (NormalThroughVertex(
                    cam, inv, prior.vertices[static_cast<std::size_t>(i)],
                    prior.vertex_normals[static_cast<std::size_t>(i)], radius2, reach,
                    [&](const Eigen::Vector3d& o, const Eigen::Vector3d& dir, double t_max) {
                      return fp.SegmentHit(o, dir, t_max);
                    },
                    &p)) {
              out.push_back({i, p});
            }
          });
        } else {
          const Eigen::Vector3d axis = cam.Rotate(fp.axis());
          tree.Query(cam.translation(), radius, axis, fp.cos_half_angle(), fp.sin_half_angle(), fp.narrow(),
                     [&](int i) {
                       Eigen::Vector3d p;
                       if (RayThroughVertex(
                               cam, inv, prior.vertices[static_cast<std::size_t>(i)],
                               prior.vertex_normals[static_cast<std::size_t>(i)], radius2,
                               [&](const Eigen::Vector3d& dir) { return fp.Hit(dir); }, &p)) {
                         out.push_back({i, p});
                       }
                     });
        }
        // Within a shape each vertex is hit once; sorting only fixes the order
        // in which equal work is done, not the result.
        std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                  [](const Hit& a, const Hit& b) { return a.vertex < b.vertex; });
      }
    });
    for (std::size_t k = begin; k < end; ++k) {
      for (const Hit& h : hits[k - begin]) {
        per_vertex[static_cast<std::size_t>(h.vertex)].push_back(h.p);
        ++total;
      }
    }
    progress.Update(static_cast<double>(end) / static_cast<double>(shapes.size()), "fusing shapes into the model");
  }
  return Finish(prior, per_vertex, rule, total);
}

FusionResult FuseShapesBruteForce(const TriangleMesh& prior, const std::vector<Pose>& x_M_cT,
                                  const std::vector<KeyframeShapes>& shapes, double radius, const FusionRule& rule) {
  std::vector<std::vector<Eigen::Vector3d>> per_vertex(prior.num_vertices());
  std::size_t total = 0;
  const PointIndex index(prior.vertices);
  const double radius2 = radius * radius;
  for (const KeyframeShapes& ks : shapes) {  // line 2
    const Pose& cam = x_M_cT[static_cast<std::size_t>(ks.keyframe)];
    const Pose inv = cam.Inverse();
    // Line 5: nearby vertices (a little more than the radius; the exact test
    // is RayThroughVertex's).
    std::vector<int> nearby;
    for (const auto& [i, d2] : index.Within(cam.translation(), radius * (1 + 1e-9) + 1e-9)) {
      (void)d2;
      nearby.push_back(i);
    }
    std::sort(nearby.begin(), nearby.end());
    for (const DetectedShape& s : ks.shapes) {  // line 6
      const double reach = NormalReach(s);
      for (const int i : nearby) {  // line 7
        const Eigen::Vector3d& v = prior.vertices[static_cast<std::size_t>(i)];
        const Eigen::Vector3d& n = prior.vertex_normals[static_cast<std::size_t>(i)];
        Eigen::Vector3d p;
        const bool hit = rule.along_normal ? NormalThroughVertex(
                                                 cam, inv, v, n, radius2, reach,
                                                 [&](const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                                                     double t_max) { return FirstShapeHitOnSegment(s, o, dir, t_max); },
                                                 &p)
                                           : RayThroughVertex(
                                                 cam, inv, v, n, radius2,
                                                 [&](const Eigen::Vector3d& dir) { return FirstShapeHit(s, dir); }, &p);
        if (hit) {
          per_vertex[static_cast<std::size_t>(i)].push_back(p);  // line 11
          ++total;
        }
      }
    }
  }
  return Finish(prior, per_vertex, rule, total);
}

}  // namespace hull
