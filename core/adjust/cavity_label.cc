#include "adjust/cavity_label.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <vector>

#include "adjust/adjust_options.h"
#include "adjust/landmark_jacobians.h"

namespace hull::adjust {

CavityEstimate Cavity(const ceres::Problem& problem, double* landmark, ceres::ResidualBlockId surface, double h,
                      double sigma_label) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  CavityEstimate out{h, kNaN};
  Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  ForEachLandmarkJacobian(problem, landmark, [&](ceres::ResidualBlockId id, const LandmarkJacobian& J) {
    if (id == surface) {
      n = J.row(0).transpose();
    } else {
      info += J.transpose() * J;
    }
  });
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

bool CavityLabelOff(const ceres::Problem& problem, double* landmark, ceres::ResidualBlockId surface, double h, bool off,
                    double sigma0, double sigma1) {
  if (off) return CavityOffModel(Cavity(problem, landmark, surface, h, sigma0), sigma0, sigma1);
  if (MaxMixtureLabel(h, sigma0, sigma1) != 1) return false;
  return CavityOffModel(Cavity(problem, landmark, surface, h, sigma1), sigma0, sigma1);
}

}  // namespace hull::adjust
