#include "adjust/landmark_jacobians.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "adjust/factors/reprojection_factor.h"
#include "adjust/factors/surface_factor.h"

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

// d(residuals)/d(landmark) of an autodiff factor by jets over the landmark's
// 3 values alone, every other parameter a constant: the same derivatives
// Ceres' jets over all parameters give (each component is computed alone),
// at a sixth of the work for a reprojection factor's 18.
template <int kResiduals, int... Sizes, class Functor, std::size_t... I>
bool LandmarkJets(const Functor& functor, double const* const* params, std::size_t slot, double* residuals,
                  double* jacobian, std::index_sequence<I...>) {
  using Jet = ceres::Jet<double, 3>;
  std::tuple<std::array<Jet, Sizes>...> values;
  auto fill = [&](auto& block, std::size_t b) {
    for (std::size_t k = 0; k < block.size(); ++k) {
      block[k] = Jet(params[b][k]);
      if (b == slot && k < 3) block[k].v[static_cast<int>(k)] = 1.0;
    }
  };
  (fill(std::get<I>(values), I), ...);
  std::array<Jet, kResiduals> out;
  if (!functor(std::get<I>(values).data()..., out.data())) return false;
  for (int i = 0; i < kResiduals; ++i) {
    residuals[i] = out[static_cast<std::size_t>(i)].a;
    for (int k = 0; k < 3; ++k) jacobian[3 * i + k] = out[static_cast<std::size_t>(i)].v[k];
  }
  return true;
}

// The landmark jets of `cost` when it is an autodiff factor of type Functor
// (*evaluated: whether it evaluated); false when it is another type.
template <class Functor, int kResiduals, int... Sizes>
bool TryLandmarkJets(const ceres::CostFunction* cost, double const* const* params, std::size_t slot, double* residuals,
                     double* jacobian, bool* evaluated) {
  const auto* autodiff = dynamic_cast<const ceres::AutoDiffCostFunction<Functor, kResiduals, Sizes...>*>(cost);
  if (!autodiff) return false;
  *evaluated = LandmarkJets<kResiduals, Sizes...>(autodiff->functor(), params, slot, residuals, jacobian,
                                                  std::index_sequence_for<std::integral_constant<int, Sizes>...>());
  return true;
}

// One block's residuals and d/d(landmark): by the landmark's jets for the
// adjustment's own factors, else by the cost function over every parameter.
bool EvaluateForLandmark(const ceres::CostFunction* cost, const std::vector<double*>& params, std::size_t slot,
                         double* residuals, double* jacobian) {
  bool ok = false;
  if (TryLandmarkJets<StereoReprojectionFactor, 4, kPoseSize, 1, kPoseSize, 3>(cost, params.data(), slot, residuals,
                                                                               jacobian, &ok) ||
      TryLandmarkJets<MonoReprojectionFactor, 2, kPoseSize, 1, kPoseSize, 3>(cost, params.data(), slot, residuals,
                                                                             jacobian, &ok) ||
      TryLandmarkJets<SurfaceFactor, 2, kPoseSize, 3>(cost, params.data(), slot, residuals, jacobian, &ok)) {
    return ok;
  }
  std::vector<double*> jacobians(params.size(), nullptr);
  jacobians[slot] = jacobian;
  return cost->Evaluate(params.data(), residuals, jacobians.data());
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
  std::vector<double> residuals;
  LandmarkJacobian J;
  for (const ceres::ResidualBlockId id : ids) {
    params.clear();
    problem.GetParameterBlocksForResidualBlock(id, &params);
    const ceres::CostFunction* cost = problem.GetCostFunctionForResidualBlock(id);
    const int n = cost->num_residuals();
    residuals.assign(static_cast<std::size_t>(n), 0.0);
    J.resize(n, 3);
    const auto slot = static_cast<std::size_t>(std::find(params.begin(), params.end(), landmark) - params.begin());
    if (slot == params.size() || !EvaluateForLandmark(cost, params, slot, residuals.data(), J.data())) continue;
    // As Ceres' ResidualBlock::Evaluate: a block with a non-finite value did not evaluate.
    if (!Eigen::Map<const Eigen::VectorXd>(residuals.data(), n).allFinite() || !J.allFinite()) continue;
    if (const ceres::LossFunction* loss = problem.GetLossFunctionForResidualBlock(id))
      CorrectForLoss(*loss, residuals, &J);
    f(id, J);
  }
}

}  // namespace hull::adjust
