#include "simulate/sonar_simulator.h"

#include <cmath>
#include <functional>
#include <random>

#include "base/error.h"

namespace hull {
namespace {

// Deterministic normal draws: mt19937_64's sequence is fixed by the standard,
// std::normal_distribution's is not.
class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : rng_(seed) {}
  double Uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }  // [0, 1)
  // Standard normal truncated at +-limit (redrawn beyond).
  double Normal(double limit = 4.0) {
    while (true) {
      if (has_spare_) {
        has_spare_ = false;
        if (std::fabs(spare_) <= limit) return spare_;
        continue;
      }
      double u1 = Uniform();
      while (u1 <= 0) u1 = Uniform();
      const double u2 = Uniform();
      const double rad = std::sqrt(-2.0 * std::log(u1));
      spare_ = rad * std::sin(2 * M_PI * u2);
      has_spare_ = true;
      const double z = rad * std::cos(2 * M_PI * u2);
      if (std::fabs(z) <= limit) return z;
    }
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0;
  bool has_spare_ = false;
};

Vector6d MakePose(double x, double y, double z, double roll, double pitch, double yaw) {
  Vector6d p;
  p << x, y, z, roll, pitch, yaw;
  return p;
}

// Range, azimuth, elevation of world point p from pose (own implementation of
// the contract's model, independent of core/sonar).
Eigen::Vector3d Polar(const Vector6d& pose, const Eigen::Vector3d& p) {
  const Eigen::Matrix3d R = RotationFromEuler(pose[3], pose[4], pose[5]);
  const Eigen::Vector3d q = R.transpose() * (p - pose.head<3>());
  const double r = q.norm();
  return {r, std::atan2(q.y(), q.x()), std::asin(q.z() / r)};
}

// The prism's 8 vertices around its centre: top (z - 0.15) P Q R S, bottom T U V W.
std::vector<Eigen::Vector3d> PrismVertices(const Eigen::Vector3d& c) {
  const double a = 0.1, h = 0.15;
  std::vector<Eigen::Vector3d> v;
  for (double dz : {-h, h}) {
    v.emplace_back(c + Eigen::Vector3d(-a, -a, dz));
    v.emplace_back(c + Eigen::Vector3d(-a, a, dz));
    v.emplace_back(c + Eigen::Vector3d(a, a, dz));
    v.emplace_back(c + Eigen::Vector3d(a, -a, dz));
  }
  return v;
}

// The paper's simulated trajectory around a prism at `centre`, seen from
// `height` above it (0 for the paper's layout): it starts at the origin with
// zero attitude, x approaches by 0.3 m, y sways twice by +-0.2 m (centred when
// the roll is largest, so the prism stays inside the thin elevation fan), z
// by +-0.05 m, and roll goes 0, +a, 0, -a, 0; pitch keeps the prism's centre at
// `centre_elevation` in the fan (0: level, the paper's layout).
std::vector<Vector6d> PrismTrajectory(const SonarSimulationOptions& o, int T, const Eigen::Vector3d& centre,
                                      double height, double centre_elevation) {
  std::vector<Vector6d> poses;
  for (int k = 0; k < T; ++k) {
    const double s = T > 1 ? static_cast<double>(k) / (T - 1) : 0.0;
    const double x = 0.15 * (1 - std::cos(M_PI * s));
    const double y = 0.2 * std::sin(4 * M_PI * s);
    const double z = centre.z() - height + 0.05 * std::sin(3 * M_PI * s);
    const double roll = o.roll_amplitude * std::sin(2 * M_PI * s);
    double pitch = 0;
    if (height != 0) pitch = -(std::atan2(centre.z() - z, centre.x() - x) - centre_elevation);
    poses.push_back(MakePose(x, y, z, roll, pitch, 0.0));
  }
  return poses;
}

// Controls, measurements and the initial pose with the contract's noise for
// the true poses and features; feature i is measured at step k when it is
// inside the field of view and, when given, visible(k, i).
AcousticSequence DrawSequence(const SonarSimulationOptions& o, const std::string& name,
                              const std::vector<Vector6d>& poses, const std::vector<Eigen::Vector3d>& features,
                              const std::function<bool(int, int)>& visible, Gaussian& rng) {
  AcousticSequence seq;
  seq.name = name;
  seq.sensor = o.sensor;
  seq.motion_noise = o.motion_noise;
  seq.initial_pose_sigma = o.initial_pose_sigma;
  SonarTruth truth;
  truth.poses = poses;
  truth.features = features;
  for (std::size_t i = 0; i < features.size(); ++i) truth.feature_ids.push_back(static_cast<std::int64_t>(i));

  const double noise = o.noise ? 1.0 : 0.0;
  for (int i = 0; i < 6; ++i) seq.initial_pose[i] = poses[0][i] + noise * o.initial_pose_sigma[i] * rng.Normal();
  for (int i = 3; i < 6; ++i) seq.initial_pose[i] = WrapAngle(seq.initial_pose[i]);

  // Draws until the sample's noise level is within kLevel of its sigma (see the header).
  constexpr double kLevel = 0.15;
  constexpr int kMaxDraws = 1000;
  const auto typical = [&](double sum_squares, std::size_t n) {
    return n == 0 || !o.noise || std::fabs(std::sqrt(sum_squares / static_cast<double>(n)) - 1) <= kLevel;
  };
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    seq.controls.clear();
    double ss = 0;
    for (std::size_t k = 1; k < poses.size(); ++k) {
      const Vector6d u_true = OplusEuler<double>(OminusEuler<double>(poses[k - 1]), poses[k]);
      SonarControl c;
      c.step = static_cast<std::int64_t>(k);
      for (int i = 0; i < 6; ++i) {
        const bool translation = i < 3;
        const double rate = translation ? o.motion_noise.translation_per_metre : o.motion_noise.rotation_per_radian;
        const double floor = translation ? o.motion_noise.translation_floor : o.motion_noise.rotation_floor;
        const double sigma = std::max(floor, rate * std::fabs(u_true[i]));
        const double n = rng.Normal();
        ss += n * n;
        c.u[i] = u_true[i] + noise * sigma * n;
      }
      c.u[3] = WrapAngle(c.u[3]);
      c.u[5] = WrapAngle(c.u[5]);
      seq.controls.push_back(c);
    }
    if (typical(ss, 6 * seq.controls.size())) break;
  }

