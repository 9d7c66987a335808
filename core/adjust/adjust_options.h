// Options of the model-assisted bundle adjustment (one struct for the GUI
// panel, the CLI flags and the project file; refused by Check() when invalid).
#pragma once

#include <cmath>
#include <string>

#include "adjust/cost_watch.h"
#include "adjust/landmark_covariance.h"
#include "geometry/mesh_index.h"

namespace hull {

// The surface constraint on the landmarks (Ozog et al., Section 4):
enum class SurfaceModel {
  kNaive,         // no surface factors (every lambda = 0)
  kAllOnSurface,  // every lambda = 1 (Geva et al.): every feature pulled onto the mesh with sigma1
  kMaxMixture,    // the method: a binary Gaussian max-mixture, the label chosen where evaluated
};
const char* SurfaceModelName(SurfaceModel m);  // "naive", "all-on-surface", "max-mixture"
// Parses the names above; throws OptionError otherwise.
SurfaceModel ParseSurfaceModel(const std::string& name);

// How the max-mixture's label of a landmark is decided (the E-step):
enum class LabelRule {
  // By the landmark's current estimate of h, where the factor is evaluated
  // (E- and M-steps merged, as in Ozog et al.). A landmark once on the
  // model is judged by the estimate its own on-model component has already
  // pulled toward the hull, so a feature of a low object (h just above the
  // decision boundary) can be pulled below it and stay there.
  kEstimate,
  // As kEstimate, and after each solve every landmark on the model is judged
  // again by its cavity estimate: its h with its own surface factor taken
  // out, h_c = h (1 + sigma_c^2 / sigma1^2), sigma_c^2 = n^T C n with C the
  // covariance its other factors give it (poses held fixed) and n the
  // direction of h. A landmark whose cavity estimate is more likely off the
  // model is labelled off for the rest of the adjustment, and the problem
  // is solved again (docs/adjustment.md, "Labels by the cavity estimate").
  kCavity,
};
const char* LabelRuleName(LabelRule r);  // "estimate", "cavity"
// Parses the names above; throws OptionError("labels") otherwise.
LabelRule ParseLabelRule(const std::string& name);

struct AdjustmentOptions {
  SurfaceModel model = SurfaceModel::kMaxMixture;
  // Surface-constraint sigmas (m): off the model (lambda = 0) and on it (lambda = 1).
  double sigma0 = 1.0;
  double sigma1 = 0.02;
  // The E-step of the max-mixture (above), and how many times at most the
  // cavity labels may send the problem back to the solver.
  LabelRule labels = LabelRule::kCavity;
  int label_rounds = 3;
  // How h(x_gM, l) finds its face: the exact closest point (default) or the
  // paper's nearest vertex and any adjacent face.
  SurfaceLookup lookup = SurfaceLookup::kClosestFace;
  // Huber threshold on whitened reprojection and DVL residuals (in sigmas).
  double huber_sigmas = 2.0;
  // Noise overrides (<= 0: the survey manifest's value).
  double pixel_sigma = 0, dvl_range_sigma = 0, depth_sigma = 0, roll_pitch_sigma = 0, servo_sigma = 0;
  double model_pose_sigma = 0;  // prior on x_gM: Sigma = sigma^2 I6
  // Gauge: x, y and yaw of the first pose held at their initial values.
  double gauge_sigma_xy = 1e-3, gauge_sigma_yaw = 1e-4;
  // What is estimated besides poses and landmarks.
  bool estimate_servo = true;
  bool estimate_extrinsic = true;
  bool estimate_model_pose = true;
  bool use_dvl = true;
  // Landmarks seen in fewer keyframes are left out (a single stereo view can
  // still be triangulated, but is weak).
  int min_observations = 2;
  // A landmark triangulated from the initial poses farther than this (m)
  // from the prior mesh (placed by the initial model pose, which the DVL
  // returns fix along the hull's normal to centimetres) is left out: no
  // foreign structure on a hull stands that far off, and such a point is a
  // wrong match the rays cannot reveal (a monocular track of two views
  // matched along the epipolar line triangulates exactly, metres off). Left
  // in, the off-model component (sigma0) pulls the model pose toward it,
  // and a flat bottom leaves the pose free to slide and turn. 0: no limit.
  // Given (landmarks.csv) and warm-started positions are not judged.
  double max_initial_deviation = 0.5;
  // Outlier rejection (wrong matches): after the solve, observations whose
  // reprojection error exceeds this many pixel sigmas (norm of the 2-D
  // error in either camera) are removed, landmarks left with fewer than
  // min_observations views are dropped, and the problem is solved again;
  // up to rejection_rounds times. 0 rounds: keep every observation.
  double outlier_sigmas = 4.0;
  int rejection_rounds = 2;
  // Solver.
  enum class LinearSolver {
    // Exact reduced camera system (SuiteSparse Cholesky). The default at
    // every size: on curtiss (10,481 keyframes) 4.2 s per LM iteration
    // against 9.3 s for the iterative solver, whose inexact steps also stop
    // at a higher cost (docs/benchmarks.md).
    kSparseSchur,
    kIterativeSchur,  // conjugate gradients on the implicit Schur complement (less memory)
  };
  LinearSolver linear_solver = LinearSolver::kSparseSchur;
  int max_iterations = 100;
  double function_tolerance = 1e-6;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  // Wall-time limit of each solve (s); 0: none. With max_iterations, the
  // cap a fuzz harness (or a GUI preview) puts on one adjustment.
  double max_solver_seconds = 0;
  int num_threads = 0;  // 0: all cores
  bool verbose = false;
  // Landmark covariances after the solve (landmark_covariance.h): full (the
  // marginal, by the Schur complement), full-qr (the same, Ceres' sparse-QR
  // covariance; slower), conditional (poses held fixed; cheap, optimistic)
  // or none. Each landmark's sigma of h follows.
  CovarianceMethod covariance = CovarianceMethod::kFull;
  // Runaway detection (cost_watch.h): a solve whose cost is not finite,
  // absurd from the start or stalled while absurd ends with an InputError
  // naming the likely input.
  CostWatchOptions watch;

  // Throws OptionError naming the field: sigma0 > sigma1 > 0, positive
  // overrides or 0, max_iterations >= 1, ...
  void Check() const;
  // The |h| at which the two mixture components are equally likely:
  // sqrt(2 ln(sigma0 / sigma1) / (1 / sigma1^2 - 1 / sigma0^2)).
  double DecisionBoundary() const;
};

// Label lambda of a signed distance under the max-mixture (1: on the model).
inline int MaxMixtureLabel(double h, double sigma0, double sigma1) {
  const double c1 = 0.5 * (h / sigma1) * (h / sigma1) + std::log(sigma1);
  const double c0 = 0.5 * (h / sigma0) * (h / sigma0) + std::log(sigma0);
  return c1 <= c0 ? 1 : 0;
}

}  // namespace hull
