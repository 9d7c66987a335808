// The underwater image renderer: what a strobe-lit monochrome camera on the
// HAUV sees of the true surface (hull plus foreign objects), ray cast with
// Embree through the exact pinhole of the survey bundle, so that a true
// landmark projected with the bundle's camera model lands on the surface
// point the image shows there.
//
// Per pixel: the first surface hit; its albedo (SurfaceAlbedo, band-limited
// to the pixel's footprint); the irradiance from each strobe (beam pattern,
// inverse-square falloff, Lambert's cosine, a shadow ray) attenuated by the
// water on the strobe->surface and surface->camera paths (Beer-Lambert);
// plus the backscatter veil (single scattering of the strobe light along the
// camera ray, integrated once per camera into a table); natural vignetting
// (cos^4); sensor shot and read noise; a linear 8-bit grey response.
// Deterministic from the noise seed.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "simulate/imaging_options.h"
#include "simulate/true_scene.h"
#include "survey/survey.h"

namespace hull {

// The strobes of `options` (given in cT) expressed in camera frame c, where
// x_cT_c places c in cT (identity for the top camera, x_cT_cB for the bottom).
std::vector<Strobe> StrobesInCamera(const std::vector<Strobe>& strobes_cT, const Pose& x_cT_c);

// One camera of the rig with its strobes: the per-camera tables (the
// backscatter veil, the exposure gain) are built once and reused for every
// view. Render() is const and may run concurrently.
class UnderwaterCamera {
 public:
  UnderwaterCamera(const PinholeIntrinsics& intrinsics, int width, int height, std::vector<Strobe> strobes_c,
                   const UnderwaterImagingOptions& options);

  // An 8-bit grey image of the scene seen from camera pose x_Mc (the camera
  // in the model frame M). range (if not null) receives the distance to the
  // surface along each pixel's ray (CV_32F, metres; 0 where nothing is hit);
  // signal (if not null) the noise-free exposure before quantisation (CV_32F,
  // share of full scale: the image is 255 x signal plus sensor noise).
  cv::Mat Render(const TrueScene& scene, const Pose& x_Mc, std::uint64_t noise_seed, cv::Mat* range = nullptr,
                 cv::Mat* signal = nullptr) const;

  // Unit ray (camera frame) through pixel position (u, v): the ray Render
  // casts through a pixel centre (u, v integers), pinhole of survey.json.
  Eigen::Vector3d Ray(double u, double v) const { return intrinsics_.Unproject({u, v}).normalized(); }
  // The surface point imaged at pixel position (u, v).
  RayHit SurfaceAt(const TrueScene& scene, const Pose& x_Mc, double u, double v) const;

  // The noise-free exposure Render() models at a lit surface point, as a
  // linear function of the albedo: signal = per_albedo * albedo + offset
  // (share of full scale), for the point p_c (camera frame) with unit normal
  // n_c seen at pixel position (u, v): strobe beam, inverse-square fall-off,
  // Lambert's cosine and Beer-Lambert attenuation in per_albedo, the
  // backscatter veil in offset, both times vignetting and the gain. Strobe
  // shadows are not modelled (the point is taken as lit by every strobe). A
  // photomosaic inverts it: albedo = (signal - offset) / per_albedo.
  struct Response {
    double per_albedo = 0, offset = 0;
  };
  Response ResponseAt(const Eigen::Vector3d& p_c, const Eigen::Vector3d& n_c, double u, double v) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const PinholeIntrinsics& intrinsics() const { return intrinsics_; }

 private:
  // A strobe ready for shading: unit axis, beam = exp(-beam_k (1 - cos angle)).
  struct Light {
    Eigen::Vector3d position, axis;
    double intensity = 1, beam_k = 1;
    Light InFrame(const Pose& x_fc) const { return {x_fc * position, x_fc.Rotate(axis), intensity, beam_k}; }
    // Light reaching point p with unit normal n (same frame as the light),
    // through water of attenuation c; unshadowed.
    double Irradiance(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double c) const;
  };
  void BuildVeil();
  float Veil(int u, int v, float range) const;

  PinholeIntrinsics intrinsics_;
  int width_, height_;
  std::vector<Light> lights_;  // in the camera frame
  UnderwaterImagingOptions options_;
  double gain_ = 1;  // radiance -> share of full scale
  // Veil table: nodes every kVeilStep pixels, cumulative integral at ranges
  // max_range * (k / kVeilSamples)^2.
  int veil_nu_ = 0, veil_nv_ = 0;
  std::vector<float> veil_;
};

}  // namespace hull
