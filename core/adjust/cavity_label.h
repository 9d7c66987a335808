// The E-step of the max-mixture by a landmark's cavity estimate
// (AdjustmentOptions::labels = LabelRule::kCavity).
//
// A landmark on the model (lambda = 1) is held toward the hull by its own
// surface factor with sigma1: its estimate h is the compromise of what its
// observations say (h_c, with variance sigma_c^2 along the direction of h)
// and that factor, h = h_c sigma1^2 / (sigma1^2 + sigma_c^2). Judged by h,
// a feature of a low object whose observations put it above the decision
// boundary is pulled below it by the very component the label chose, and
// stays there. Its cavity estimate -- the landmark with its own surface
// factor taken out, the rest of the problem held at the solution -- is
// h_c = h (1 + sigma_c^2 / sigma_lambda^2) to first order, and the label is
// the component under which h_c is the more likely.
#pragma once

#include <Eigen/Core>

#include "adjust/landmark_jacobians.h"  // ceres::Problem, ceres::ResidualBlockId declared

namespace hull::adjust {

struct CavityEstimate {
  double h = 0;      // the cavity estimate of the signed distance h (m)
  double sigma = 0;  // its standard deviation along the direction of h (m); NaN: the observations fix no height
};

// The cavity estimate of the landmark `landmark` of `problem` at its current
// state: sigma_c^2 = n^T (J^T J)^-1 n over its residual blocks other than
// `surface` (every other parameter block held fixed, robust losses applied),
// n the unit direction of h (the gradient of `surface`'s first residual over
// the landmark), and h_c = h (1 + sigma_c^2 / sigma_label^2), h the current
// signed distance and sigma_label the sigma of the component its surface
// factor applies now. NaN sigma (and h_c = h) when the other blocks do not
// fix the landmark's height.
CavityEstimate Cavity(const ceres::Problem& problem, double* landmark, ceres::ResidualBlockId surface, double h,
                      double sigma_label);

// Whether the max-mixture puts a cavity estimate off the model: the label
// of h_c (MaxMixtureLabel) is 0.
bool CavityOffModel(const CavityEstimate& c, double sigma0, double sigma1);

// The E-step for one landmark at signed distance h, `off` whether it is
// labelled off by its cavity estimate now; returns whether it is after this
// step. One on the model (by h) whose cavity estimate is off it is labelled
// off; one labelled off earlier whose estimate (its cavity estimate: sigma0
// hardly pulls it) is back on the model -- a wrong observation removed
// since, a linearisation that overshot -- is given back to the max-mixture;
// one the max-mixture puts off by h stays as it is.
bool CavityLabelOff(const ceres::Problem& problem, double* landmark, ceres::ResidualBlockId surface, double h, bool off,
                    double sigma0, double sigma1);

}  // namespace hull::adjust
