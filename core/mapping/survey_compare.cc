#include "mapping/survey_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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

TriangleMesh WithNormals(TriangleMesh m) {
  m.ComputeNormals();
  return m;
}

// Maps placed on the CAD: each vertex's foot (its closest point of the CAD
// surface) and the CAD's normal there, with progress over every placement
// the comparison makes.
class CadPlacement {
 public:
  CadPlacement(const TriangleMesh& cad, double total, Progress& progress)
      : cad_(WithNormals(cad)), index_(cad_), total_(total), progress_(progress) {}
  CadPlacement(const CadPlacement&) = delete;
  CadPlacement& operator=(const CadPlacement&) = delete;

  // The feet of m's vertices placed by x (and the normals there, when asked).
  std::vector<Eigen::Vector3d> Place(const TriangleMesh& m, const Pose& x, const char* what,
                                     std::vector<Eigen::Vector3d>* normals) {
    constexpr std::size_t kChunk = 4096;
    std::vector<Eigen::Vector3d> feet(m.num_vertices());
    if (normals) normals->resize(m.num_vertices());
    for (std::size_t i = 0; i < feet.size(); ++i, ++done_) {
      if (i % kChunk == 0) {
        progress_.ThrowIfCancelled();
        progress_.Update(static_cast<double>(done_) / total_, what);
      }
      const ClosestPoint c = index_.Closest(x * m.vertices[i]);
      feet[i] = c.point;
      if (normals) (*normals)[i] = cad_.face_normals[static_cast<std::size_t>(c.face)];
    }
    return feet;
  }

 private:
  const TriangleMesh cad_;
  const MeshIndex index_;
  const double total_;
  std::size_t done_ = 0;
  Progress& progress_;
};

// One survey's map as the comparison reads it: its height field keyed by
// where its vertices stand on the CAD (on its own placement), which object
// each vertex belongs to, and its objects' peaks.
struct MapSide {
  const TriangleMesh& model;
  const std::vector<DetectedObject>& objects;
  const std::vector<double>& dev;
  const std::vector<double>* sigma;
  std::vector<Eigen::Vector3d> feet, normals;
  std::unique_ptr<PointIndex> index;  // over feet
  std::vector<int> object_of;
  std::vector<Peak> peaks;
};

// A map's side. Its peaks: the highest vertex of every detected object and
// each other local maximum of an object (no higher vertex within
// peak_spacing). An object's change is read at its peaks, not as its max
// height: two maps split and join touching lumps differently, and a joined
// object's max stands on one lump only (docs/mapping.md, "Change between two
// surveys").
MapSide ReadSide(const TriangleMesh& model, const std::vector<DetectedObject>& objects, const std::vector<double>& dev,
                 CadPlacement& placement, const char* what, const SurveyCompareOptions& o) {
  MapSide s{model, objects, dev, model.FindScalar("sigma"), {}, {}, nullptr, {}, {}};
  s.feet = placement.Place(model, Pose(), what, &s.normals);
  s.index = std::make_unique<PointIndex>(s.feet);
  s.object_of = ObjectOfVertex(model, objects, dev, s.feet, o.match_radius, o.change_threshold);
  s.peaks = ObjectPeaks(dev, s.object_of, s.feet, *s.index, objects.size(), o.peak_spacing);
  return s;
}

// B's map registered to A's by the objects' tops (their feet and the CAD's
// normals there), one per object: a lump's top stands where it stood
// whatever each map's object detection made of touching lumps, which moves
// objects' centroids by decimetres (the top of an object that joins lumps
// is one of theirs); one per object, so that the noise peaks of a flat top
// do not outvote the objects.
SurveyRegistration RegisterByTops(const MapSide& a, const MapSide& b, const SurveyRegistrationOptions& ro) {
  auto tops = [](const MapSide& s) {
    std::vector<DetectedObject> points;
    for (const Peak& p : s.peaks) {
      if (!p.top) continue;
      DetectedObject t;
      t.centroid_m = s.feet[p.vertex];
      t.normal_m = s.normals[p.vertex];
      points.push_back(std::move(t));
    }
    return points;
  };
  return RegisterSurveys(tops(a), tops(b), ro);
}

// The per-vertex change of B's model against A's height where B's vertex
// stands (feet_b: on the registered placement), its sigma from both maps'
// and whether it is significant.
void MeasureChange(const MapSide& a, const MapSide& b, const std::vector<Eigen::Vector3d>& feet_b,
                   const SurveyCompareOptions& o, SurveyComparison& out) {
  const std::size_t nb = b.model.num_vertices();
  out.model = b.model;
  std::vector<double> change(nb), sigma(nb), significant(nb, 0.0);
  for (std::size_t i = 0; i < nb; ++i) {
    const auto nearest = a.index->NearestOne(feet_b[i]);
    const std::size_t j = static_cast<std::size_t>(std::max(0, nearest.first));
    change[i] = b.dev[i] - a.dev[j];
    const double sa = SigmaAt(a.sigma, j), sb = SigmaAt(b.sigma, i);
    sigma[i] = std::sqrt(sa * sa + sb * sb);
    if (std::isfinite(sigma[i]) && std::abs(change[i]) > o.significance_k * sigma[i]) {
      significant[i] = 1;
      ++out.significant_vertices;
    }
  }
  out.model.SetScalar("change", change);
  out.model.SetScalar("change_sigma", sigma);
  out.model.SetScalar("change_significant", significant);
}

// Pairs of peaks of A and B within reach of each other, closest first, each
// peak in one pair at most: per peak, the other map's peak (-1: none).
struct PeakPairing {
  std::vector<int> of_a, of_b;
};

