// Hull forms for the simulators: a closed, ship-like parametric hull (flat
// bottom with a flat keel, bilge radius, tapered bow and stern, a rising
// forefoot and stern cut-up) at SS Curtiss size by default.
//
// Model frame M of the parametric hull: x forward from the aft end (x = 0)
// to the bow (x = length), y to port, z up from the keel (z = 0 at the
// midship keel); the waterline is at z = draft.
#pragma once

#include <string>

#include "base/error.h"
#include "geometry/triangle_mesh.h"

namespace hull {

struct HullFormOptions {
  double length = 183.0;           // m, SS Curtiss
  double beam = 27.0;              // m
  double draft = 9.1;              // m
  double depth = 14.0;             // m, keel to deck (closes the mesh above water)
  double bilge_radius = 2.5;       // m, at the parallel midbody
  double midbody_start = 0.30;     // fraction of length where the parallel midbody begins
  double midbody_end = 0.65;       // ... and ends (the bow taper starts here)
  double end_half_breadth = 0.04;  // fraction of the half-beam left at the ends
  double stern_rise = 3.0;         // m, keel rise at the aft end
  double bow_rise = 1.5;           // m, keel rise at the stem
  double station_spacing = 1.0;    // m between sections
  int bottom_points = 10;          // samples of the half bottom (flat keel to bilge)
  int bilge_points = 10;           // samples of the bilge arc
  int side_points = 10;            // samples of the side (bilge to deck)
  int deck_points = 4;             // samples of the half deck

  void Check() const;  // throws OptionError
};

// Closed, outward-oriented mesh in M (see above).
TriangleMesh MakeParametricHull(const HullFormOptions& options = {});

}  // namespace hull
