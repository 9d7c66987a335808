#include "mapping/survey_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "base/error.h"
#include "geometry/mesh_index.h"
#include "geometry/point_index.h"
#include "geometry/vertex_regions.h"

namespace hull {
namespace {

const std::vector<double>& Deviation(const TriangleMesh& m, const char* which) {
  const std::vector<double>* d = m.FindScalar("deviation");
  if (!d || d->size() != m.num_vertices()) {
    throw std::invalid_argument(std::string("CompareSurveys: model ") + which + " has no per-vertex deviation");
  }
  return *d;
}

double SigmaAt(const std::vector<double>* sigma, std::size_t i) {
  return sigma && i < sigma->size() ? (*sigma)[i] : std::numeric_limits<double>::quiet_NaN();
}

// A model vertex's detected object (index into the objects; -1: none).
int ObjectAt(const std::vector<int>& object_of, int vertex) {
  return vertex >= 0 && static_cast<std::size_t>(vertex) < object_of.size()
             ? object_of[static_cast<std::size_t>(vertex)]
             : -1;
}

// Which detected object each vertex of a model belongs to (-1: none): the
// object's own vertices where the results list them (objects.json
// "vertices"). Objects read without them (results written before the
// lists) get the connected regions (over the model's edges) of the other
// vertices at least min_height high whose mean foot lies nearest their
// centroid, within max_radius: the footprints as the object detection made
// them, whatever their shape (a ring of fouling's centroid is bare hull).
std::vector<int> ObjectOfVertex(const TriangleMesh& model, const std::vector<DetectedObject>& objects,
                                const std::vector<double>& dev, const std::vector<Eigen::Vector3d>& feet,
                                double max_radius, double min_height) {
  std::vector<int> of(feet.size(), -1);
  std::vector<std::size_t> unlisted;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    if (objects[k].vertices.empty()) {
      unlisted.push_back(k);
      continue;
    }
    for (const int v : objects[k].vertices) {
      if (v >= 0 && static_cast<std::size_t>(v) < of.size() && of[static_cast<std::size_t>(v)] < 0) {
        of[static_cast<std::size_t>(v)] = static_cast<int>(k);
      }
    }
  }
  if (unlisted.empty()) return of;
  const std::size_t n = feet.size();
  const VertexRegions regions = ConnectedVertexRegions(model, [&](int v) {
    return of[static_cast<std::size_t>(v)] < 0 && dev[static_cast<std::size_t>(v)] >= min_height;
  });
  const std::size_t nr = static_cast<std::size_t>(regions.num_regions);
  std::vector<Eigen::Vector3d> sum(nr, Eigen::Vector3d::Zero());
  std::vector<int> count(nr, 0);
  for (std::size_t v = 0; v < n; ++v) {
    const int r = regions.region_of[v];
    if (r < 0) continue;
    sum[static_cast<std::size_t>(r)] += feet[v];
    ++count[static_cast<std::size_t>(r)];
  }
  std::vector<int> region_object(nr, -1);
  for (std::size_t r = 0; r < nr; ++r) {
    const Eigen::Vector3d mean = sum[r] / count[r];
    double best = max_radius;
    for (const std::size_t k : unlisted) {
      const double d = (objects[k].centroid_m - mean).norm();
      if (d <= best) {
        best = d;
        region_object[r] = static_cast<int>(k);
      }
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    const int r = regions.region_of[v];
    if (r >= 0) of[v] = region_object[static_cast<std::size_t>(r)];
  }
  return of;
}

struct Peak {
  std::size_t vertex;
  int object;
  bool top;  // the object's highest vertex
};

// The peaks of a map's objects: every object vertex with no higher vertex
// (ties: none of a lower index) whose foot lies within `spacing` of its own,
// and every object's highest vertex. Vertices without a finite height are
// none.
std::vector<Peak> ObjectPeaks(const std::vector<double>& dev, const std::vector<int>& object_of,
                              const std::vector<Eigen::Vector3d>& feet, const PointIndex& index,
                              std::size_t num_objects, double spacing) {
  std::vector<Peak> peaks;
  std::vector<int> top(num_objects, -1);
  for (std::size_t v = 0; v < object_of.size(); ++v) {
    const int k = object_of[v];
    if (k < 0 || !std::isfinite(dev[v])) continue;
    int& t = top[static_cast<std::size_t>(k)];
    if (t < 0 || dev[v] > dev[static_cast<std::size_t>(t)]) t = static_cast<int>(v);
    bool highest = true;
    for (const auto& hit : index.Within(feet[v], spacing, false)) {
      const std::size_t j = static_cast<std::size_t>(hit.first);
      if (dev[j] > dev[v] || (dev[j] == dev[v] && j < v)) {
        highest = false;
        break;
      }
    }
    if (highest) peaks.push_back({v, k, false});
  }
  for (std::size_t k = 0; k < num_objects; ++k) {
    if (top[k] < 0) continue;
    const std::size_t v = static_cast<std::size_t>(top[k]);
    const auto it = std::find_if(peaks.begin(), peaks.end(), [&](const Peak& p) { return p.vertex == v; });
    if (it != peaks.end()) {
      it->top = true;
    } else {
      peaks.push_back({v, static_cast<int>(k), true});
    }
  }
  return peaks;
}

// The highest height of a model within r of c (its vertices' feet); where it
// has no vertex that close (a coarse stretch nothing was fused into), its
// nearest vertex's.
struct DiscMax {
  double h = 0;
  int vertex = -1;
};
DiscMax MaxOver(const PointIndex& at, const std::vector<double>& dev, const Eigen::Vector3d& c, double r) {
  DiscMax m;
  m.h = -std::numeric_limits<double>::infinity();
  for (const auto& hit : at.Within(c, r, false)) {
    const double h = dev[static_cast<std::size_t>(hit.first)];
    if (h > m.h || (h == m.h && hit.first < m.vertex)) {
      m.h = h;
      m.vertex = hit.first;
    }
  }
  if (m.vertex >= 0) return m;
  m.vertex = at.NearestOne(c).first;
  m.h = m.vertex >= 0 ? dev[static_cast<std::size_t>(m.vertex)] : 0.0;
  return m;
}

}  // namespace

void SurveyCompareOptions::Check() const {
  if (!(std::isfinite(match_radius) && match_radius > 0)) throw OptionError("match_radius", "must be positive (m)");
  if (!(std::isfinite(change_threshold) && change_threshold > 0)) {
    throw OptionError("change_threshold", "must be positive (m)");
  }
  if (!(std::isfinite(significance_k) && significance_k > 0)) throw OptionError("significance_k", "must be positive");
  if (!(std::isfinite(peak_spacing) && peak_spacing > 0)) throw OptionError("peak_spacing", "must be positive (m)");
  if (!(std::isfinite(peak_reach) && peak_reach > 0 && peak_reach <= match_radius)) {
    throw OptionError("peak_reach", "must be positive (m) and at most match_radius");
  }
  if (!(std::isfinite(max_misplacement) && max_misplacement > 0)) {
    throw OptionError("max_misplacement", "must be positive (m)");
  }
}

const char* ObjectChangeKindName(ObjectChangeKind k) {
  switch (k) {
    case ObjectChangeKind::kNew:
      return "new";
    case ObjectChangeKind::kRemoved:
      return "removed";
    case ObjectChangeKind::kGrown:
      return "grown";
    case ObjectChangeKind::kShrunk:
      return "shrunk";
    case ObjectChangeKind::kUnchanged:
      return "unchanged";
  }
  return "?";
}

SurveyComparison CompareSurveys(const TriangleMesh& cad, const TriangleMesh& model_a,
                                const std::vector<DetectedObject>& objects_a, const TriangleMesh& model_b,
                                const std::vector<DetectedObject>& objects_b, const SurveyCompareOptions& o) {
  NullProgress progress;
  return CompareSurveys(cad, model_a, objects_a, model_b, objects_b, o, progress);
}

SurveyComparison CompareSurveys(const TriangleMesh& cad, const TriangleMesh& model_a,
                                const std::vector<DetectedObject>& objects_a, const TriangleMesh& model_b,
                                const std::vector<DetectedObject>& objects_b, const SurveyCompareOptions& o,
                                Progress& progress) {
  o.Check();
  const std::vector<double>& dev_a = Deviation(model_a, "A");
  const std::vector<double>& dev_b = Deviation(model_b, "B");
  const std::vector<double>* sigma_a = model_a.FindScalar("sigma");
  const std::vector<double>* sigma_b = model_b.FindScalar("sigma");
  TriangleMesh cad_copy = cad;
  cad_copy.ComputeNormals();
  const MeshIndex index(cad_copy);

  // Each height field keyed by where its vertices stand on the CAD (their
  // feet), B's first on its own placement.
  constexpr std::size_t kChunk = 4096;
  const std::size_t na = model_a.num_vertices(), nb = model_b.num_vertices();
  const double total = static_cast<double>(na + 2 * nb) + 1.0;
  std::size_t done = 0;
  auto place = [&](const TriangleMesh& m, const Pose& x, const char* what, std::vector<Eigen::Vector3d>* normals) {
    std::vector<Eigen::Vector3d> feet(m.num_vertices());
    if (normals) normals->resize(m.num_vertices());
    for (std::size_t i = 0; i < feet.size(); ++i, ++done) {
      if (i % kChunk == 0) {
        progress.ThrowIfCancelled();
        progress.Update(static_cast<double>(done) / total, what);
      }
      const ClosestPoint c = index.Closest(x * m.vertices[i]);
      feet[i] = c.point;
      if (normals) (*normals)[i] = cad_copy.face_normals[static_cast<std::size_t>(c.face)];
    }
    return feet;
  };
  std::vector<Eigen::Vector3d> normals_a, normals_b;
  const std::vector<Eigen::Vector3d> feet_a = place(model_a, Pose(), "placing survey A's model on the CAD", &normals_a);
  const PointIndex a_index(feet_a);
  const std::vector<Eigen::Vector3d> own_feet_b =
      place(model_b, Pose(), "placing survey B's model on the CAD", &normals_b);
  const PointIndex own_b_index(own_feet_b);

  // Each map's peaks: the highest vertex of every detected object and each
  // other local maximum of an object (no higher vertex within peak_spacing).
  // An object's change is read at its peaks, not as its max height: two maps
  // split and join touching lumps differently, and a joined object's max
  // stands on one lump only (docs/mapping.md, "Change between two surveys").
  const std::vector<int> object_of_a =
      ObjectOfVertex(model_a, objects_a, dev_a, feet_a, o.match_radius, o.change_threshold);
  const std::vector<int> object_of_b =
      ObjectOfVertex(model_b, objects_b, dev_b, own_feet_b, o.match_radius, o.change_threshold);
  const std::vector<Peak> peaks_a = ObjectPeaks(dev_a, object_of_a, feet_a, a_index, objects_a.size(), o.peak_spacing);
  const std::vector<Peak> peaks_b =
      ObjectPeaks(dev_b, object_of_b, own_feet_b, own_b_index, objects_b.size(), o.peak_spacing);

  // B's map registered to A's by the objects' tops (their feet and the
  // CAD's normals there), one per object: a lump's top stands where it stood
  // whatever each map's object detection made of touching lumps, which
  // moves objects' centroids by decimetres (the top of an object that joins
  // lumps is one of theirs); one per object, so that the noise peaks of a
  // flat top do not outvote the objects.
  SurveyComparison out;
  SurveyRegistrationOptions ro;
  ro.match_radius = o.peak_spacing;
  ro.max_offset = o.max_misplacement;
  if (o.register_surveys) {
    auto tops = [](const std::vector<Peak>& peaks, const std::vector<Eigen::Vector3d>& feet,
                   const std::vector<Eigen::Vector3d>& normals) {
      std::vector<DetectedObject> points;
      for (const Peak& p : peaks) {
        if (!p.top) continue;
        DetectedObject t;
        t.centroid_m = feet[p.vertex];
        t.normal_m = normals[p.vertex];
        points.push_back(std::move(t));
      }
      return points;
    };
    out.registration = RegisterSurveys(tops(peaks_a, feet_a, normals_a), tops(peaks_b, own_feet_b, normals_b), ro);
  }
  const Pose& x_ab = out.registration.a_from_b;  // B's map placed on A's
  const std::vector<Eigen::Vector3d> feet_b =
      out.registration.registered ? place(model_b, x_ab, "measuring the change on survey B's model", nullptr)
                                  : own_feet_b;
  const PointIndex b_index(feet_b);
  out.model = model_b;
  std::vector<double> change(nb), sigma(nb), significant(nb, 0.0);
  for (std::size_t i = 0; i < nb; ++i) {
    const auto nearest = a_index.NearestOne(feet_b[i]);
    const std::size_t j = static_cast<std::size_t>(std::max(0, nearest.first));
    change[i] = dev_b[i] - dev_a[j];
    const double sa = SigmaAt(sigma_a, j), sb = SigmaAt(sigma_b, i);
    sigma[i] = std::sqrt(sa * sa + sb * sb);
    if (std::isfinite(sigma[i]) && std::abs(change[i]) > o.significance_k * sigma[i]) {
      significant[i] = 1;
      ++out.significant_vertices;
    }
  }
  out.model.SetScalar("change", change);
  out.model.SetScalar("change_sigma", sigma);
  out.model.SetScalar("change_significant", significant);

  // The disc about a peak in which both maps' heights are read: the other
  // map's view of the same top may stand this far off (twice the
  // registration's residual). Where the registration was asked for but
  // neither found a motion nor found the maps in place (fewer than 3 tops in
  // common either way), they may stand apart by anything: match_radius.
  const bool in_place =
      out.registration.registered || !o.register_surveys || out.registration.identity_inliers >= ro.min_inliers;
  const double reach = in_place ? std::min(o.peak_reach + 2 * out.registration.rms, o.match_radius) : o.match_radius;
  out.reach = reach;

  // One site per peak of B and per peak of A, a pair of peaks within reach
  // of each other (closest first) being one site.
  struct PeakPair {
    double d;
    std::size_t a, b;
  };
  std::vector<PeakPair> pairs;
  std::vector<int> peak_at_b(nb, -1);
  for (std::size_t b = 0; b < peaks_b.size(); ++b) peak_at_b[peaks_b[b].vertex] = static_cast<int>(b);
  for (std::size_t a = 0; a < peaks_a.size(); ++a) {
    for (const auto& hit : b_index.Within(feet_a[peaks_a[a].vertex], reach, false)) {
      const int b = peak_at_b[static_cast<std::size_t>(hit.first)];
      if (b >= 0) pairs.push_back({hit.second, a, static_cast<std::size_t>(b)});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const PeakPair& x, const PeakPair& y) {
    if (x.d != y.d) return x.d < y.d;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  std::vector<int> pair_of_a(peaks_a.size(), -1), pair_of_b(peaks_b.size(), -1);
  for (const PeakPair& p : pairs) {
    if (pair_of_a[p.a] >= 0 || pair_of_b[p.b] >= 0) continue;
    pair_of_a[p.a] = static_cast<int>(p.b);
    pair_of_b[p.b] = static_cast<int>(p.a);
  }
  auto classify = [&](double delta) {
    return delta >= o.change_threshold    ? ObjectChangeKind::kGrown
           : delta <= -o.change_threshold ? ObjectChangeKind::kShrunk
                                          : ObjectChangeKind::kUnchanged;
  };
  struct Site {
    ObjectChange c;
    int obj_a, obj_b;
    std::size_t order;  // ties: the order the sites were made in
  };
  std::vector<Site> sites;
  auto add_site = [&](int pa, int pb) {
    const Eigen::Vector3d& at = pb >= 0 ? feet_b[peaks_b[static_cast<std::size_t>(pb)].vertex]
                                        : feet_a[peaks_a[static_cast<std::size_t>(pa)].vertex];
    const DiscMax ma = MaxOver(a_index, dev_a, at, reach), mb = MaxOver(b_index, dev_b, at, reach);
    Site s;
    s.obj_a = pa >= 0 ? peaks_a[static_cast<std::size_t>(pa)].object : ObjectAt(object_of_a, ma.vertex);
    s.obj_b = pb >= 0 ? peaks_b[static_cast<std::size_t>(pb)].object : ObjectAt(object_of_b, mb.vertex);
    ObjectChange& c = s.c;
    if (s.obj_a >= 0) c.id_a = objects_a[static_cast<std::size_t>(s.obj_a)].id;
    if (s.obj_b >= 0) c.id_b = objects_b[static_cast<std::size_t>(s.obj_b)].id;
    // B's peak, else B's highest vertex there where B has an object there
    // (in B's M, like the rows with a peak of B), else A's peak (in A's M).
    c.centroid = pb >= 0        ? model_b.vertices[peaks_b[static_cast<std::size_t>(pb)].vertex]
                 : s.obj_b >= 0 ? model_b.vertices[static_cast<std::size_t>(mb.vertex)]
                                : model_a.vertices[peaks_a[static_cast<std::size_t>(pa)].vertex];
    c.height_a = ma.h;
    c.height_b = mb.h;
    c.change = c.height_b - c.height_a;
    if (s.obj_a < 0 && c.height_a < o.change_threshold && c.height_b >= o.change_threshold) {
      c.kind = ObjectChangeKind::kNew;
      c.height_a = 0;
      c.change = c.height_b;
    } else if (s.obj_b < 0 && c.height_b < o.change_threshold && c.height_a >= o.change_threshold) {
      c.kind = ObjectChangeKind::kRemoved;
      c.height_b = 0;
      c.change = -c.height_a;
    } else {
      c.kind = classify(c.change);
      c.from_height_field = s.obj_a < 0 || s.obj_b < 0;
    }
    s.order = sites.size();
    sites.push_back(std::move(s));
  };
  for (std::size_t b = 0; b < peaks_b.size(); ++b) add_site(pair_of_b[b], static_cast<int>(b));
  for (std::size_t a = 0; a < peaks_a.size(); ++a) {
    if (pair_of_a[a] < 0) add_site(static_cast<int>(a), -1);
  }

  // One row per pair of objects (or object of one map) and kind: the site
  // that changed most; where an object pair has a changed site, its
  // unchanged sites are dropped.
  std::sort(sites.begin(), sites.end(), [](const Site& x, const Site& y) {
    auto group = [](const Site& s) { return s.obj_b < 0 ? 2 : s.c.kind == ObjectChangeKind::kNew ? 1 : 0; };
    if (group(x) != group(y)) return group(x) < group(y);
    if (x.obj_b != y.obj_b) return x.obj_b < y.obj_b;
    if (x.obj_a != y.obj_a) return x.obj_a < y.obj_a;
    if (x.c.kind != y.c.kind) return x.c.kind < y.c.kind;
    if (std::abs(x.c.change) != std::abs(y.c.change)) return std::abs(x.c.change) > std::abs(y.c.change);
    const double hx = std::max(x.c.height_a, x.c.height_b), hy = std::max(y.c.height_a, y.c.height_b);
    return hx != hy ? hx > hy : x.order < y.order;
  });
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const Site& s = sites[i];
    if (i > 0 && sites[i - 1].obj_a == s.obj_a && sites[i - 1].obj_b == s.obj_b && sites[i - 1].c.kind == s.c.kind) {
      continue;  // the same objects and kind, a smaller change
    }
    if (s.c.kind == ObjectChangeKind::kUnchanged) {
      const bool changed_elsewhere = std::any_of(sites.begin(), sites.end(), [&](const Site& t) {
        return t.obj_a == s.obj_a && t.obj_b == s.obj_b && t.c.kind != ObjectChangeKind::kUnchanged;
      });
      if (changed_elsewhere) continue;
    }
    out.objects.push_back(s.c);
  }
  progress.Update(1.0, "compared: " + std::to_string(out.objects.size()) + " objects");
  return out;
}

}  // namespace hull