  const SonarSensor& s = o.sensor;
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    seq.measurements.clear();
    double ss_range = 0, ss_azimuth = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
      for (std::size_t i = 0; i < features.size(); ++i) {
        const Eigen::Vector3d polar = Polar(poses[k], features[i]);
        const bool inside = polar[0] >= s.range_min && polar[0] <= s.range_max &&
                            std::fabs(polar[1]) <= s.azimuth_fov / 2 && std::fabs(polar[2]) <= s.elevation_fov / 2;
        if (!inside || (visible && !visible(static_cast<int>(k), static_cast<int>(i)))) continue;
        const double nr = rng.Normal(), na = rng.Normal();
        SonarMeasurement m;
        m.step = static_cast<std::int64_t>(k);
        m.feature = truth.feature_ids[i];
        m.range = polar[0] + noise * s.range_sigma * nr;
        m.azimuth = polar[1] + noise * s.azimuth_sigma * na;
        if (m.range < s.range_min || m.range > s.range_max || std::fabs(m.azimuth) > s.azimuth_fov / 2) continue;
        ss_range += nr * nr;
        ss_azimuth += na * na;
        seq.measurements.push_back(m);
      }
    }
    if (typical(ss_range, seq.measurements.size()) && typical(ss_azimuth, seq.measurements.size())) break;
  }
  seq.truth = std::move(truth);
  return seq;
}

}  // namespace

const char* SonarPresetName(SonarPreset preset) {
  switch (preset) {
    case SonarPreset::kPrism:
      return "prism";
    case SonarPreset::kTank:
      return "tank";
    case SonarPreset::kAbove:
      return "above";
  }
  return "?";
}

SonarPreset ParseSonarPreset(const std::string& name) {
  if (name == "prism") return SonarPreset::kPrism;
  if (name == "tank") return SonarPreset::kTank;
  if (name == "above") return SonarPreset::kAbove;
  throw OptionError("preset", "unknown sonar preset '" + name + "'; expected prism, tank or above");
}

bool SonarSimulationOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& field, const std::string& reason) {
    if (why) *why = field + ": " + reason;
    return false;
  };
  if (num_steps < 0 || num_steps > 1000000) return fail("num_steps", "must be 0 (the preset's) or 1..1000000");
  if (!(distance > sensor.range_min + 0.5 && distance < sensor.range_max - 0.5)) {
    return fail("distance",
                "must keep the prism inside the range limits (range_min + 0.5 < distance < range_max - 0.5)");
  }
  if (!(above_distance > sensor.range_min + 0.5 && above_distance < sensor.range_max - 0.5)) {
    return fail("above_distance",
                "must keep the prism inside the range limits (range_min + 0.5 < above_distance < range_max - 0.5)");
  }
  if (!(roll_amplitude >= 0 && roll_amplitude < 1.5)) return fail("roll_amplitude", "must be in [0, 1.5) rad");
  if (!(std::fabs(tank_roll_step) < 1.0)) return fail("tank_roll_step", "must be below 1 rad in magnitude");
  if (!(std::fabs(tank_pitch) < 1.4)) return fail("tank_pitch", "must be below 1.4 rad in magnitude");
  if (!(above_height >= 0 && above_height < 2)) return fail("above_height", "must be in [0, 2) m");
  if (!(std::fabs(above_centre_elevation) < sensor.elevation_fov / 2)) {
    return fail("above_centre_elevation", "must lie inside the elevation field of view");
  }
  if (extra_features < 0 || extra_features > 1000000) return fail("extra_features", "must be in 0..1000000");
  if (!(extra_box.array() >= 0).all()) return fail("extra_box", "sizes must not be negative");
  if (!(sensor.range_min > 0 && sensor.range_max > sensor.range_min && sensor.azimuth_fov > 0 &&
        sensor.elevation_fov > 0 && sensor.range_sigma > 0 && sensor.azimuth_sigma > 0)) {
    return fail("sensor", "needs 0 < range_min < range_max, positive fields of view and sigmas");
  }
  if (!(motion_noise.translation_per_metre >= 0 && motion_noise.rotation_per_radian >= 0 &&
        motion_noise.translation_floor > 0 && motion_noise.rotation_floor > 0)) {
    return fail("motion_noise", "needs non-negative rates and positive floors");
  }
  if (!(initial_pose_sigma.array() > 0).all()) return fail("initial_pose_sigma", "must be positive");
  return true;
}

