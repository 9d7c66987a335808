#include "mapping/shape_detection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>

#include "geometry/point_index.h"
#include "mapping/alpha_shape.h"
#include "mapping/dbscan.h"

namespace hull {
namespace {

// Features closer than this to the camera plane cannot be projected.
constexpr double kMinDepth = 1e-3;

}  // namespace

void AdmitPeakPoints(const std::vector<Eigen::Vector3d>& points, double eps, DbscanResult& db) {
  // The |d| axis of DBSCAN's metric separates an object from the hull
  // around it, but also the top of a narrow peak from its flanks: the top
  // features of a tube-worm tuft stand 3-5 cm above the next ones, 5-8 cm
  // away, and fall out as noise together with the peak.
  std::vector<Eigen::Vector3d> flat;  // clustered points on the image plane (x, y, 0)
  std::vector<int> flat_of;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (db.labels[i] < 0) continue;
    flat.emplace_back(points[i].x(), points[i].y(), 0.0);
    flat_of.push_back(static_cast<int>(i));
  }
  if (flat.empty()) return;
  const PointIndex clustered(flat);
  std::vector<int> joins(points.size(), DbscanResult::kNoise);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (db.labels[i] != DbscanResult::kNoise) continue;
    // The nearest clustered point within eps on the image plane that is lower.
    for (const auto& [k, d2] : clustered.Within(Eigen::Vector3d(points[i].x(), points[i].y(), 0.0), eps)) {
      (void)d2;
      const auto j = static_cast<std::size_t>(flat_of[static_cast<std::size_t>(k)]);
      if (points[j].z() < points[i].z()) {
        joins[i] = db.labels[j];
        break;
      }
    }
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (joins[i] >= 0) db.labels[i] = joins[i];
  }
}

void KeepSeededClusters(const std::vector<char>& seed, int min_seeds, DbscanResult& db) {
  std::vector<int> seeds(static_cast<std::size_t>(db.num_clusters), 0);
  for (std::size_t i = 0; i < db.labels.size(); ++i) {
    if (db.labels[i] >= 0 && seed[i]) ++seeds[static_cast<std::size_t>(db.labels[i])];
  }
  std::vector<int> renumber(static_cast<std::size_t>(db.num_clusters), DbscanResult::kNoise);
  int kept = 0;
  for (std::size_t c = 0; c < seeds.size(); ++c) {
    if (seeds[c] >= min_seeds) renumber[c] = kept++;
  }
  for (int& label : db.labels) {
    if (label >= 0) label = renumber[static_cast<std::size_t>(label)];
  }
  db.num_clusters = kept;
}

