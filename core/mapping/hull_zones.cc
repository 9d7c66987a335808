#include "mapping/hull_zones.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace hull {

const char* HullSideName(HullSide s) {
  switch (s) {
    case HullSide::kBottom:
      return "bottom";
    case HullSide::kPort:
      return "port";
    case HullSide::kStarboard:
      return "starboard";
    case HullSide::kNone:
      return "none";
  }
  return "?";
}

HullFrame::HullFrame(const Eigen::Vector3d& forward, const Eigen::Vector3d& up, double stern, double bow, int stations,
                     double bottom_angle_deg)
    : stern_(stern), bow_(bow), stations_(std::max(1, stations)), cos_bottom_(std::cos(bottom_angle_deg * M_PI / 180)) {
  up_ = up.normalized();
  forward_ = (forward - forward.dot(up_) * up_).normalized();
  port_ = up_.cross(forward_);
}

int HullFrame::Station(const Eigen::Vector3d& p_m) const {
  const double s = DistanceFromBow(p_m) / station_length();
  if (!(s > 0)) return 0;
  return std::min(stations_ - 1, static_cast<int>(std::floor(s)));
}

HullSide HullFrame::Side(const Eigen::Vector3d& n) const {
  const double len = n.norm();
  if (!(len > 0)) return HullSide::kNone;
  const double down = -n.dot(up_) / len;
  if (down >= cos_bottom_) return HullSide::kBottom;
  if (-down >= cos_bottom_) return HullSide::kNone;
  return n.dot(port_) >= 0 ? HullSide::kPort : HullSide::kStarboard;
}

int HullFrame::Zone(const Eigen::Vector3d& p_m, const Eigen::Vector3d& n) const {
  const HullSide side = Side(n);
  if (side == HullSide::kNone) return -1;
  return ZoneIndex(Station(p_m), side);
}

HullFrame MakeHullFrame(const TriangleMesh& cad, const std::optional<ModelAxes>& axes, const Pose& x_gM, int stations,
                        double bottom_angle_deg) {
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX(), up;
  if (axes) {
    forward = axes->forward;
    up = axes->up;
  } else {
    // The axis of M that x_gM maps closest to -z of g (up in g is -z: z is depth).
    double best = -2;
    for (int i = 0; i < 3; ++i) {
      for (const double sign : {1.0, -1.0}) {
        const Eigen::Vector3d e = sign * Eigen::Vector3d::Unit(i);
        const double score = -x_gM.Rotate(e).z();
        if (score > best + 1e-12) {
          best = score;
          up = e;
        }
      }
    }
  }
  if (!(forward.norm() > 0 && up.norm() > 0) || forward.normalized().cross(up.normalized()).norm() < 1e-3) {
    throw InputError({"survey.json", 0, 0, "model_axes"},
                     "the hull's forward and up axes are parallel (or zero); give model_axes in survey.json");
  }
  const Eigen::Vector3d u = up.normalized();
  const Eigen::Vector3d f = (forward - forward.dot(u) * u).normalized();
  double lo = 0, hi = 0;
  if (!cad.vertices.empty()) {
    lo = hi = cad.vertices.front().dot(f);
    for (const auto& v : cad.vertices) {
      lo = std::min(lo, v.dot(f));
      hi = std::max(hi, v.dot(f));
    }
  }
  if (!(hi > lo)) hi = lo + 1.0;
  return HullFrame(f, u, lo, hi, stations, bottom_angle_deg);
}

}  // namespace hull