SonarLayout MakeSonarLayout(const SonarSimulationOptions& o) {
  std::string why;
  if (!o.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  SonarLayout l;
  const double a = 0.1, h = 0.15;  // the prism: 0.2 x 0.2 x 0.3 m
  switch (o.preset) {
    case SonarPreset::kPrism: {
      const int T = o.num_steps > 0 ? o.num_steps : 21;
      l.centre = Eigen::Vector3d(o.distance, 0, 0);
      l.features = PrismVertices(l.centre);
      l.poses = PrismTrajectory(o, T, l.centre, 0.0, 0.0);
      l.name = "prism: the simulation of Mai et al. (square prism, 8 vertices)";
      break;
    }
    case SonarPreset::kAbove: {
      const int T = o.num_steps > 0 ? o.num_steps : 21;
      l.centre = Eigen::Vector3d(o.above_distance, 0, o.above_height);
      l.features = PrismVertices(l.centre);
      l.poses = PrismTrajectory(o, T, l.centre, o.above_height, o.above_centre_elevation);
      l.name = "above: the prism seen from above its centre (every elevation of one sign)";
      break;
    }
    case SonarPreset::kTank: {
      const int T = o.num_steps > 0 ? o.num_steps : 8;
      const Eigen::Vector3d bore(std::cos(o.tank_pitch), 0, -std::sin(o.tank_pitch));
      l.centre = o.distance * bore;
      const Eigen::Vector3d& c = l.centre;
      if (o.tank_face == TankFace::kFront) {
        // The vertical face toward the sonar: A top-left, B top-right, C bottom-right, D bottom-left.
        l.features = {c + Eigen::Vector3d(0, -0.1, -0.15), c + Eigen::Vector3d(0, 0.1, -0.15),
                      c + Eigen::Vector3d(0, 0.1, 0.15), c + Eigen::Vector3d(0, -0.1, 0.15)};
        l.object = Eigen::AlignedBox3d(c + Eigen::Vector3d(0, -a, -h), c + Eigen::Vector3d(2 * a, a, h));
      } else {
        // The top face: A, B near, C, D far (AD and BC point away from the sonar).
        l.features = {c + Eigen::Vector3d(-0.1, -0.1, 0), c + Eigen::Vector3d(-0.1, 0.1, 0),
                      c + Eigen::Vector3d(0.1, 0.1, 0), c + Eigen::Vector3d(0.1, -0.1, 0)};
        l.object = Eigen::AlignedBox3d(c + Eigen::Vector3d(-a, -a, 0), c + Eigen::Vector3d(a, a, 2 * h));
      }
      for (int k = 0; k < T; ++k) {
        l.poses.push_back(MakePose(0, 0, 0, WrapAngle(k * o.tank_roll_step), o.tank_pitch, 0));
      }
      l.name = "tank: the tank experiment of Mai et al. (tilted 20 deg, rolled 0..70 deg, 4 vertices)";
      break;
    }
  }
  if (o.preset != SonarPreset::kTank) {
    l.object = Eigen::AlignedBox3d(l.centre - Eigen::Vector3d(a, a, h), l.centre + Eigen::Vector3d(a, a, h));
  }
  // Every corner of the prism, the preset's features first.
  l.object_vertices = l.features;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner = l.object.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
    bool known = false;
    for (const Eigen::Vector3d& f : l.features) known = known || (f - corner).norm() < 1e-9;
    if (!known) l.object_vertices.push_back(corner);
  }
  return l;
}

AcousticSequence SimulateSonar(const SonarSimulationOptions& o) {
  SonarLayout l = MakeSonarLayout(o);
  Gaussian rng(o.seed);
  for (int i = 0; i < o.extra_features; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) p[a] = l.centre[a] + (rng.Uniform() - 0.5) * o.extra_box[a];
    l.features.push_back(p);
  }
  return DrawSequence(o, l.name, l.poses, l.features, nullptr, rng);
}

AcousticSequence SimulateSonarSequence(const SonarSimulationOptions& o, const std::string& name,
                                       const std::vector<Vector6d>& poses, const std::vector<Eigen::Vector3d>& features,
                                       const std::function<bool(int, int)>& visible) {
  Gaussian rng(o.seed);
  return DrawSequence(o, name, poses, features, visible, rng);
}

AcousticSequence SimulateSonarPreset(const std::string& preset, std::uint64_t seed) {
  SonarSimulationOptions o;
  o.preset = ParseSonarPreset(preset);
  o.seed = seed;
  return SimulateSonar(o);
}

}  // namespace hull
