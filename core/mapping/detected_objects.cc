#include "mapping/detected_objects.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "geometry/vertex_regions.h"
#include "mapping/surface_clip.h"

namespace hull {
namespace {

struct ZoneAccumulator {
  double area = 0, integral = 0, max_height = 0;
};

struct Component {
  double area = 0, integral = 0, max_height = 0;
  int peak = -1;  // the highest vertex
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  std::vector<int> vertices;
  std::map<int, ZoneAccumulator> zones;
  std::set<int> landmarks;
  std::set<std::int64_t> keyframes;
  int object = -1;  // index into the output, when kept
};

// Nearest-rank percentile q in (0, 1] of a non-empty set.
double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  const std::size_t i = std::min(v.size() - 1, rank > 0 ? rank - 1 : 0);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v.end());
  return v[i];
}

// The sigma_h of the component's supporting landmark nearest to its highest
// vertex (NaN when none has a sigma_h).
double PeakSigma(const Component& c, const TriangleMesh& prior, const Pose& x_Mg, const MappingInput& input) {
  double sigma = std::nan(""), best = std::numeric_limits<double>::infinity();
  if (c.peak < 0) return sigma;
  const Eigen::Vector3d& peak = prior.vertices[static_cast<std::size_t>(c.peak)];
  for (const int l : c.landmarks) {
    const MappingLandmark& m = input.landmarks[static_cast<std::size_t>(l)];
    if (!(m.sigma_h > 0) || !std::isfinite(m.sigma_h)) continue;
    const double d = (x_Mg * m.p_g - peak).squaredNorm();
    if (d < best) {
      best = d;
      sigma = m.sigma_h;
    }
  }
  return sigma;
}

// An object: a footprint of at least object_min_area, or (smaller) at least
// object_min_features of the run's shaped features over it standing above
// h_min, held by the shapes of at least object_min_views keyframes.
bool KeepComponent(const Component& c, const MappingInput& input, const MappingOptions& o) {
  if (!(c.area > 0)) return false;
  if (c.area >= o.object_min_area) return true;
  if (o.object_min_features <= 0) return false;
  int high = 0;
  for (const int l : c.landmarks) high += input.landmarks[static_cast<std::size_t>(l)].deviation > o.object_min_height;
  return high >= o.object_min_features && static_cast<int>(c.keyframes.size()) >= o.object_min_views;
}

// Connected regions of the prior's vertices above h_min (over the mesh's
// edges), each with its vertices and its highest one.
std::vector<Component> RegionsAbove(const TriangleMesh& prior, const std::vector<double>& deviation, double h,
                                    std::vector<int>* comp_of) {
  const VertexRegions regions =
      ConnectedVertexRegions(prior, [&](int v) { return deviation[static_cast<std::size_t>(v)] > h; });
  *comp_of = regions.region_of;
  std::vector<Component> comps(static_cast<std::size_t>(regions.num_regions));
  for (int v = 0; v < static_cast<int>(prior.num_vertices()); ++v) {
    if ((*comp_of)[static_cast<std::size_t>(v)] < 0) continue;
    Component& c = comps[static_cast<std::size_t>((*comp_of)[static_cast<std::size_t>(v)])];
    c.vertices.push_back(v);
    if (c.peak < 0 || deviation[static_cast<std::size_t>(v)] > c.max_height) {
      c.max_height = deviation[static_cast<std::size_t>(v)];
      c.peak = v;
    }
  }
  return comps;
}

// Footprints: each face clipped to where its interpolated deviation exceeds
// h_min, added to its region's area, height integral and first moment, and
// per hull zone.
void AddFootprints(const TriangleMesh& prior, const std::vector<double>& deviation, double h, const HullFrame& hull,
                   const std::vector<int>& comp_of, std::vector<Component>& comps) {
  for (std::size_t f = 0; f < prior.num_faces(); ++f) {
    const Face& F = prior.faces[f];
    int comp = -1;
    for (const int v : F) {
      if (comp < 0) comp = comp_of[static_cast<std::size_t>(v)];
    }
    if (comp < 0) continue;
    ClipPolygon poly;
    for (const int v : F)
      poly.push_back({prior.vertices[static_cast<std::size_t>(v)], deviation[static_cast<std::size_t>(v)]});
    ClipKeep(poly, [h](const ClipVertex& c) { return c.value - h; });
    const ClipMoments m = Moments(poly);
    if (!(m.area > 0)) continue;
    Component& c = comps[static_cast<std::size_t>(comp)];
    c.area += m.area;
    c.integral += m.value;
    c.first += m.first;
    const int zone = hull.Zone(m.first / m.area, prior.face_normals[f]);
    if (zone < 0) continue;
    ZoneAccumulator& z = c.zones[zone];
    z.area += m.area;
    z.integral += m.value;
    for (const int v : F) z.max_height = std::max(z.max_height, deviation[static_cast<std::size_t>(v)]);
  }
}

