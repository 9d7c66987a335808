// What the model-assisted bundle adjustment produces. Its files (a folder
// with adjustment.json, timing.json, poses.csv, landmarks.csv and
// dvl_residuals.csv) are written and read by results/adjustment_files.h.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "adjust/adjust_options.h"
#include "geometry/pose.h"

namespace hull {

struct IterationRecord {
  int iteration = 0;
  double cost = 0;                 // 0.5 sum of squared (robustified) residuals
  double seconds = 0;              // since the solver started
  double fraction_on_surface = 0;  // share of landmarks with lambda = 1 (Fig. 16)
};

struct LandmarkEstimate {
  std::int64_t id = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // in g
  int label = 1;                                // lambda: 1 on the hull, 0 foreign structure (max-mixture decision)
  double deviation = 0;                         // h(x_gM, l): orthogonal signed distance to the mesh (m)
  int observations = 0;                         // keyframes that saw it
  // Covariance of p (m^2, in g) and the standard deviation of `deviation`
  // it implies along the surface normal (m); NaN when not computed.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Constant(std::nan(""));
  double sigma_h = std::nan("");
};

struct DvlResidual {
  std::int64_t keyframe = 0;
  int beam = 1;         // 1..4
  double measured = 0;  // m
  double initial = 0;   // measured - predicted at the initial alignment (NaN: the beam misses the mesh)
  double final = 0;     // measured - predicted after adjustment
};

struct AdjustmentResult {
  static constexpr int kFormatVersion = 1;

  // Inputs, so that later steps (mapping, the GUI) can find them: absolute
  // paths of the survey bundle and the prior mesh, and the mesh's load scale.
  std::string bundle_path;
  std::string mesh_path;
  double mesh_scale = 1.0;

  AdjustmentOptions options;
  std::vector<std::int64_t> keyframes;
  std::vector<Vector6d> poses;  // x_gv per keyframe
  std::vector<double> servo;
  Vector6d x_gM = Vector6d::Zero(), x_gM_initial = Vector6d::Zero();
  Vector6d x_s_cT = Vector6d::Zero(), x_s_cT_initial = Vector6d::Zero();
  std::vector<LandmarkEstimate> landmarks;
  std::vector<DvlResidual> dvl;
  std::vector<IterationRecord> iterations;

  std::string termination;  // Ceres' termination type and message
  bool converged = false;
  double seconds = 0;  // wall time of the whole adjustment
  double solver_seconds = 0;
  double initial_cost = 0, final_cost = 0;
  int num_residual_blocks = 0;
  int num_landmarks_skipped = 0;  // too few observations, not triangulable, or lost to outlier rejection
  // Of those skipped: triangulated farther than options.max_initial_deviation from the prior mesh.
  int num_landmarks_off_model = 0;
  int observations_rejected = 0;  // reprojection outliers removed (wrong matches)
  // Landmarks labelled off the model at the end by their cavity estimate
  // (their estimate lay on it when the E-step judged them; LabelRule::kCavity,
  // cavity_label.h).
  int num_labels_off_by_cavity = 0;
  // How the landmark covariances were computed (a fallback says why) and how long it took.
  CovarianceMethod covariance_method = CovarianceMethod::kNone;
  std::string covariance_note;
  double covariance_seconds = 0;      // wall
  double covariance_cpu_seconds = 0;  // process CPU (all threads); not written
  // The Schur complement's reduced system: columns and factor nonzeros (not written).
  std::size_t covariance_reduced_size = 0, covariance_factor_nonzeros = 0;

  // The fraction of landmarks with lambda = 1 at the end.
  double FractionOnSurface() const;
};

}  // namespace hull