namespace {

// Lines 4-11 of Algorithm 1 for one keyframe: its points (every observed
// landmark in front of the camera, into out.points), those clustered (x, y,
// |d|) with their index into out.points and whether each is a seed (above
// tau), and DBSCAN's clusters (peak points admitted), before the
// hysteresis drops unseeded clusters.
struct KeyframeClusters {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> point_of;  // -> out.points
  std::vector<char> seed;     // |d| > tau
  DbscanResult db;
};

KeyframeClusters ClusterKeyframe(const MappingInput& input, int keyframe, const MappingOptions& o,
                                 KeyframeShapes& out) {
  const MappingKeyframe& kf = input.keyframes[static_cast<std::size_t>(keyframe)];
  out.keyframe = keyframe;
  out.id = kf.id;
  const Pose cT_g = kf.x_g_cT.Inverse();
  // Lines 4-10: the points to cluster, (x, y, |d|): those above tau (the
  // seeds) and, with hysteresis (shape_grow_height < tau), those above the
  // lower level that a cluster may grow through.
  const double low = std::min(o.tau, o.shape_grow_height);
  KeyframeClusters c;
  for (const int li : kf.landmarks) {
    const MappingLandmark& l = input.landmarks[static_cast<std::size_t>(li)];
    ShapePoint p;
    p.landmark = li;
    p.p_c = cT_g * l.p_g;
    if (p.p_c.z() < kMinDepth) continue;
    p.pixel = input.camera.top.Project(p.p_c);
    p.deviation = l.deviation;
    if (std::abs(l.deviation) > low) {
      c.points.emplace_back(p.p_c.x(), p.p_c.y(), std::abs(l.deviation));
      c.point_of.push_back(static_cast<int>(out.points.size()));
      c.seed.push_back(std::abs(l.deviation) > o.tau);
    }
    out.points.push_back(p);
  }
  // Line 11: DBSCAN.
  c.db = Dbscan(c.points, o.dbscan_eps, o.dbscan_min_points);
  if (o.fusion_keep_peaks) AdmitPeakPoints(c.points, o.dbscan_eps, c.db);
  return c;
}

bool Hysteresis(const MappingOptions& o) { return std::min(o.tau, o.shape_grow_height) < o.tau; }

// The landmarks of a keyframe's clusters that hold a seed (above tau),
// appended to *list.
void AddSeededClusterLandmarks(const KeyframeShapes& out, const KeyframeClusters& c, std::vector<int>* list) {
  std::vector<char> has_seed(static_cast<std::size_t>(c.db.num_clusters), 0);
  for (std::size_t i = 0; i < c.seed.size(); ++i) {
    if (c.db.labels[i] >= 0 && c.seed[i]) has_seed[static_cast<std::size_t>(c.db.labels[i])] = 1;
  }
  for (std::size_t i = 0; i < c.seed.size(); ++i) {
    if (c.db.labels[i] >= 0 && has_seed[static_cast<std::size_t>(c.db.labels[i])]) {
      list->push_back(out.points[static_cast<std::size_t>(c.point_of[i])].landmark);
    }
  }
}

// Per landmark: held by a seeded cluster of some keyframe (per_keyframe:
// each keyframe's AddSeededClusterLandmarks).
std::vector<char> SeededFrom(const std::vector<std::vector<int>>& per_keyframe, std::size_t num_landmarks) {
  std::vector<char> seeded(num_landmarks, 0);
  for (const std::vector<int>& list : per_keyframe) {
    for (const int li : list) seeded[static_cast<std::size_t>(li)] = 1;
  }
  return seeded;
}

// Lines 11-15 after DBSCAN: the hysteresis keeps the clusters that hold a
// seed (or, seeded, a landmark another keyframe's seeded cluster holds), and
// each kept cluster gets its alpha shape.
KeyframeShapes ShapeClusters(const MappingInput& input, const MappingOptions& o, KeyframeShapes out, KeyframeClusters c,
                             const std::vector<char>* seeded) {
  DbscanResult& db = c.db;
  const std::vector<char>& seed = c.seed;
  const std::vector<int>& cluster_point_of = c.point_of;
  if (Hysteresis(o)) {
    // A cluster is kept when it holds a seed, or (seeded) a landmark that
    // another keyframe's seeded cluster holds.
    std::vector<char> keeps = seed;
    if (seeded) {
      for (std::size_t i = 0; i < keeps.size(); ++i) {
        const int li = out.points[static_cast<std::size_t>(cluster_point_of[i])].landmark;
        if ((*seeded)[static_cast<std::size_t>(li)]) keeps[i] = 1;
      }
    }
    KeepSeededClusters(keeps, 1, db);
  }
  std::vector<std::vector<int>> members(static_cast<std::size_t>(db.num_clusters));
  for (std::size_t i = 0; i < db.labels.size(); ++i) {
    const int c = db.labels[i];
    ShapePoint& p = out.points[static_cast<std::size_t>(cluster_point_of[i])];
    // A point below tau that no kept cluster grew through is not clustered.
    p.cluster = c >= 0 || seed[i] ? c : ShapePoint::kBelowTau;
    if (c >= 0) members[static_cast<std::size_t>(c)].push_back(cluster_point_of[i]);
  }
  // Lines 12-15: an alpha shape per cluster over camera (x, y), lifted by z.
  for (int c = 0; c < db.num_clusters; ++c) {
    const std::vector<int>& m = members[static_cast<std::size_t>(c)];
    std::vector<Eigen::Vector2d> xy;
    xy.reserve(m.size());
    for (const int pi : m) xy.push_back(out.points[static_cast<std::size_t>(pi)].p_c.head<2>());
    std::vector<Face> tris = AlphaShapeTriangles(xy, o.alpha);
    if (tris.empty()) continue;
    // Keep only the vertices the triangles use, in cluster order.
    std::vector<int> local(m.size(), -1);
    for (const Face& f : tris) {
      for (const int v : f) local[static_cast<std::size_t>(v)] = 0;
    }
    DetectedShape s;
    s.cluster = c;
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (local[i] < 0) continue;
      local[i] = static_cast<int>(s.points.size());
      const ShapePoint& p = out.points[static_cast<std::size_t>(m[i])];
      s.points.push_back(m[i]);
      s.vertices_c.push_back(p.p_c);
      s.vertices_g.push_back(input.landmarks[static_cast<std::size_t>(p.landmark)].p_g);
      s.pixels.push_back(p.pixel);
      s.deviation.push_back(p.deviation);
    }
    for (const Face& f : tris) {
      // Counter-clockwise in camera (x, y) has its normal along +z, away from
      // the camera: swap two corners so that it faces the camera.
      const Face t = {local[static_cast<std::size_t>(f[0])], local[static_cast<std::size_t>(f[2])],
                      local[static_cast<std::size_t>(f[1])]};
      s.triangles.push_back(t);
      const Eigen::Vector3d& a = s.vertices_c[static_cast<std::size_t>(t[0])];
      s.area += 0.5 * (s.vertices_c[static_cast<std::size_t>(t[1])] - a)
                          .cross(s.vertices_c[static_cast<std::size_t>(t[2])] - a)
                          .norm();
    }
    out.shapes.push_back(std::move(s));
  }
  return out;
}

}  // namespace

