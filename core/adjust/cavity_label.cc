#include "adjust/cavity_label.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <vector>

#include "adjust/adjust_options.h"

namespace hull::adjust {

CavityEstimate Cavity(const ceres::Problem& problem, double* landmark, ceres::ResidualBlockId surface, double h,
                      double sigma_label) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  CavityEstimate out{h, kNaN};
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocksForParameterBlock(landmark, &ids);
  Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  std::vector<double*> params;
  for (const ceres::ResidualBlockId id : ids) {
    params.clear();
    problem.GetParameterBlocksForResidualBlock(id, &params);
    const int nr = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
    std::vector<double> residuals(static_cast<std::size_t>(nr));
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> J(nr, 3);
    std::vector<double*> jacobians(params.size(), nullptr);
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (params[i] == landmark) jacobians[i] = J.data();
    }
    double cost = 0;
    if (!problem.EvaluateResidualBlock(id, true, &cost, residuals.data(), jacobians.data())) continue;
    if (id == surface) {
      n = J.row(0).transpose();
    } else {
      info += J.transpose() * J;
    }
  }
  if (!(n.norm() > 0)) return out;
  n.normalize();
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(info);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) return out;
  const double var = n.dot(ldlt.solve(n));
  if (!(var >= 0) || !std::isfinite(var)) return out;
  out.sigma = std::sqrt(var);
  out.h = h * (1.0 + var / (sigma_label * sigma_label));
  return out;
}

bool CavityOffModel(const CavityEstimate& c, double sigma0, double sigma1) {
  return std::isfinite(c.h) && MaxMixtureLabel(c.h, sigma0, sigma1) == 0;
}

}  // namespace hull::adjust