PeakPairing PairPeaks(const MapSide& a, const MapSide& b, const PointIndex& b_index, double reach) {
  struct PeakPair {
    double d;
    std::size_t a, b;
  };
  std::vector<PeakPair> pairs;
  std::vector<int> peak_at_b(b.model.num_vertices(), -1);
  for (std::size_t k = 0; k < b.peaks.size(); ++k) peak_at_b[b.peaks[k].vertex] = static_cast<int>(k);
  for (std::size_t k = 0; k < a.peaks.size(); ++k) {
    for (const auto& hit : b_index.Within(a.feet[a.peaks[k].vertex], reach, false)) {
      const int pb = peak_at_b[static_cast<std::size_t>(hit.first)];
      if (pb >= 0) pairs.push_back({hit.second, k, static_cast<std::size_t>(pb)});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const PeakPair& x, const PeakPair& y) {
    if (x.d != y.d) return x.d < y.d;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  PeakPairing p{std::vector<int>(a.peaks.size(), -1), std::vector<int>(b.peaks.size(), -1)};
  for (const PeakPair& q : pairs) {
    if (p.of_a[q.a] >= 0 || p.of_b[q.b] >= 0) continue;
    p.of_a[q.a] = static_cast<int>(q.b);
    p.of_b[q.b] = static_cast<int>(q.a);
  }
  return p;
}

// A place where the maps are compared: a peak of B (with its paired peak of
// A, if any) or an unpaired peak of A, and the objects there.
struct Site {
  ObjectChange c;
  int obj_a, obj_b;
  std::size_t order;  // ties: the order the sites were made in
};

// The site of peak pa of A and/or pb of B (-1: none): both maps' highest
// heights within reach of it, the objects there, and the kind of change.
Site MakeSite(const MapSide& a, const MapSide& b, const std::vector<Eigen::Vector3d>& feet_b, const PointIndex& b_index,
              int pa, int pb, double reach, const SurveyCompareOptions& o) {
  const Eigen::Vector3d& at = pb >= 0 ? feet_b[b.peaks[static_cast<std::size_t>(pb)].vertex]
                                      : a.feet[a.peaks[static_cast<std::size_t>(pa)].vertex];
  const DiscMax ma = MaxOver(*a.index, a.dev, at, reach), mb = MaxOver(b_index, b.dev, at, reach);
  Site s;
  s.obj_a = pa >= 0 ? a.peaks[static_cast<std::size_t>(pa)].object : ObjectAt(a.object_of, ma.vertex);
  s.obj_b = pb >= 0 ? b.peaks[static_cast<std::size_t>(pb)].object : ObjectAt(b.object_of, mb.vertex);
  ObjectChange& c = s.c;
  if (s.obj_a >= 0) c.id_a = a.objects[static_cast<std::size_t>(s.obj_a)].id;
  if (s.obj_b >= 0) c.id_b = b.objects[static_cast<std::size_t>(s.obj_b)].id;
  // B's peak, else B's highest vertex there where B has an object there (in
  // B's M, like the rows with a peak of B), else A's peak (in A's M).
  c.centroid = pb >= 0        ? b.model.vertices[b.peaks[static_cast<std::size_t>(pb)].vertex]
               : s.obj_b >= 0 ? b.model.vertices[static_cast<std::size_t>(mb.vertex)]
                              : a.model.vertices[a.peaks[static_cast<std::size_t>(pa)].vertex];
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
    c.kind = c.change >= o.change_threshold    ? ObjectChangeKind::kGrown
             : c.change <= -o.change_threshold ? ObjectChangeKind::kShrunk
                                               : ObjectChangeKind::kUnchanged;
    c.from_height_field = s.obj_a < 0 || s.obj_b < 0;
  }
  return s;
}

// One row per pair of objects (or object of one map) and kind: the site that
// changed most; where an object pair has a changed site, its unchanged sites
// are dropped.
std::vector<ObjectChange> ChangeRows(std::vector<Site> sites) {
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
  std::vector<ObjectChange> rows;
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
    rows.push_back(s.c);
  }
  return rows;
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
  const std::size_t na = model_a.num_vertices(), nb = model_b.num_vertices();
  CadPlacement placement(cad, static_cast<double>(na + 2 * nb) + 1.0, progress);
  const MapSide a = ReadSide(model_a, objects_a, dev_a, placement, "placing survey A's model on the CAD", o);
  const MapSide b = ReadSide(model_b, objects_b, dev_b, placement, "placing survey B's model on the CAD", o);

  SurveyComparison out;
  SurveyRegistrationOptions ro;
  ro.match_radius = o.peak_spacing;
  ro.max_offset = o.max_misplacement;
  if (o.register_surveys) out.registration = RegisterByTops(a, b, ro);
  const Pose& x_ab = out.registration.a_from_b;  // B's map placed on A's
  const std::vector<Eigen::Vector3d> feet_b =
      out.registration.registered ? placement.Place(model_b, x_ab, "measuring the change on survey B's model", nullptr)
                                  : b.feet;
  const PointIndex b_index(feet_b);
  MeasureChange(a, b, feet_b, o, out);

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
  const PeakPairing pairing = PairPeaks(a, b, b_index, reach);
  std::vector<Site> sites;
  auto add_site = [&](int pa, int pb) {
    sites.push_back(MakeSite(a, b, feet_b, b_index, pa, pb, reach, o));
    sites.back().order = sites.size() - 1;
  };
  for (std::size_t k = 0; k < b.peaks.size(); ++k) add_site(pairing.of_b[k], static_cast<int>(k));
  for (std::size_t k = 0; k < a.peaks.size(); ++k) {
    if (pairing.of_a[k] < 0) add_site(static_cast<int>(k), -1);
  }
  out.objects = ChangeRows(std::move(sites));
  progress.Update(1.0, "compared: " + std::to_string(out.objects.size()) + " objects");
  return out;
}

}  // namespace hull
