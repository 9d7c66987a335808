#include "ui/session/inspection_results.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <unordered_set>

namespace hull::ui {

std::vector<DvlHit> AdjustedDvlHits(const SurveyBundle& bundle, const AdjustmentResult& result) {
  std::unordered_map<std::int64_t, int> index;
  for (std::size_t i = 0; i < result.keyframes.size(); ++i) index[result.keyframes[i]] = static_cast<int>(i);
  std::vector<DvlHit> hits;
  hits.reserve(bundle.dvl.size() * 4);
  for (const DvlRecord& d : bundle.dvl) {
    auto it = index.find(d.keyframe);
    if (it == index.end()) continue;
    const int k = it->second;
    const double servo = k < static_cast<int>(result.servo.size()) ? result.servo[k] : 0.0;
    const Pose x_gd = DvlPose(bundle.manifest, result.poses[k], servo);
    for (int beam = 0; beam < 4; ++beam) {
      if (!DvlRecord::HasReturn(d.range[beam])) continue;
      DvlHit hit;
      hit.point = x_gd * (d.range[beam] * bundle.manifest.BeamDirection(beam));
      hit.nav_index = k;
      hit.beam = beam;
      hits.push_back(hit);
    }
  }
  return hits;
}

AdjustedOverlays ComputeAdjustedOverlays(const SurveyBundle& bundle, const AdjustmentResult& result) {
  AdjustedOverlays out;
  out.keyframes = result.keyframes;
  out.trajectory.reserve(result.poses.size());
  for (const Vector6d& x : result.poses) out.trajectory.push_back(x.head<3>());
  out.dvl_hits = AdjustedDvlHits(bundle, result);

  std::unordered_map<std::int64_t, const TrueLandmark*> truth;
  if (bundle.truth) {
    for (const TrueLandmark& l : bundle.truth->landmarks) truth[l.landmark] = &l;
  }
  out.landmarks.reserve(result.landmarks.size());
  for (const LandmarkEstimate& e : result.landmarks) {
    AdjustedLandmark l;
    l.id = e.id;
    l.position = e.p;
    l.label = e.label;
    l.deviation = e.deviation;
    l.observations = e.observations;
    auto t = truth.find(e.id);
    if (t != truth.end()) {
      l.has_truth = true;
      l.true_deviation = t->second->deviation;
      l.object = t->second->object;
    }
    out.landmarks.push_back(l);
  }
  for (const auto& p : out.trajectory) out.bounds.extend(p);
  for (const auto& h : out.dvl_hits) out.bounds.extend(h.point);
  for (std::size_t i = 0; i < out.landmarks.size(); ++i) {
    const AdjustedLandmark& l = out.landmarks[i];
    out.bounds.extend(l.position);
    out.min_deviation = i == 0 ? l.deviation : std::min(out.min_deviation, l.deviation);
    out.max_deviation = i == 0 ? l.deviation : std::max(out.max_deviation, l.deviation);
  }
  return out;
}

MappingOverlays ComputeMappingOverlays(const MappingResult& result, const TriangleMesh& cad) {
  MappingOverlays out;
  const TriangleMesh& model = result.model;
  for (const DetectedObject& o : result.objects) {
    const std::unordered_set<int> inside(o.vertices.begin(), o.vertices.end());
    // Edges of the faces touching a vertex above h_min; those used once
    // bound the footprint (just outside it, so that it shows whole).
    std::map<std::pair<int, int>, int> edges;
    for (const Face& f : model.faces) {
      if (!inside.count(f[0]) && !inside.count(f[1]) && !inside.count(f[2])) continue;
      for (int e = 0; e < 3; ++e) {
        const int a = f[e], b = f[(e + 1) % 3];
        ++edges[{std::min(a, b), std::max(a, b)}];
      }
    }
    std::vector<std::array<Eigen::Vector3d, 2>> outline;
    for (const auto& [edge, count] : edges) {
      if (count == 1) outline.push_back({model.vertices[edge.first], model.vertices[edge.second]});
    }
    double radius = 0.05;
    for (int v : o.vertices) radius = std::max(radius, (model.vertices[v] - o.centroid_m).norm());
    out.object_outlines.push_back(std::move(outline));
    out.object_radius.push_back(radius);
  }

  const int zones = result.hull.num_zones();
  std::vector<Eigen::Vector3d> sum(zones, Eigen::Vector3d::Zero());
  std::vector<double> area(zones, 0.0);
  std::vector<int> zone_of(cad.faces.size(), -1);
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    const Face& t = cad.faces[f];
    const Eigen::Vector3d& a = cad.vertices[t[0]];
    const Eigen::Vector3d& b = cad.vertices[t[1]];
    const Eigen::Vector3d& c = cad.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double twice = n.norm();
    if (twice <= 0) continue;
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    const int z = result.hull.Zone(centroid, n / twice);
    if (z < 0 || z >= zones) continue;
    zone_of[f] = z;
    sum[z] += 0.5 * twice * centroid;
    area[z] += 0.5 * twice;
  }
  out.zone_centres.assign(zones, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  out.zone_radius.assign(zones, 0.0);
  for (int z = 0; z < zones; ++z) {
    if (area[z] > 0) out.zone_centres[z] = sum[z] / area[z];
  }
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    const int z = zone_of[f];
    if (z < 0) continue;
    for (int k = 0; k < 3; ++k) {
      out.zone_radius[z] = std::max(out.zone_radius[z], (cad.vertices[cad.faces[f][k]] - out.zone_centres[z]).norm());
    }
  }

  if (const std::vector<double>* d = model.FindScalar("deviation"); d && !d->empty()) {
    out.min_deviation = *std::min_element(d->begin(), d->end());
    out.max_deviation = *std::max_element(d->begin(), d->end());
  }
  for (const KeyframeShapes& k : result.keyframes) {
    for (const DetectedShape& s : k.shapes) out.shape_triangles += s.triangles.size();
  }
  return out;
}

}  // namespace hull::ui
