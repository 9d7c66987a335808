#include "adjust/landmark_jacobians.h"

#include <ceres/ceres.h>

#include <vector>

namespace hull::adjust {

void ForEachLandmarkJacobian(const ceres::Problem& problem, double* landmark,
                             const std::function<void(ceres::ResidualBlockId, const LandmarkJacobian&)>& f) {
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocksForParameterBlock(landmark, &ids);
  std::vector<double*> params;
  for (const ceres::ResidualBlockId id : ids) {
    params.clear();
    problem.GetParameterBlocksForResidualBlock(id, &params);
    const int n = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
    std::vector<double> residuals(static_cast<std::size_t>(n));
    LandmarkJacobian J(n, 3);
    std::vector<double*> jacobians(params.size(), nullptr);
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (params[i] == landmark) jacobians[i] = J.data();
    }
    double cost = 0;
    if (!problem.EvaluateResidualBlock(id, true, &cost, residuals.data(), jacobians.data())) continue;
    f(id, J);
  }
}

}  // namespace hull::adjust
