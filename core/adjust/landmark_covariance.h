// Per-landmark 3-D covariance from the adjustment, and its propagation to
// the signed distance h (an M3C2-style level of detection: a deviation is
// significant when |h| > k sigma_h).
//
// Three ways, chosen by AdjustmentOptions::covariance:
//  - kFull: the landmark blocks of (J^T J)^-1 (J at the solution, robust
//    losses applied) by the Schur complement of the landmarks
//    (landmark_covariance_schur.h: a sparse LDL^T of the reduced camera
//    system and its selected inverse): the marginal of each landmark with
//    the uncertainty of poses, servo, extrinsic and model pose folded in,
//    and its joint covariance with the model pose.
//  - kFullSparseQr: the same matrices by Ceres' Covariance (sparse QR of
//    the whole Jacobian): the former default, kept to check kFull against;
//    several times slower.
//    Both fall back to kConditional when the information matrix is
//    singular (the fallback is reported).
//  - kConditional: each landmark's own information (its residual blocks'
//    J^T J with every other block held fixed), inverted: cheap (linear in
//    the observations) but optimistic, since pose errors are ignored.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "adjust/landmark_jacobians.h"  // ceres::Problem, ceres::ResidualBlockId declared

namespace hull {

enum class CovarianceMethod { kNone, kConditional, kFull, kFullSparseQr };
const char* CovarianceMethodName(CovarianceMethod m);
// "none", "conditional", "full" or "full-qr"; throws OptionError("covariance")
// otherwise.
CovarianceMethod ParseCovarianceMethod(const std::string& name);

struct LandmarkCovariances {
  std::vector<Eigen::Matrix3d> covariance;  // per block, in the blocks' frame (g), symmetric; NaN when unavailable
  // Per block, sigma of h from the joint covariance of the landmark and the
  // model pose (kFull, kFullSparseQr with a surface residual); NaN where not
  // computed.
  std::vector<double> sigma_h;
  CovarianceMethod method = CovarianceMethod::kNone;  // what was used in the end
  std::string note;                                   // why a fallback happened, if it did
  double seconds = 0;                                 // wall time
  double cpu_seconds = 0;                             // process CPU time (all threads) over the same span
  // kFull: the columns of the reduced system S and the strictly lower
  // nonzeros of its LDL^T factor (0 otherwise).
  std::size_t reduced_size = 0, factor_nonzeros = 0;
};

// blocks: the landmark parameter blocks (3 doubles each) of `problem`, at
// the solution. num_threads > 0. With model_block (the model pose) and
// surface (per block, the residual block of its surface constraint, whose
// parameters are the model pose and the landmark; null where none), kFull
// and kFullSparseQr also give sigma_h: h moves with the landmark *relative to the model*,
// so the common motion of both (the survey's drift, which the landmark's
// marginal alone is dominated by) cancels. The gradient of h is the
// surface residual's Jacobian over [model, landmark] scaled so that its
// landmark part has unit length (dh/dl is the unit normal).
LandmarkCovariances ComputeLandmarkCovariances(ceres::Problem& problem, const std::vector<double*>& blocks,
                                               CovarianceMethod method, int num_threads, double* model_block = nullptr,
                                               const std::vector<ceres::ResidualBlockId>* surface = nullptr);

// sigma_h = sqrt(n^T Sigma n) for the unit surface normal n (same frame as
// Sigma); NaN when Sigma is.
double DeviationSigma(const Eigen::Matrix3d& covariance, const Eigen::Vector3d& normal);

}  // namespace hull
