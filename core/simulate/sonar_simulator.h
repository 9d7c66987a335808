// The imaging-sonar simulator: writes acoustic sequences with truth for the
// layouts of Mai et al. ("3-D Reconstruction of Underwater Object Based on
// Extended Kalman Filter by Using Acoustic Camera Images"):
//
//  prism  the paper's simulation: a square prism 0.2 x 0.2 x 0.3 m (8
//         vertices), T = 21 viewpoints about 2.5 m from it, the sonar facing
//         it (pitch = yaw = 0) while x, y, z and roll vary (the first pose
//         is the origin with zero attitude, the prism 2.5 m ahead; roll
//         swings through +-roll_amplitude, which makes the elevation
//         observable).
//         Features 0-3 are the top vertices (P, Q, R, S), 4-7 the bottom
//         ones (T, U, V, W).
//  tank   the paper's tank experiment: the sonar at the origin tilted 20 deg
//         down (pitch -0.349 with z down), rolled 0, 10, ..., 70 deg about its
//         boresight (T = 8), the prism about 2.5 m ahead with the boresight
//         through the centre of the face it shows the sonar. Four vertices
//         A, B, C, D (ids 0-3): by default those of that face (A, B top, C, D
//         bottom, so AB and CD are horizontal, AD and BC the 0.3 m vertical
//         edges: the geometry of the paper's Fig. 11, where AD and BC start
//         about 0.18 m wrong); tank_face = kTop uses the four top vertices
//         instead (A, B near, C, D far).
//  above  the prism trajectory raised above_height (0.5 m) above the prism's
//         centre, above_distance (3 m) from it, and pitched down so that the
//         prism lies in the lower half of the elevation fan (its centre at
//         above_centre_elevation): at the first view every true elevation has
//         the same sign, so the paper's elevation-0 start is biased for all
//         features at once (3 m rather than 2.5 m: the 0.3 m tall prism must
//         fit in half of the 14 deg fan).
//
// The world frame has z down. Controls are the true relative motion plus
// Gaussian noise with the contract's standard deviations (proportional to the
// motion, component by component, with floors); measurements are the true
// range and azimuth plus Gaussian noise (range_sigma, azimuth_sigma), both
// truncated at 4 sigma. Only features truly inside the field of view (range,
// azimuth and elevation) are measured, and a noisy measurement falling outside
// the range or azimuth limits is dropped. A short sequence (the tank's 32
// measurements) can draw a sample whose noise level is far from its sigma;
// the draws are repeated until the normalised RMS of the range, of the
// azimuth and of the control noise each lie within 15 % of 1 (what the
// contract checker expects of a sequence; long sequences never need a
// second draw). Deterministic from the seed on every platform
// (std::mt19937_64 and an own Box-Muller).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "survey/acoustic_sequence.h"

namespace hull {

enum class SonarPreset { kPrism, kTank, kAbove };
enum class TankFace { kFront, kTop };

// "prism" / "tank" / "above"; ParseSonarPreset throws OptionError on another name.
const char* SonarPresetName(SonarPreset preset);
SonarPreset ParseSonarPreset(const std::string& name);

struct SonarSimulationOptions {
  SonarPreset preset = SonarPreset::kPrism;
  // Seeds every random draw.
  std::uint64_t seed = 1;
  // Number of viewpoints T; 0 takes the preset's (prism and above 21, tank 8).
  int num_steps = 0;
  // Distance (m) from the first viewpoint to the prism's centre (tank: to the
  // centre of the face or top the features lie on).
  double distance = 2.5;
  // prism / above: roll sweeps between -roll_amplitude and +roll_amplitude (rad).
  double roll_amplitude = 0.6109;  // 35 deg
  // tank: roll step (rad) and tilt (pitch, rad; negative looks down with z down).
  double tank_roll_step = 0.17453292519943295;  // 10 deg
  double tank_pitch = -0.3490658503988659;      // -20 deg
  TankFace tank_face = TankFace::kFront;
  // above: height (m) of the trajectory above the prism's centre, horizontal
  // distance (m) from the first viewpoint to it and the elevation (rad,
  // positive below the boresight) of the prism's centre in the first view.
  double above_height = 0.5;
  double above_distance = 3.0;
  double above_centre_elevation = 0.061;  // 3.5 deg
  // Extra features at random in a box around the prism (benchmarks, larger
  // states); ids follow the preset's.
  int extra_features = 0;
  Eigen::Vector3d extra_box = Eigen::Vector3d(0.6, 1.2, 0.5);  // m, centred on the prism
  // The sensor and the noise written into the sequence.
  SonarSensor sensor;
  SonarMotionNoise motion_noise;
  Vector6d initial_pose_sigma = Vector6d::Constant(1e-3);
  // false: exact controls, measurements and initial pose (for tests of the model).
  bool noise = true;

  // True when every field is usable; otherwise false and, when why is given,
  // the field and the reason.
  bool Check(std::string* why = nullptr) const;
};

// Simulates an acoustic sequence with truth (throws OptionError when
// options.Check() fails).
AcousticSequence SimulateSonar(const SonarSimulationOptions& options);

// The geometry of a layout without noise: the true poses, the preset's
// features and the prism.
struct SonarLayout {
  std::string name;
  std::vector<Vector6d> poses;                       // per step, world frame (z down)
  std::vector<Eigen::Vector3d> features;             // the preset's features (without extra_features)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // of the prism (tank: of the featured face)
  Eigen::AlignedBox3d object;                        // the prism, axis-aligned
  std::vector<Eigen::Vector3d> object_vertices;      // its 8 corners, the preset's features first
};
// Throws OptionError when options.Check() fails.
SonarLayout MakeSonarLayout(const SonarSimulationOptions& options);

// SimulateSonar's noise (initial pose, controls, measurements; seeded by
// options.seed) for given true poses and features: feature i is measured at
// step k when it is inside the field of view and visible(k, i) (e.g. not
// occluded in a scene).
AcousticSequence SimulateSonarSequence(const SonarSimulationOptions& options, const std::string& name,
                                       const std::vector<Vector6d>& poses, const std::vector<Eigen::Vector3d>& features,
                                       const std::function<bool(int, int)>& visible);

// The presets with their defaults: "prism", "tank" or "above" (throws
// OptionError on another name). For hullinspect-cli simulate.
AcousticSequence SimulateSonarPreset(const std::string& preset, std::uint64_t seed);

}  // namespace hull
