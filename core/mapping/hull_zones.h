// Hull-relative positions (the contract's hull axes): the distance from the
// bow along the model's forward axis, the station (the hull's length cut
// into equal intervals, station 0 at the bow) and the zone side -- bottom,
// port or starboard -- from the outward surface normal.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "survey/survey.h"

namespace hull {

enum class HullSide {
  kBottom,     // outward normal within bottom_angle of straight down
  kPort,       // otherwise, facing port (the normal has a component toward port)
  kStarboard,  // otherwise, facing starboard
  kNone,       // facing up within bottom_angle (decks): no zone
};
const char* HullSideName(HullSide s);  // "bottom", "port", "starboard", "none"
constexpr int kZoneSides = 3;          // bottom, port, starboard

class HullFrame {
 public:
  // +x forward, +z up, a 1 m hull of 20 stations, bottom within 45 degrees.
  HullFrame() : HullFrame(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 0.0, 1.0, 20, 45.0) {}
  // forward and up in M (need not be unit; must not be parallel); bow and
  // stern are the extreme coordinates along forward of the hull.
  HullFrame(const Eigen::Vector3d& forward, const Eigen::Vector3d& up, double stern, double bow, int stations,
            double bottom_angle_deg);

  const Eigen::Vector3d& forward() const { return forward_; }
  const Eigen::Vector3d& up() const { return up_; }
  // up x forward: toward port for a right-handed (forward, port, up) frame.
  const Eigen::Vector3d& port() const { return port_; }
  double length() const { return bow_ - stern_; }
  int stations() const { return stations_; }
  double station_length() const { return length() / stations_; }
  int num_zones() const { return stations_ * kZoneSides; }

  // Metres from the bow along forward (0 at the bow, length() at the stern).
  double DistanceFromBow(const Eigen::Vector3d& p_m) const { return bow_ - p_m.dot(forward_); }
  // 0 (bow) .. stations() - 1 (stern); points beyond the ends are clamped.
  int Station(const Eigen::Vector3d& p_m) const;
  HullSide Side(const Eigen::Vector3d& outward_normal_m) const;
  // Zone index station * 3 + side, or -1 for HullSide::kNone.
  int Zone(const Eigen::Vector3d& p_m, const Eigen::Vector3d& outward_normal_m) const;
  static int ZoneIndex(int station, HullSide side) { return station * kZoneSides + static_cast<int>(side); }

 private:
  Eigen::Vector3d forward_, up_, port_;
  double stern_, bow_;
  int stations_;
  double cos_bottom_;
};

// The contract's hull axes: model_axes when given; otherwise forward is +x
// of M and up is the axis of M (+-x, +-y, +-z) that x_gM maps closest to
// -z of g. forward is made perpendicular to up. The bow and stern are the
// CAD's extremes along forward. Throws InputError when forward and up are
// parallel.
HullFrame MakeHullFrame(const TriangleMesh& cad, const std::optional<ModelAxes>& axes, const Pose& x_gM, int stations,
                        double bottom_angle_deg);

}  // namespace hull
