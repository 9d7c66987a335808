#include "adjust/landmark_jacobians.h"

#include <ceres/ceres.h>

#include <cmath>
#include <vector>

namespace hull::adjust {
namespace {

// Applies a robust loss to a block's Jacobian as Ceres' Corrector does
// (Triggs et al., "Bundle adjustment: a modern synthesis", 4.3): with
// s = |r|^2 and rho(s), J <- sqrt(rho') (I - alpha r r^T / s) J, alpha from
// rho''; for losses with rho'' <= 0 (Huber, Cauchy, ...) J <- sqrt(rho') J.
void CorrectForLoss(const ceres::LossFunction& loss, const std::vector<double>& r, LandmarkJacobian* J) {
  double s = 0;
  for (double v : r) s += v * v;
  double rho[3];
  loss.Evaluate(s, rho);
  const double sqrt_rho1 = std::sqrt(rho[1]);
  if (s == 0.0 || rho[2] <= 0.0) {
    *J *= sqrt_rho1;
    return;
  }
  const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * s * rho[2] / rho[1]);
  const double alpha_sq_norm = alpha / s;
  const Eigen::Map<const Eigen::VectorXd> rv(r.data(), static_cast<Eigen::Index>(r.size()));
  const Eigen::RowVector3d rtj = rv.transpose() * (*J);
  *J = sqrt_rho1 * (*J - alpha_sq_norm * rv * rtj);
}

}  // namespace

// Evaluates each block's cost function directly at the parameters' current
// values (Problem::EvaluateResidualBlock would also work, but it updates the
// problem's copy of every parameter block's state, so two landmarks could not
// be evaluated at once, and it costs an allocation and a state copy per call).
void ForEachLandmarkJacobian(const ceres::Problem& problem, double* landmark,
                             const std::function<void(ceres::ResidualBlockId, const LandmarkJacobian&)>& f) {
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocksForParameterBlock(landmark, &ids);
  std::vector<double*> params;
  std::vector<double*> jacobians;
  std::vector<double> residuals;
  LandmarkJacobian J;
  for (const ceres::ResidualBlockId id : ids) {
    params.clear();
    problem.GetParameterBlocksForResidualBlock(id, &params);
    const ceres::CostFunction* cost = problem.GetCostFunctionForResidualBlock(id);
    const int n = cost->num_residuals();
    residuals.assign(static_cast<std::size_t>(n), 0.0);
    J.resize(n, 3);
    jacobians.assign(params.size(), nullptr);
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (params[i] == landmark) jacobians[i] = J.data();
    }
    if (!cost->Evaluate(params.data(), residuals.data(), jacobians.data())) continue;
    // As Ceres' ResidualBlock::Evaluate: a block with a non-finite value did not evaluate.
    if (!Eigen::Map<const Eigen::VectorXd>(residuals.data(), n).allFinite() || !J.allFinite()) continue;
    if (const ceres::LossFunction* loss = problem.GetLossFunctionForResidualBlock(id))
      CorrectForLoss(*loss, residuals, &J);
    f(id, J);
  }
}

}  // namespace hull::adjust
