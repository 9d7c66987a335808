#include "mapping/object_identity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace hull {

int ObjectIdNumber(const std::string& id) {
  static const std::string kPrefix = "obj-";
  if (id.size() <= kPrefix.size() || id.compare(0, kPrefix.size(), kPrefix) != 0) return 0;
  int n = 0;
  for (std::size_t i = kPrefix.size(); i < id.size(); ++i) {
    if (id[i] < '0' || id[i] > '9' || n > 100000000) return 0;
    n = 10 * n + (id[i] - '0');
  }
  return n;
}

double ObjectIdentity::Radius(const DetectedObject& o) const {
  return std::max(min_radius_, std::sqrt(std::max(0.0, o.area) / M_PI));
}

namespace {

// Along the hull (the footprint's vertices stand off the CAD by their
// height; the centroid lies on it): the distance in the plane normal to n.
double DistanceToFootprint(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                           const std::vector<Eigen::Vector3d>& footprint) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : footprint) {
    const Eigen::Vector3d d = v - p;
    best = std::min(best, (d - d.dot(n) * n).squaredNorm());
  }
  return std::sqrt(best);
}

std::vector<Eigen::Vector3d> FootprintOf(const DetectedObject& o, const TriangleMesh& model) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(o.vertices.size());
  for (const int v : o.vertices) {
    if (v >= 0 && static_cast<std::size_t>(v) < model.num_vertices()) {
      out.push_back(model.vertices[static_cast<std::size_t>(v)]);
    }
  }
  return out;
}

}  // namespace

bool ObjectIdentity::Same(const DetectedObject& o, const std::vector<Eigen::Vector3d>& footprint,
                          const Known& k) const {
  if ((o.centroid_m - k.centroid_m).norm() <= std::max(Radius(o), k.radius)) return true;
  const Eigen::Vector3d n = o.normal_m.squaredNorm() > 0 ? o.normal_m.normalized() : Eigen::Vector3d::Zero();
  return DistanceToFootprint(o.centroid_m, n, k.footprint) <= min_radius_ ||
         DistanceToFootprint(k.centroid_m, n, footprint) <= min_radius_;
}

void ObjectIdentity::Assign(std::vector<DetectedObject>* objects, const TriangleMesh& model) {
  // Every candidate pair (centroid distance, object, known), nearest first.
  std::vector<std::vector<Eigen::Vector3d>> footprints;
  for (const DetectedObject& o : *objects) footprints.push_back(FootprintOf(o, model));
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const DetectedObject& o = (*objects)[i];
    for (std::size_t k = 0; k < known_.size(); ++k) {
      if (Same(o, footprints[i], known_[k])) pairs.emplace_back((o.centroid_m - known_[k].centroid_m).norm(), i, k);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> match(objects->size(), -1);
  std::vector<bool> taken(known_.size(), false);
  for (const auto& [d, i, k] : pairs) {
    if (match[i] >= 0 || taken[k]) continue;
    match[i] = static_cast<int>(k);
    taken[k] = true;
  }
  // The matched ones take their known id and update where it was seen; the
  // others, in the run's order (from the bow aft), get the next numbers.
  for (std::size_t i = 0; i < objects->size(); ++i) {
    DetectedObject& o = (*objects)[i];
    if (match[i] >= 0) {
      Known& k = known_[static_cast<std::size_t>(match[i])];
      o.id = k.id;
      k.centroid_m = o.centroid_m;
      k.radius = Radius(o);
      k.footprint = std::move(footprints[i]);
    } else {
      o.id = "obj-" + std::to_string(++last_number_);
      known_.push_back({o.id, o.centroid_m, Radius(o), std::move(footprints[i])});
    }
  }
}

void ObjectIdentity::Clear() {
  known_.clear();
  last_number_ = 0;
}

}  // namespace hull
