// A lump's apex estimated beyond its highest feature (issue 12, part 1).
// Sparse features sample a smooth peak below its apex: at 300 features per
// m^2 the top centimetre of a narrow lump (a few cm across) holds a feature
// less often than not, and the gap between the apex and the highest feature
// is about kappa / (2 pi rho) for a paraboloid apex of curvature kappa
// sampled at density rho (1-2 cm on the simulated strip lumps). The remedy
// of sub-pixel peak localisation: around each local maximum of the
// supported features, a quadric height model
//
//   h(u, v) = a + b u + c v + d u^2 + e u v + f v^2
//
// (u, v: coordinates in the CAD's tangent plane at the top feature's foot,
// h: the features' signed deviation) is fitted by least squares; by default
// the rotationally symmetric one, e = 0 and d = f (4 unknowns: within a few
// centimetres of a top there are too few features for 6, and the full
// quadric put flat-topped lumps' apexes centimetres above them). The fit
// takes the adjusted landmarks within `radius` whose deviation is at most
// `cap` below the top feature (the cap, where a paraboloid holds), and its
// apex is accepted only when it is an honest interpolation
// (docs/mapping.md, "Fitting a lump's apex"):
//
// - the top feature is a shape vertex in at least `support` keyframes and
//   stands above min_height (what the fusion's support rule would raise),
//   and no higher such feature lies within `radius`;
// - at least min_features features, held by the shapes of at least
//   min_keyframes keyframes;
// - the quadric is concave (negative-definite Hessian) and its apex lies
//   inside the convex hull of the fitted features' (u, v): no
//   extrapolation beyond the support;
// - the residual RMS is at most max_rms;
// - each fit's estimate is the lower of its apex and the feature nearest
//   that apex raised by the rise the fit predicts from it (where features
//   are dense one lies at the apex, and the fit's misfit cannot lift it);
// - leave-one-out: the fit is repeated without each feature in turn; every
//   one of those fits must pass the same tests, their apexes must agree
//   within loo_spread, and the apex taken is the lowest estimate of them
//   all. So no single feature (a wrong match) can raise the apex above
//   what the others support;
// - it rises above the highest supported feature, by at most max_rise.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/mesh_index.h"
#include "mapping/mapping_input.h"
#include "mapping/mapping_options.h"
#include "mapping/shape_detection.h"

namespace hull {

struct PeakFitOptions {
  double radius = 0.10;       // m, features fitted around the top feature (tangent-plane distance)
  int min_features = 6;       // features in the fit
  int min_keyframes = 2;      // keyframes whose shapes hold the fitted features
  int support = 2;            // keyframes whose shapes must hold the top feature
  double min_height = 0.03;   // m, the top feature must stand above it (h_min)
  double max_rms = 0.008;     // m, residual RMS of the fit
  double max_rise = 0.035;    // m, the apex above the highest supported feature at most
  double loo_spread = 0.010;  // m, the leave-one-out apexes agree within it
  double cap = 0.04;          // m, only features at most this far below the top feature (0: all)
  int near_features = 1;      // features nearest the apex whose raised height bounds it
  bool isotropic = true;      // h = a + b u + c v + d (u^2 + v^2); false: the full quadric
};

struct FittedPeak {
  int landmark = -1;                                  // the top feature (index into MappingInput::landmarks)
  double top = 0;                                     // its deviation (m)
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();     // the apex's foot on the CAD (in M)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // the CAD's outward normal there (in M)
  double height = 0;                                  // the apex's deviation (m; the leave-one-out minimum)
  double full_height = 0;                             // the apex of the fit over every feature (m)
  int features = 0;                                   // features fitted
  int keyframes = 0;                                  // keyframes whose shapes hold them
  double rise = 0;                                    // the fit's apex above its value at the feature nearest it (m)
  double rms = 0;                                     // residual RMS of the fit over every feature (m)
  bool accepted = false;
  std::string reason;     // why not accepted ("" when accepted)
  std::string placement;  // accepted: what the fusion made of it ("placed", or why not)
  int vertex = -1;        // placed: the model vertex raised to the apex
};

// The fit's options from the mapping's: support and min_height are the
// fusion's (fusion_support, object_min_height), the rest PeakFitOptions'.
PeakFitOptions PeakFitOptionsFor(const MappingOptions& options);

// One result per candidate (a supported feature above min_height that no
// other supported feature within `radius` exceeds), accepted or not, highest
// top first. x_Mg: the mapping input's x_gM inverted. Deterministic.
std::vector<FittedPeak> FitPeaks(const MappingInput& input, const MeshIndex& cad,
                                 const std::vector<KeyframeShapes>& shapes, const PeakFitOptions& options);

// The quadric fit itself, for the tests: (u, v, h) samples; returns false
// (with *reason) when the fit is not concave, its apex lies outside the
// samples' convex hull or the system is singular. *apex_uv, *apex_h: the
// apex; *rms: the residual RMS.
bool FitQuadricApex(const std::vector<Eigen::Vector3d>& uvh, bool isotropic, Eigen::Vector2d* apex_uv, double* apex_h,
                    double* rms, std::string* reason, std::vector<double>* fitted = nullptr);

}  // namespace hull
