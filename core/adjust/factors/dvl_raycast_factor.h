// DVL raycast (eq. 14): the range predicted for one beam by casting it from
// the DVL head x_g,d = x_gv (+) x_vs(theta) (+) x_s_d against the prior mesh
// placed by x_gM = x_gC (+) x_CM. The hit face is found afresh at every evaluation (double
// precision, Embree); the range is then differentiated through the plane of
// that face: r = n . (p0 - o_M) / (n . d_M), exact for a planar face. A beam
// that misses keeps the plane of its last hit (a piecewise-planar extension).
// Whitened by sigma (3 mm by default); the problem adds a Huber loss.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <atomic>

#include "adjust/factors/pose_math.h"
#include "geometry/mesh_index.h"

namespace hull::adjust {

struct DvlModel {
  const MeshIndex* mesh = nullptr;
  Pose mount;         // servo.mount
  Pose servo_to_dvl;  // x_s_d
  double max_range = 30.0;
  // The model pose block holds x_gC, a frame at the surveyed region with M's
  // orientation; x_gM = x_gC (+) model_offset (a pure translation). See
  // bundle_adjuster.cc: it keeps a yaw of the prior from swinging the region.
  Pose model_offset;
};

// Origin and direction of a beam in g for a vehicle pose and servo angle.
template <typename T>
void BeamInGlobal(const DvlModel& m, const T* pose, const T* servo, const Eigen::Vector3d& beam,
                  Eigen::Matrix<T, 3, 1>& origin, Eigen::Matrix<T, 3, 1>& dir) {
  const PoseT<T> g_d =
      PoseFromBlock(pose) * PoseConstant<T>(m.mount) * ServoRotation(servo[0]) * PoseConstant<T>(m.servo_to_dvl);
  origin = g_d.t;
  dir = g_d.q * beam.cast<T>();
}

class DvlRaycastFactor {
 public:
  static constexpr double kMinIncidenceCosine = 0.26;

  DvlRaycastFactor(const DvlModel* model, const Eigen::Vector3d& beam, double measured, double sigma)
      : model_(model), beam_(beam.normalized()), measured_(measured), inv_sigma_(1.0 / sigma) {}

  // Predicted range (and the face hit) for plain doubles.
  static double PredictRange(const DvlModel& m, const double* pose, const double* servo, const double* x_gC,
                             const Eigen::Vector3d& beam, int* face = nullptr) {
    Eigen::Vector3d o, d;
    BeamInGlobal(m, pose, servo, beam.normalized(), o, d);
    const Pose Mg = (BlockToPose(x_gC) * m.model_offset).Inverse();
    const RayHit hit = m.mesh->Raycast(Mg * o, Mg.Rotate(d), m.max_range);
    if (face) *face = hit.hit ? hit.face : -1;
    return hit.hit ? hit.range : std::numeric_limits<double>::quiet_NaN();
  }

  template <typename T>
  bool operator()(const T* pose, const T* servo, const T* x_gC, T* residual) const {
    Eigen::Matrix<T, 3, 1> o, d;
    BeamInGlobal(*model_, pose, servo, beam_, o, d);
    const PoseT<T> Mg = (PoseFromBlock(x_gC) * PoseConstant<T>(model_->model_offset)).Inverse();
    const Eigen::Matrix<T, 3, 1> oM = Mg * o, dM = Mg.q * d;
    const RayHit hit = model_->mesh->Raycast(ScalarOf(oM), ScalarOf(dM), model_->max_range);
    const TriangleMesh& mesh = model_->mesh->mesh();
    // Data association: the face hit now, unless the face used last time
    // explains the measured range better (the beam slipping past a
    // silhouette onto a far part of the hull is a jump of metres in the
    // prediction; staying on the last face's plane keeps the cost continuous).
    auto plane_range = [&](int f, double* cosine) {
      const Eigen::Vector3d& n = mesh.face_normals[static_cast<std::size_t>(f)];
      const Eigen::Vector3d& p0 = mesh.vertices[static_cast<std::size_t>(mesh.faces[static_cast<std::size_t>(f)][0])];
      const Eigen::Vector3d o = ScalarOf(oM), d = ScalarOf(dM);
      *cosine = std::abs(n.dot(d)) / d.norm();
      return n.dot(p0 - o) / n.dot(d);
    };
    int face = hit.hit ? hit.face : -1;
    const int last = last_face_.load(std::memory_order_relaxed);
    if (last >= 0 && last != face) {
      double c_last = 0;
      const double r_last = plane_range(last, &c_last);
      const bool last_ok = c_last >= kMinIncidenceCosine && r_last > 0;
      if (face < 0 ? last_ok : (last_ok && std::abs(r_last - measured_) < std::abs(hit.range - measured_))) {
        face = last;
      }
    }
    if (face >= 0) last_face_.store(face, std::memory_order_relaxed);
    if (face < 0) {
      residual[0] = T(0);  // never hit the mesh: no information
      return true;
    }
    const Eigen::Vector3d& n = mesh.face_normals[static_cast<std::size_t>(face)];
    const Eigen::Vector3d& p0 = mesh.vertices[static_cast<std::size_t>(mesh.faces[static_cast<std::size_t>(face)][0])];
    const T denom = n.cast<T>().dot(dM);
    if (std::abs(ScalarOf(denom)) < kMinIncidenceCosine * ScalarOf(dM.norm())) {
      // Grazing the face (beyond ~75 deg of incidence): the predicted range
      // jumps with the smallest motion, and a DVL's bottom track would not
      // lock there either. No information.
      residual[0] = T(0);
      return true;
    }
    const T range = n.cast<T>().dot(p0.cast<T>() - oM) / denom;
    residual[0] = (range - T(measured_)) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const DvlModel* model, const Eigen::Vector3d& beam, double measured,
                                     double sigma) {
    return new ceres::AutoDiffCostFunction<DvlRaycastFactor, 1, kPoseSize, 1, kPoseSize>(
        new DvlRaycastFactor(model, beam, measured, sigma));
  }

 private:
  const DvlModel* model_;
  const Eigen::Vector3d beam_;
  const double measured_, inv_sigma_;
  mutable std::atomic<int> last_face_{-1};
};

}  // namespace hull::adjust