std::vector<char> SeededLandmarks(const MappingInput& input, const MappingOptions& o) {
  if (!Hysteresis(o)) return std::vector<char>(input.landmarks.size(), 0);
  const int n = static_cast<int>(input.keyframes.size());
  std::vector<std::vector<int>> per_keyframe(static_cast<std::size_t>(n));
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 16), [&](const tbb::blocked_range<int>& r) {
    for (int k = r.begin(); k != r.end(); ++k) {
      KeyframeShapes out;
      const KeyframeClusters c = ClusterKeyframe(input, k, o, out);
      AddSeededClusterLandmarks(out, c, &per_keyframe[static_cast<std::size_t>(k)]);
    }
  });
  return SeededFrom(per_keyframe, input.landmarks.size());
}

KeyframeShapes DetectShapes(const MappingInput& input, int keyframe, const MappingOptions& o,
                            const std::vector<char>* seeded) {
  KeyframeShapes out;
  KeyframeClusters c = ClusterKeyframe(input, keyframe, o, out);
  return ShapeClusters(input, o, std::move(out), std::move(c), seeded);
}

std::vector<KeyframeShapes> DetectAllShapes(const MappingInput& input, const MappingOptions& options,
                                            Progress& progress) {
  const int n = static_cast<int>(input.keyframes.size());
  std::vector<KeyframeShapes> out(static_cast<std::size_t>(n));
  std::vector<KeyframeClusters> clusters(static_cast<std::size_t>(n));
  std::atomic<bool> cancelled{false};
  // Each keyframe's stage in parallel, stopping when progress asks.
  auto each_keyframe = [&](const std::function<void(std::size_t)>& f) {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 16), [&](const tbb::blocked_range<int>& r) {
      if (cancelled.load(std::memory_order_relaxed) || progress.Cancelled()) {
        cancelled = true;
        return;
      }
      for (int k = r.begin(); k != r.end(); ++k) f(static_cast<std::size_t>(k));
    });
    progress.ThrowIfCancelled();
    if (cancelled) throw Cancelled();
  };
  // DBSCAN once per keyframe; the seeds across views read every keyframe's
  // clusters before any is shaped.
  each_keyframe([&](std::size_t k) { clusters[k] = ClusterKeyframe(input, static_cast<int>(k), options, out[k]); });
  std::vector<char> seeded;
  if (options.shape_seed_across_views) {
    std::vector<std::vector<int>> per_keyframe(static_cast<std::size_t>(n));
    if (Hysteresis(options)) {
      for (std::size_t k = 0; k < clusters.size(); ++k)
        AddSeededClusterLandmarks(out[k], clusters[k], &per_keyframe[k]);
    }
    seeded = SeededFrom(per_keyframe, input.landmarks.size());
  }
  const std::vector<char>* seeded_ptr = options.shape_seed_across_views ? &seeded : nullptr;
  each_keyframe([&](std::size_t k) {
    out[k] = ShapeClusters(input, options, std::move(out[k]), std::move(clusters[k]), seeded_ptr);
  });
  return out;
}

}  // namespace hull
