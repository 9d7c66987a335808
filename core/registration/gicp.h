// Generalized ICP (Segal, Haehnel and Thrun 2009) between two point clouds:
// the registration the paper uses to place the prior model (Section 2.5).
// Backed by PCL's GeneralizedIterativeClosestPoint; PCL stays inside
// gicp.cc, so no PCL type crosses this header.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "geometry/pose.h"

namespace hull {

struct GicpOptions {
  // The defaults are tuned on the real scans in ../shared/data (two outdoor
  // scans of about 70,000 points over 40 x 60 m, 0.5 m and 0.7 deg apart):
  // within 1 cm and 0.1 deg over voxel 0.08-0.12 m, reach 1-2 m and 8-12
  // neighbours; a reach below 1 m or 20 neighbours bias the rotation by up to
  // 0.4 deg there, and without the coarse stage a start 2.3 deg off stops in a
  // local minimum 0.9 deg from the truth.

  // Edge (m) of the voxel grid both clouds are reduced to (one centroid per
  // occupied voxel) for the fine stage; 0 keeps every point.
  double voxel_size = 0.1;
  // Fine stage: source and target points farther apart than this (m) after
  // the current transform are not paired; also the reach of the fitness.
  double max_correspondence_distance = 1.5;
  // Coarse stage run first (a wider basin of convergence): voxel edge (m)
  // and reach (m). coarse_voxel_size = 0 skips the coarse stage.
  double coarse_voxel_size = 0.5;
  double coarse_max_correspondence_distance = 2.0;
  // Outer iterations (pairing + BFGS solve) at most, per stage.
  int max_iterations = 100;
  // Stop a stage when no translation component changes by more than this
  // (m) in an iteration (PCL's transformation epsilon, compared per
  // component) ...
  double transformation_epsilon = 1e-6;
  // ... and no rotation-matrix entry by more than this (about radians).
  double rotation_epsilon = 1e-6;
  // Neighbours used to estimate each point's local covariance (PCL's
  // "correspondence randomness", k of the GICP paper).
  int correspondence_randomness = 10;
  // BFGS iterations of the inner solve per outer iteration.
  int max_optimizer_iterations = 50;
  // BFGS stops when the gradient's translation and rotation parts fall below
  // these (cost per metre and per radian; PCL's default is 1e-2).
  double translation_gradient_tolerance = 1e-4;
  double rotation_gradient_tolerance = 1e-4;

  // Throws hull::OptionError naming the first field out of range.
  void Check() const;
};

enum class GicpStatus {
  kConverged,      // the update fell below both epsilons
  kMaxIterations,  // stopped at max_iterations (the transform may still be usable)
  kTooFewPoints,   // a cloud had fewer points than correspondence_randomness
  kSolverFailed,   // too few correspondences or the BFGS solve failed; the last good transform is returned
};
const char* GicpStatusName(GicpStatus s);

struct GicpResult {
  Pose transform;  // x_target_source: p_target = transform * p_source
  bool converged = false;
  GicpStatus status = GicpStatus::kSolverFailed;
  int iterations = 0;  // outer iterations run (both stages)
  // RMS (m) of the distances from each transformed source point to its
  // nearest target point, over the pairs within max_correspondence_distance
  // (of the clouds actually aligned, i.e. after voxel reduction).
  double fitness = 0;
  std::size_t correspondences = 0;  // pairs counted in fitness
  std::size_t source_points = 0;    // points aligned in the fine stage (after voxel reduction)
  std::size_t target_points = 0;
};

// Aligns source to target starting from `initial` (x_target_source). Both
// clouds are shifted to their centroids internally (PCL works in float and
// its covariances lose precision far from the origin), so clouds in large
// coordinates are fine. Throws OptionError when options fail Check().
GicpResult AlignGicp(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                     const Pose& initial, const GicpOptions& options = {});

// One centroid per occupied cubic voxel of edge `voxel` (m), in the order the
// voxels are first met; voxel <= 0 returns the points unchanged.
std::vector<Eigen::Vector3d> VoxelDownsample(const std::vector<Eigen::Vector3d>& points, double voxel);

}  // namespace hull
