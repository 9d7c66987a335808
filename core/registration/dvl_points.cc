#include "registration/dvl_points.h"

#include <array>
#include <stdexcept>
#include <string>

#include "base/error.h"

namespace hull {

Pose VehicleToDvl(const SurveyManifest& manifest, double servo) {
  return manifest.VehicleToServo(servo) * Pose::FromVector(manifest.servo_to_dvl);
}

std::vector<DvlPoint> DvlPointsInG(const SurveyBundle& bundle, const std::vector<Pose>& x_gv,
                                   const std::vector<double>& servo) {
  if (x_gv.size() != bundle.nav.size() || servo.size() != bundle.nav.size()) {
    throw std::invalid_argument("DvlPointsInG: " + std::to_string(x_gv.size()) + " poses and " +
                                std::to_string(servo.size()) + " servo angles for " +
                                std::to_string(bundle.nav.size()) + " nav records");
  }
  const auto index = bundle.KeyframeIndex();
  const SurveyManifest& man = bundle.manifest;
  std::array<Eigen::Vector3d, 4> beams;
  for (int b = 0; b < 4; ++b) beams[static_cast<std::size_t>(b)] = man.BeamDirection(b);
  std::vector<DvlPoint> out;
  out.reserve(4 * bundle.dvl.size());
  for (std::size_t row = 0; row < bundle.dvl.size(); ++row) {
    const DvlRecord& d = bundle.dvl[row];
    const auto it = index.find(d.keyframe);
    if (it == index.end()) {
      // Row 1 is the header.
      throw InputError({"dvl.csv", static_cast<int>(row) + 2, 1, "keyframe"},
                       "keyframe " + std::to_string(d.keyframe) + " is not in nav.csv");
    }
    const auto i = static_cast<std::size_t>(it->second);
    const Pose x_gd = x_gv[i] * VehicleToDvl(man, servo[i]);
    for (int b = 0; b < 4; ++b) {
      const double r = d.range[static_cast<std::size_t>(b)];
      if (!DvlRecord::HasReturn(r)) continue;
      DvlPoint p;
      p.origin = x_gd.translation();
      p.direction = x_gd.Rotate(beams[static_cast<std::size_t>(b)]);
      p.range = r;
      p.point = p.origin + r * p.direction;
      p.keyframe = d.keyframe;
      p.nav_index = it->second;
      p.beam = b;
      out.push_back(p);
    }
  }
  return out;
}

std::vector<DvlPoint> DvlPointsFromInitialNav(const SurveyBundle& bundle) {
  std::vector<Pose> x_gv;
  std::vector<double> servo;
  x_gv.reserve(bundle.nav.size());
  servo.reserve(bundle.nav.size());
  for (const NavRecord& n : bundle.nav) {
    x_gv.push_back(Pose::FromVector(n.x_gv));
    servo.push_back(n.servo);
  }
  return DvlPointsInG(bundle, x_gv, servo);
}

std::vector<Pose> InitialPosesWithZpr(const SurveyBundle& bundle, double depth_window, bool measured_roll_pitch) {
  const std::vector<NavRecord>& nav = bundle.nav;
  std::vector<Pose> out;
  out.reserve(nav.size());
  // Sliding window over time (nav is sorted by t): prefix sums of depth - z.
  std::vector<double> prefix(nav.size() + 1, 0.0);
  for (std::size_t i = 0; i < nav.size(); ++i) prefix[i + 1] = prefix[i] + (nav[i].depth - nav[i].x_gv[2]);
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < nav.size(); ++i) {
    Vector6d x = nav[i].x_gv;
    if (depth_window > 0) {
      while (nav[lo].t < nav[i].t - 0.5 * depth_window) ++lo;
      while (hi < nav.size() && nav[hi].t <= nav[i].t + 0.5 * depth_window) ++hi;
      x[2] += (prefix[hi] - prefix[lo]) / static_cast<double>(hi - lo);
    }
    if (measured_roll_pitch) {
      x[3] = nav[i].roll_meas;
      x[4] = nav[i].pitch_meas;
    }
    out.push_back(Pose::FromVector(x));
  }
  return out;
}

std::vector<Eigen::Vector3d> PointsOf(const std::vector<DvlPoint>& returns) {
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(returns.size());
  for (const DvlPoint& r : returns) pts.push_back(r.point);
  return pts;
}

}  // namespace hull
