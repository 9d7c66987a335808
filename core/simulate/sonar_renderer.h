// Renders polar acoustic images (ARIS/DIDSON-like) of a SonarScene with
// Embree, the kind of model HoloOcean uses for its imaging sonar:
//  - every beam sends a fan of rays over the elevation aperture (and a few
//    across its width); the first hit of each ray is its echo, so anything
//    behind a nearer surface lies in its acoustic shadow;
//  - a hit returns reflectivity * |cos(incidence)|^exponent (the surface's
//    material) times the elevation beam pattern, the spreading loss
//    r^-spreading_exponent and the two-way absorption; consecutive rays on
//    the same flat surface spread their echo evenly over the range bins
//    between their hits (a surface is continuous, not a set of samples), and
//    at a surface's edge over the range its plane covers up to the end of
//    the ray's elevation interval;
//  - point scatterers (the object's vertices) return their strength with
//    the same losses, where the scene shows them (in view, not occluded);
//  - the azimuth beam pattern (main lobe and side lobes, which smear bright
//    returns across beams) is applied along each row;
//  - multiplicative speckle (intensity Gamma-distributed with `speckle_looks`
//    looks) on the surfaces' echoes, a milder fluctuation on the point
//    scatterers, and additive receiver noise (exponential intensity);
//  - the intensity is stored in decibels as 8-bit grey: 255 at
//    0 dB + gain_db, 0 at -dynamic_range_db.
// Intensities are relative: 1 is the strongest return a surface can give a
// pixel (reflectivity 1 seen head-on across the whole elevation fan, in one
// range bin, before losses).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "simulate/sonar_scene.h"
#include "survey/acoustic_sequence.h"

namespace hull {

struct SonarRenderOptions {
  // Rays per beam over the elevation aperture, and across the beam's width.
  int elevation_rays = 48;
  int azimuth_rays = 2;
  // Echo intensity falls as r^-spreading_exponent (two-way spherical
  // spreading is 4; the sonar's time-varying gain gives most of it back).
  double spreading_exponent = 1.0;
  // Absorption (dB per metre, one way; applied over the two-way path).
  // Fresh water at 1.8 MHz: about 0.4 dB/m.
  double absorption_db_per_m = 0.4;
  // Elevation beam pattern: Gaussian in the elevation, this many dB down at the fan's edges.
  double elevation_edge_db = -3.0;
  // Azimuth beam pattern sinc^2(x / null_beams) over x beams from the beam's
  // axis, side lobes (beyond the first null) lowered by sidelobe_db, cut
  // after pattern_radius beams.
  double null_beams = 1.2;
  double sidelobe_db = -12.0;
  int pattern_radius = 12;
  // Speckle of the surfaces' echoes: number of looks of the Gamma-distributed
  // intensity (1: fully developed speckle, exponential intensity).
  int speckle_looks = 2;
  // Looks of the point scatterers' fluctuation (a dominant scatterer barely fluctuates).
  int point_looks = 16;
  // Mean intensity of the receiver noise (exponential).
  double noise_level = 2e-6;
  // Encoding: 8-bit dB, 255 at 0 dB + gain_db, 0 at -dynamic_range_db.
  double gain_db = 0.0;
  double dynamic_range_db = 60.0;

  bool Check(std::string* why = nullptr) const;
};

class SonarRenderer {
 public:
  // The scene must outlive the renderer. Throws OptionError when
  // options.Check() fails.
  SonarRenderer(const SonarScene& scene, const SonarSensor& sensor, const SonarImageFormat& format,
                const SonarRenderOptions& options = {});
  ~SonarRenderer();
  SonarRenderer(const SonarRenderer&) = delete;
  SonarRenderer& operator=(const SonarRenderer&) = delete;

  // Linear intensity (CV_32F, range_bins x beams) seen from a pose; seed
  // draws the speckle and noise. Thread-safe.
  cv::Mat RenderIntensity(const Vector6d& pose, std::uint64_t seed) const;
  // The 8-bit dB encoding of an intensity image.
  cv::Mat Encode(const cv::Mat& intensity) const;
  cv::Mat Render(const Vector6d& pose, std::uint64_t seed) const { return Encode(RenderIntensity(pose, seed)); }

  // A world point inside the field of view (range, azimuth, elevation) and
  // not hidden behind a surface of the scene.
  bool Sees(const Vector6d& pose, const Eigen::Vector3d& p) const;

  const SonarRenderOptions& options() const { return options_; }

 private:
  double Loss(double range) const;
  double ElevationWeight(double phi) const;
  double BeamPattern(double beams_off_axis) const;

  const SonarScene& scene_;
  SonarSensor sensor_;
  SonarImageFormat format_;
  SonarRenderOptions options_;
  std::unique_ptr<MeshIndex> index_;
  // Ray directions in the sonar frame: [beam][azimuth ray][elevation ray].
  std::vector<Eigen::Vector3d> directions_;
  // The boundaries between their elevation intervals: [beam][azimuth ray][elevation ray + 1].
  std::vector<Eigen::Vector3d> boundaries_;
  std::vector<double> elevation_weight_;  // per elevation ray, times its share of the fan
  cv::Mat pattern_;                       // 1 x (2 radius + 1) azimuth kernel
};

}  // namespace hull