// The shaped features over each region (nearest model vertex in the
// region), and the keyframes whose shapes hold them.
void AddFeatures(const PointIndex& prior_index, const MappingInput& input, const std::vector<KeyframeShapes>& shapes,
                 const std::vector<int>& comp_of, std::vector<Component>& comps) {
  const Pose x_Mg = input.x_gM.Inverse();
  std::set<int> used;
  for (const auto& ks : shapes) {
    for (const auto& s : ks.shapes) {
      for (const int pi : s.points) used.insert(ks.points[static_cast<std::size_t>(pi)].landmark);
    }
  }
  std::vector<int> landmark_comp(input.landmarks.size(), -1);
  for (const int l : used) {
    const auto nearest = prior_index.NearestOne(x_Mg * input.landmarks[static_cast<std::size_t>(l)].p_g);
    if (nearest.first < 0) continue;
    const int c = comp_of[static_cast<std::size_t>(nearest.first)];
    if (c < 0) continue;
    landmark_comp[static_cast<std::size_t>(l)] = c;
    comps[static_cast<std::size_t>(c)].landmarks.insert(l);
  }
  for (const auto& ks : shapes) {
    for (const auto& s : ks.shapes) {
      for (const int pi : s.points) {
        const int c = landmark_comp[static_cast<std::size_t>(ks.points[static_cast<std::size_t>(pi)].landmark)];
        if (c >= 0) comps[static_cast<std::size_t>(c)].keyframes.insert(ks.id);
      }
    }
  }
}

// The object a kept region is: its place on the hull, size, heights and the
// features and views that hold it up.
DetectedObject MakeObject(const Component& c, const TriangleMesh& prior, const std::vector<double>& deviation,
                          const MeshIndex& cad_index, const HullFrame& hull, const MappingInput& input) {
  DetectedObject obj;
  obj.id = "obj-" + std::to_string(c.object + 1);
  obj.centroid_m = c.first / c.area;
  const ClosestPoint cp = cad_index.Closest(obj.centroid_m);
  obj.normal_m =
      cp.face >= 0 ? cad_index.mesh().face_normals[static_cast<std::size_t>(cp.face)] : Eigen::Vector3d(-hull.up());
  obj.distance_from_bow = hull.DistanceFromBow(obj.centroid_m);
  obj.station = hull.Station(obj.centroid_m);
  obj.side = hull.Side(obj.normal_m);
  obj.area = c.area;
  obj.mean_height = c.integral / c.area;
  obj.max_height = c.max_height;
  std::vector<double> heights;
  for (const int v : c.vertices) heights.push_back(deviation[static_cast<std::size_t>(v)]);
  obj.p95_height = Percentile(heights, 0.95);
  obj.max_height_sigma = PeakSigma(c, prior, input.x_gM.Inverse(), input);
  obj.num_features = static_cast<int>(c.landmarks.size());
  obj.keyframes.assign(c.keyframes.begin(), c.keyframes.end());
  obj.num_views = static_cast<int>(obj.keyframes.size());
  obj.vertices = c.vertices;
  return obj;
}

}  // namespace

ObjectDetection DetectObjects(const TriangleMesh& prior, const std::vector<double>& deviation,
                              const PointIndex& prior_index, const MeshIndex& cad_index, const HullFrame& hull,
                              const MappingInput& input, const std::vector<KeyframeShapes>& shapes,
                              const MappingOptions& o) {
  ObjectDetection out;
  const std::size_t nz = static_cast<std::size_t>(hull.num_zones());
  out.zone_covered_area.assign(nz, 0.0);
  out.zone_height_integral.assign(nz, 0.0);
  out.zone_max_height.assign(nz, 0.0);
  out.zone_objects.assign(nz, 0);
  std::vector<int> comp_of;
  std::vector<Component> comps = RegionsAbove(prior, deviation, o.object_min_height, &comp_of);
  AddFootprints(prior, deviation, o.object_min_height, hull, comp_of, comps);
  AddFeatures(prior_index, input, shapes, comp_of, comps);

  // Keep the large enough ones and the small ones that enough features
  // standing above h_min, seen from enough keyframes, hold up (a tall narrow
  // lump); order them from the bow aft.
  std::vector<int> kept;
  for (std::size_t i = 0; i < comps.size(); ++i) {
    if (KeepComponent(comps[i], input, o)) kept.push_back(static_cast<int>(i));
  }
  auto centroid = [&](int i) -> Eigen::Vector3d {
    const Component& c = comps[static_cast<std::size_t>(i)];
    return c.first / c.area;
  };
  std::sort(kept.begin(), kept.end(), [&](int a, int b) {
    const double da = hull.DistanceFromBow(centroid(a)), db = hull.DistanceFromBow(centroid(b));
    if (da != db) return da < db;
    return a < b;
  });
  for (std::size_t k = 0; k < kept.size(); ++k) comps[static_cast<std::size_t>(kept[k])].object = static_cast<int>(k);

  for (const int i : kept) {
    const Component& c = comps[static_cast<std::size_t>(i)];
    DetectedObject obj = MakeObject(c, prior, deviation, cad_index, hull, input);
    for (const auto& [zone, z] : c.zones) {
      out.zone_covered_area[static_cast<std::size_t>(zone)] += z.area;
      out.zone_height_integral[static_cast<std::size_t>(zone)] += z.integral;
      out.zone_max_height[static_cast<std::size_t>(zone)] =
          std::max(out.zone_max_height[static_cast<std::size_t>(zone)], z.max_height);
    }
    if (obj.side != HullSide::kNone)
      ++out.zone_objects[static_cast<std::size_t>(HullFrame::ZoneIndex(obj.station, obj.side))];
    out.objects.push_back(std::move(obj));
  }
  return out;
}

}  // namespace hull
