// The true albedo of a simulated hull and its foreign objects: what the
// underwater renderer images and what a photomosaic is scored against.
//
// Procedural and deterministic from a seed, defined in model coordinates (M)
// so that every view of a spot sees the same texture: no repeating tile, no
// texture coordinates. The hull carries anti-fouling paint with slow tone
// changes, biofilm blotches, abraded paint showing the lighter primer,
// rust streaks along the flow, weld seams between plates (longitudinal seams
// every 2 m of girth, staggered butts every 3 m along the hull) and a fine
// grain; about a fifth of it is clean paint with little texture (the hull is
// not uniformly salient, Ozog et al. Section 2.5). Fouling patches carry
// barnacle-like shells on a dark weed film, the cylinder white paint with
// dark markings and rust specks, the box bare metal with hazard stripes.
//
// Albedo is a reflectance in [0.03, 0.9] at the strobe's wavelength (the
// camera is monochrome). `footprint` is the surface length one pixel covers
// (m): texture finer than about two footprints is left out, as a camera's
// optics would blur it (0 keeps every octave down to 7.5 mm).
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "simulate/procedural_noise.h"
#include "survey/survey.h"

namespace hull {

enum class SurfaceMaterial { kHullPaint, kFouling, kPaintedSteel, kBareMetal };

// patch -> fouling, cylinder -> painted steel, box -> bare metal.
SurfaceMaterial MaterialOf(ObjectKind kind);

class SurfaceAlbedo {
 public:
  // forward and up: the hull's axes in M (seams and streaks follow them).
  SurfaceAlbedo(std::uint64_t seed, const Eigen::Vector3d& forward, const Eigen::Vector3d& up);

  // Albedo at p (in M) on a surface with unit normal n; object: the truth
  // object the point lies on, or nullptr for the hull.
  float At(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const TrueObject* object, float footprint) const {
    return object ? OnObject(*object, p, n, footprint) : OnHull(p, n, footprint);
  }
  float OnHull(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float footprint) const;
  float OnObject(const TrueObject& object, const Eigen::Vector3f& p, const Eigen::Vector3f& n, float footprint) const;
  // OnObject for n points at once (objects[i]: point i's object; positions,
  // normals, footprints as in HullBatch); the same values, the shared
  // texture layers computed kLanes points at a time.
  void ObjectBatch(const TrueObject* const* objects, const float* px, const float* py, const float* pz, const float* nx,
                   const float* ny, const float* nz, const float* footprint, int n, float* out) const;
  // OnHull for n points at once (structure of arrays: positions, normals,
  // footprints), about four times faster per point; the same values.
  void HullBatch(const float* px, const float* py, const float* pz, const float* nx, const float* ny, const float* nz,
                 const float* footprint, int n, float* out) const;
  // HullBatch for points along a line of pixels (an image row's hull hits,
  // in order), cheaper still: the coarsest texture (paint tone, blotches and
  // clean zones, 12 cm and longer) is computed exactly every 6th point and
  // interpolated linearly between where the points lie on a short straight
  // segment (within 1.5 cm, 0.5 mm off the line; exact elsewhere), so it
  // differs from OnHull by well under 0.01 in albedo.
  void HullRow(const float* px, const float* py, const float* pz, const float* nx, const float* ny, const float* nz,
               const float* footprint, int n, float* out) const;

  std::uint64_t seed() const { return seed_; }
  const Eigen::Vector3d& forward() const { return forward_; }
  const Eigen::Vector3d& up() const { return up_; }

 private:
  static constexpr int kLanes = NoiseLattice::kLanes;
  // The shared texture layers (blotch, wear, tone, grain) of m <= kLanes points.
  void Layers(const float* px, const float* py, const float* pz, const float* footprint, int m,
              float (&layer)[4][kLanes]) const;
  void Layers(const Eigen::Vector3f& p, float footprint, float (&layer)[4]) const;
  // Adds octaves k0 <= k < k1 of the layers.
  void Octaves(const float* px, const float* py, const float* pz, const float* footprint, int m, int k0, int k1,
               float (&layer)[4][kLanes]) const;
  // The coarse octaves of the layers and the clean-zone noise.
  void Coarse(const float* px, const float* py, const float* pz, const float* footprint, int m,
              float (&layer)[4][kLanes], float* zone) const;
  // coarse (if not null): the coarse layers (coarse[0..3]) and zones
  // (coarse[4]) of the m points, else computed.
  void HullChunk(const float* px, const float* py, const float* pz, const float* nx, const float* ny, const float* nz,
                 const float* footprint, int m, const float* const* coarse, float* out) const;
  float ObjectFromLayers(const TrueObject& object, const Eigen::Vector3f& p, const Eigen::Vector3f& n, float footprint,
                         const float (&layer)[4]) const;
  float Fouling(const Eigen::Vector3f& p, float footprint, const float (&layer)[4]) const;

  std::uint64_t seed_;
  Eigen::Vector3d forward_, up_;
  Eigen::Vector3f f_, u_, q_;  // forward, up, port (single precision, for the per-pixel work)
  GradientNoise noise_, coarse_, streaks_;
};

}  // namespace hull
