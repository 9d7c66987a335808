// The surface constraint on one landmark (eqs. 4, 5 and 7 of Ozog et al.):
//   h(x_gM, l) = (H l - p)^T n / |n|,   H = (-)x_gM (maps g into M),
// with p the closest point of the prior mesh and n the outward normal of its
// face, looked up afresh at every evaluation (data association per
// iteration) and held constant for the derivative (see SurfaceDirection for
// points beyond a face's edge). Measurement z = 0.
//
//   all-on-surface:  r = h / sigma1                       (every lambda = 1)
//   max-mixture:     p(z|X) = eta max_lambda N(h; 0, sigma_lambda^2), equal weights.
//     The label is the component with the lower negative log-likelihood
//       0.5 (h / sigma)^2 + ln sigma,
//     chosen where the likelihood is evaluated (E- and M-steps merged). The
//     normalisation stays in the cost as a constant second residual
//     sqrt(2 ln(sigma / sigma_min)) (libRSF's MaxMixture), so the cost is a
//     sum of squares and the chosen label is the true maximum.
//     With `off_model` (LabelRule::kCavity) pointing at a nonzero flag, the
//     label is 0 whatever h: the E-step between solves found the landmark's
//     cavity estimate off the model (cavity_label.h).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <atomic>
#include <cmath>

#include "adjust/adjust_options.h"
#include "adjust/factors/pose_math.h"
#include "geometry/mesh_index.h"

namespace hull::adjust {

// The direction along which h is measured for a point q (in M) whose
// closest point on the mesh is sd.point: the outward normal of its face
// (eq. 5) when q lies over the face's interior; where the closest point is on
// an edge or a vertex of the face (q beyond the face's boundary), the unit
// direction from it to q, signed by the face normal -- the limit of eq. 5 from
// every face that meets there, so h stays continuous instead of jumping
// between the planes of faces meeting at a sharp edge.
inline Eigen::Vector3d SurfaceDirection(const SurfaceDistance& sd, const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - sd.point;
  const double along = d.dot(sd.normal);
  const Eigen::Vector3d tangential = d - along * sd.normal;
  if (tangential.norm() > 1e-6 + 1e-3 * d.norm()) return (along >= 0 ? 1.0 : -1.0) * d.normalized();
  return sd.normal;
}

// h(x_gM, l) for plain doubles, as the factor evaluates it.
inline double SurfaceDeviation(const MeshIndex& mesh, const Pose& x_gM, const Eigen::Vector3d& l_g,
                               SurfaceLookup lookup, int* hint = nullptr) {
  const Eigen::Vector3d q = x_gM.Inverse() * l_g;
  const SurfaceDistance sd = mesh.OrthogonalSignedDistance(q, lookup, hint ? *hint : -1);
  if (hint) *hint = sd.face;
  return SurfaceDirection(sd, q).dot(q - sd.point);
}

class SurfaceFactor {
 public:
  // model_offset: x_CM, with the model pose block holding x_gC (x_gM = x_gC (+) x_CM).
  SurfaceFactor(const MeshIndex* mesh, const Pose* model_offset, SurfaceLookup lookup, SurfaceModel model,
                double sigma0, double sigma1, const char* off_model = nullptr)
      : mesh_(mesh),
        offset_(model_offset),
        lookup_(lookup),
        max_mixture_(model == SurfaceModel::kMaxMixture),
        sigma0_(sigma0),
        sigma1_(sigma1),
        offset0_(std::sqrt(2.0 * std::log(sigma0 / sigma1))),
        off_model_(off_model) {}

  template <typename T>
  bool operator()(const T* x_gC, const T* landmark, T* residual) const {
    const PoseT<T> Mg = (PoseFromBlock(x_gC) * PoseConstant<T>(*offset_)).Inverse();
    const Eigen::Matrix<T, 3, 1> lM = Mg * Eigen::Matrix<T, 3, 1>(landmark[0], landmark[1], landmark[2]);
    const SurfaceDistance sd =
        mesh_->OrthogonalSignedDistance(ScalarOf(lM), lookup_, hint_.load(std::memory_order_relaxed));
    hint_.store(sd.face, std::memory_order_relaxed);
    const Eigen::Vector3d dir = SurfaceDirection(sd, ScalarOf(lM));
    const T h = dir.cast<T>().dot(lM - sd.point.cast<T>());
    const bool forced_off = max_mixture_ && off_model_ && *off_model_;
    if (!max_mixture_ || (!forced_off && MaxMixtureLabel(ScalarOf(h), sigma0_, sigma1_) == 1)) {
      residual[0] = h / T(sigma1_);
      residual[1] = T(0);
    } else {
      residual[0] = h / T(sigma0_);
      residual[1] = T(offset0_);
    }
    return true;
  }

  static ceres::CostFunction* Create(const MeshIndex* mesh, const Pose* model_offset, SurfaceLookup lookup,
                                     SurfaceModel model, double sigma0, double sigma1,
                                     const char* off_model = nullptr) {
    return new ceres::AutoDiffCostFunction<SurfaceFactor, 2, kPoseSize, 3>(
        new SurfaceFactor(mesh, model_offset, lookup, model, sigma0, sigma1, off_model));
  }

 private:
  const MeshIndex* mesh_;
  const Pose* offset_;
  const SurfaceLookup lookup_;
  const bool max_mixture_;
  const double sigma0_, sigma1_, offset0_;
  const char* off_model_;  // null: the label by h alone
  mutable std::atomic<int> hint_{-1};
};

}  // namespace hull::adjust
