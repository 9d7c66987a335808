// What the conditional covariance (landmark_covariance.h) and the cavity
// estimate (cavity_label.h) share: a landmark's residual blocks evaluated
// with the Jacobian over that landmark alone, every other block held fixed.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace ceres {
class Problem;
namespace internal {
class ResidualBlock;
}
using ResidualBlockId = internal::ResidualBlock*;  // as ceres/problem.h declares it
}  // namespace ceres

namespace hull::adjust {

// d(residuals)/d(landmark), one row per residual (robust losses applied).
using LandmarkJacobian = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Calls f(id, J) for each residual block of the parameter block `landmark`
// (3 values) that evaluates, in the order the problem lists them, at the
// parameter blocks' current values. Changes nothing in the problem, so
// different landmarks may be evaluated on different threads at once.
void ForEachLandmarkJacobian(const ceres::Problem& problem, double* landmark,
                             const std::function<void(ceres::ResidualBlockId, const LandmarkJacobian&)>& f);

}  // namespace hull::adjust
