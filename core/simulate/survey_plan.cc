#include "simulate/survey_plan.h"

#include <algorithm>
#include <cmath>

namespace hull {

Pose ShipPlacement(const HullAxes& axes, const Eigen::Vector3d& centre, double heading) {
  Eigen::Matrix3d F, E;
  F.col(0) = axes.forward.normalized();
  F.col(2) = axes.up.normalized();
  F.col(1) = F.col(2).cross(F.col(0)).normalized();  // port
  F.col(2) = F.col(0).cross(F.col(1));               // re-orthogonalised up
  E.col(0) = Eigen::Vector3d::UnitX();
  E.col(1) = -Eigen::Vector3d::UnitY();
  E.col(2) = -Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix() * E * F.transpose();
  Eigen::Vector3d t = -(R * centre);
  t.z() = axes.waterline;  // a point at the waterline height maps to depth 0
  return Pose(R, t);
}

Pose VehicleToCamera(const SurveyManifest& rig, const Pose& x_s_cT, double servo) {
  return rig.VehicleToServo(servo) * x_s_cT;
}

namespace {

struct Station {
  Eigen::Vector3d hit_g;     // hull point
  Eigen::Vector3d normal_g;  // outward normal there
  int track;
};

// Vehicle pose that puts the camera at `standoff` from `hit` looking into the
// hull, for a vehicle heading `yaw` with small roll/pitch.
PlannedKeyframe PoseForStation(const Station& st, double yaw, double roll, double pitch, double standoff,
                               const SurveyManifest& rig, const Pose& x_s_cT) {
  const Eigen::Matrix3d R = RotationFromEuler(roll, pitch, yaw);
  const Eigen::Vector3d want = R.transpose() * (-st.normal_g);  // pointing, in v
  const double theta = std::atan2(-want.z(), want.x());
  const Eigen::Vector3d tray = R * Eigen::Vector3d(std::cos(theta), 0, -std::sin(theta));
  const Eigen::Vector3d cam = st.hit_g - standoff * tray;
  const Pose v_c = VehicleToCamera(rig, x_s_cT, theta);
  PlannedKeyframe k;
  k.x_gv = Pose(R, cam - R * v_c.translation());
  k.servo = theta;
  k.track = st.track;
  return k;
}

}  // namespace

std::vector<PlannedKeyframe> PlanLawnmower(const MeshIndex& cad, const HullAxes& axes, const Pose& x_gM,
                                           const SurveyManifest& rig, const Pose& x_s_cT, const LawnmowerOptions& o,
                                           Rng& rng) {
  const TriangleMesh& mesh = cad.mesh();
  const Eigen::Vector3d f = axes.forward.normalized(), u = axes.up.normalized(), p = u.cross(f).normalized();
  double fmin = 1e300, umin = 1e300, pmax = 0;
  for (const auto& v : mesh.vertices) {
    fmin = std::min(fmin, v.dot(f));
    umin = std::min(umin, v.dot(u));
    pmax = std::max(pmax, std::abs(v.dot(p)));
  }
  const double cos_bottom = std::cos(o.max_bottom_slope_deg * M_PI / 180.0);
  // Slow wobble: sums of sinusoids with random phases, in time.
  const double ph[4] = {rng.Uniform(0, 6.3), rng.Uniform(0, 6.3), rng.Uniform(0, 6.3), rng.Uniform(0, 6.3)};
  const double wob = o.wobble_deg * M_PI / 180.0;

  // 1. Stations, track by track, alternating direction (lawnmower).
  std::vector<std::vector<Station>> tracks;
  std::vector<double> track_standoff;
  std::vector<double> track_yaw;
  const double ship_yaw = std::atan2((x_gM.rotation() * f).y(), (x_gM.rotation() * f).x());
  auto along = [&](bool reverse) {
    std::vector<double> s;
    const int n = std::max(2, static_cast<int>(std::floor((o.end - o.start) / o.keyframe_spacing)) + 1);
    for (int i = 0; i < n; ++i) s.push_back(fmin + o.start + (o.end - o.start) * i / (n - 1));
    if (reverse) std::reverse(s.begin(), s.end());
    return s;
  };
  // Bottom tracks: rays cast up (+u) from below the keel.
  const int nb = std::max(1, static_cast<int>(std::floor(2 * o.half_width / o.track_spacing + 1e-9)) + 1);
  for (int k = 0; k < nb; ++k) {
    const double y = nb == 1 ? 0.0 : -o.half_width + 2 * o.half_width * k / (nb - 1);
    std::vector<Station> track;
    for (double s : along(k % 2 == 1)) {
      const Eigen::Vector3d from = s * f + y * p + (umin - 20.0) * u;
      const RayHit hit = cad.Raycast(from, u, 100.0);
      if (!hit.hit) continue;
      const Eigen::Vector3d n = mesh.face_normals[static_cast<std::size_t>(hit.face)];
      if (n.dot(-u) < cos_bottom) continue;
      track.push_back({x_gM * hit.point, x_gM.Rotate(n), static_cast<int>(tracks.size())});
    }
    if (track.size() >= 2) {
      tracks.push_back(std::move(track));
      track_standoff.push_back(o.standoff);
      track_yaw.push_back(ship_yaw);
    }
  }
  // Side tracks (full hull): rays cast horizontally toward the centreline.
  if (o.coverage == SurveyCoverage::kFullHull) {
    const double keel_depth = axes.waterline - umin;
    for (int side = 0; side < 2; ++side) {
      const double sgn = side == 0 ? -1.0 : 1.0;  // starboard (-port) first
      int k = 0;
      for (double depth = 1.0; depth < keel_depth - 0.5; depth += o.side_track_spacing, ++k) {
        std::vector<Station> track;
        for (double s : along(k % 2 == 1)) {
          const Eigen::Vector3d from = s * f + sgn * (pmax + 20.0) * p + (axes.waterline - depth) * u;
          const RayHit hit = cad.Raycast(from, -sgn * p, 100.0);
          if (!hit.hit) continue;
          const Eigen::Vector3d n = mesh.face_normals[static_cast<std::size_t>(hit.face)];
          if (std::abs(n.dot(u)) > 0.7 || n.dot(sgn * p) < 0.3) continue;
          track.push_back({x_gM * hit.point, x_gM.Rotate(n), static_cast<int>(tracks.size())});
        }
        if (track.size() >= 2) {
          tracks.push_back(std::move(track));
          track_standoff.push_back(o.side_standoff);
          // Face the hull: heading along -n projected horizontally (from the track's middle).
          const Eigen::Vector3d n = tracks.back()[tracks.back().size() / 2].normal_g;
          track_yaw.push_back(std::atan2(-n.y(), -n.x()));
        }
      }
    }
  }

  // 2. Keyframes along the tracks, with transits between consecutive tracks.
  std::vector<PlannedKeyframe> out;
  double t = 0;
  auto wobble = [&](double time, int i) { return wob * std::sin(2 * M_PI * time / (37.0 + 11.0 * i) + ph[i]); };
  auto push = [&](PlannedKeyframe k) {
    if (!out.empty()) {
      const double d = (k.x_gv.translation() - out.back().x_gv.translation()).norm();
      t += std::max(0.5, d / o.speed);
    }
    k.t = t;
    out.push_back(k);
  };
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    std::vector<PlannedKeyframe> keys;
    for (const Station& st : tracks[k]) {
      const double tt = t + keys.size() * o.keyframe_spacing / o.speed;
      const double standoff = track_standoff[k] + o.standoff_jitter * std::sin(2 * M_PI * tt / 53.0 + ph[3]);
      keys.push_back(PoseForStation(st, track_yaw[k], wobble(tt, 0), wobble(tt, 1), standoff, rig, x_s_cT));
    }
    if (!out.empty()) {
      // Transit: orientation and servo interpolated along a path that bulges
      // away from the hull (by half the distance) so it never cuts through it.
      const PlannedKeyframe a = out.back(), b = keys.front();
      const Eigen::Vector3d pa = a.x_gv.translation(), pb = b.x_gv.translation();
      const Eigen::Vector3d away =
          ((pa - tracks[k - 1].back().hit_g).normalized() + (pb - tracks[k].front().hit_g).normalized()).normalized();
      const double dist = (pb - pa).norm();
      const double bulge = dist > 3.0 ? 0.5 * dist : 0.0;
      const int n = static_cast<int>(std::floor(dist / o.keyframe_spacing));
      for (int i = 1; i < n; ++i) {
        const double a_ = static_cast<double>(i) / n;
        PlannedKeyframe m;
        const Eigen::Vector3d pos = (1 - a_) * pa + a_ * pb + std::sin(M_PI * a_) * bulge * away;
        m.x_gv = Pose(a.x_gv.quaternion().slerp(a_, b.x_gv.quaternion()), pos);
        m.servo = (1 - a_) * a.servo + a_ * b.servo;
        m.track = -1;
        push(m);
      }
    }
    for (auto& key : keys) push(key);
  }
  return out;
}

}  // namespace hull
