// The initial alignment of a survey to its prior model (Ozog et al.,
// Section 2.5): the DVL returns, placed in g by the initial poses (nav.csv's
// dead reckoning with the depth and IMU measurements folded in) and the
// instrumented servo angles, are registered to the CAD mesh by GICP; the
// result x_gM seeds the bundle adjustment's prior on the model pose.
//
// The target cloud. The paper registers to the mesh vertices, but CAD faces
// are often a metre or more across, far coarser than the returns (a few
// decimetres apart): vertices would pair each return with a corner metres
// away. So the surface is sampled on a grid of sample_spacing (5 cm) per
// face instead, and only within sample_margin (1 m, more than a guess's
// error over the footprint) of a return placed by the initial guess: the
// whole hull at 5 cm would be millions of points, the footprint's
// neighbourhood is about 10^5.
//
// Degenerate surveys. A survey of a flat or prismatic stretch (the demo's
// bottom patch) fixes only some directions of x_gM (depth and tilt of the
// plane); GICP drifts freely along the others. The alignment keeps the
// start's value along them (see min_observability) and reports how many it
// could fix (constrained_directions).
//
// Coarse search (no guess). Hypotheses: the hull upright (model_axes' up ->
// -z of g; default forward +x, up +z of M), its forward axis at headings
// from the vehicle's mean heading, the returns' principal axis (each both
// ways) and a sweep; the returns' centroid on one of the surface anchors
// (every anchor_spacing) whose normal agrees with the returns' footprint.
// Every hypothesis is scored on a subsample, the best distinct ones get
// point-to-plane ICP, the best of those GICP, and the best fit wins. Limits:
//  - It can only find what the returns determine. Over a flat or prismatic
//    stretch every place along it fits equally (the demo: tied over tens of
//    metres); the search then reports the tie (CoarseSearchReport::tied and
//    its spread) and picks by convention: the heading nearest the vehicle's
//    (the HAUV faces the bow on bottom surveys; a vehicle facing the stern
//    gives a placement 180 deg off), then the middle of the tied stretch,
//    which bounds the error by half the stretch but does not remove it.
//  - Near the bow and stern the returns' fit is blurred by the navigation's
//    drift (centimetres), so the curved ends still place the survey only to
//    within metres and degrees (simulated 12 m patches at either end: 3-4 m
//    and up to 7 deg), and a bow survey can tie with a stern placement.
//  - The ship is assumed upright (trim and list are left to GICP) and the
//    model's axes correct; hypotheses are every anchor_spacing and
//    heading_step_deg, so a hull much smaller than the returns' footprint or
//    a footprint of a few metres will not be placed reliably.
// A real guess (model_pose_guess, or a few features picked by hand) is
// always better; the search is a fallback.
//
// Every DVL beam also gets its range residual (the range predicted by ray
// casting the beam, as placed for the alignment, against the mesh placed by
// x_gM, minus the measured range) before and after the alignment: the
// paper's Fig. 18 compares them with the residuals after bundle adjustment
// (for which DvlRangeResiduals recomputes them from the optimised poses).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "registration/dvl_points.h"
#include "registration/gicp.h"
#include "survey/survey.h"

namespace hull {

// GICP settings for sparse DVL returns (source) against dense samples of the
// mesh (target): no voxel reduction in the fine stage (the returns are
// already sparser than any voxel worth using), a reach of 0.5 m that covers a
// guess a few decimetres off, a coarse stage on a 0.3 m grid with a 1.5 m
// reach, 10 neighbours per covariance and 1e-4 stopping thresholds.
GicpOptions DvlGicpOptions();

struct ModelAlignmentOptions {
  GicpOptions gicp = DvlGicpOptions();
  // The returns are placed by nav.csv's initial poses with the absolute
  // sensors folded in (see InitialPosesWithZpr): depth corrected over this
  // window (s; 0: the dead-reckoned z as is) ...
  double depth_window = 60.0;
  // ... and roll and pitch from the IMU instead of dead reckoning.
  bool measured_roll_pitch = true;
  // Target cloud: the mesh surface sampled on a grid of about this spacing
  // (m) per face, and kept only within sample_margin (m) of a DVL return
  // placed by the initial guess (see the top of this file).
  double sample_spacing = 0.05;
  double sample_margin = 1.0;
  // Degeneracy guard: GICP's update is kept only along the motions that
  // change the returns' distances to the mesh by at least this much (mean
  // squared metres of distance per squared metre of motion, a rotation
  // counted as the motion of the returns' RMS radius); along the others
  // (in-plane motion and yaw over a flat bottom, motion along a prismatic
  // stretch) the start is kept. 0 keeps the whole update.
  double min_observability = 0.01;
  // DVL range residuals: a beam is cast at most this far (m); a beam that
  // misses the mesh within it has no predicted range (residual NaN).
  double max_beam_range = 30.0;
  // Wall-time budget of the whole alignment (s): the coarse search, the
  // sampling of the mesh and every GICP run check it between their steps
  // and stop with an error naming the stage when it is spent (each GICP
  // stage is also bounded by gicp.max_iterations). 0: no budget.
  double max_seconds = 600.0;

  // ---- coarse search (only when no initial x_gM is given) ------------------
  // Anchors: the mesh surface sampled about every anchor_spacing (m); each
  // hypothesis puts the DVL returns' centroid on an anchor.
  double anchor_spacing = 2.0;
  // Headings tried besides those suggested by the data (the vehicle's median
  // heading and the footprint's principal axis, each both ways): a sweep every
  // heading_step_deg (0: no sweep).
  double heading_step_deg = 30.0;
  // Anchors whose normal, under a heading, is farther than this (deg) from
  // the DVL footprint's normal are skipped (only when the footprint is
  // planar enough to have one).
  double max_normal_angle_deg = 35.0;
  // DVL returns used to score each hypothesis (an even subsample).
  int score_points = 96;
  // The best hypotheses by score (at least 2 m or 20 deg apart) that get a
  // few point-to-plane ICP steps on that subsample and are scored again ...
  int icp_hypotheses = 48;
  // ... and the best of those refined by GICP, against mesh samples
  // candidate_sample_spacing (m) apart (lighter than the final alignment's).
  int refine_hypotheses = 6;
  double candidate_sample_spacing = 0.1;
  // Scores (truncated RMS point-to-mesh distance, m) within this of the best
  // count as a tie: the data cannot tell those hypotheses apart.
  double tie_tolerance = 0.01;
  // Distances beyond this (m) count as this in the scores (outliers: foreign
  // objects, no-hull returns).
  double score_truncation = 0.5;

  // Throws hull::OptionError naming the first field out of range.
  void Check() const;
};

// One DVL beam's residual at the initial and at the aligned model pose.
struct DvlBeamResidual {
  std::int64_t keyframe = 0;
  int beam = 0;         // 0..3 (dvl.csv r1..r4)
  double measured = 0;  // m
  double before = 0;    // predicted - measured at the initial x_gM (NaN: the beam misses the mesh)
  double after = 0;     // the same at the aligned x_gM
};

// What the coarse search tried and how sure it can be.
struct CoarseSearchReport {
  bool ran = false;
  std::size_t hypotheses = 0;  // scored
  std::size_t refined = 0;     // refined by GICP
  // Refined hypotheses whose score tied with the winner's (within
  // tie_tolerance), the winner included: > 1 means the returns fit the hull
  // equally well in several places (e.g. a stretch of flat bottom, or the
  // bow-stern symmetry of a parallel midbody) and the choice among them was
  // made by the tie-break below, not by the data.
  std::size_t tied = 0;
  // Spread of the tied set: the largest distance (m) between the places the
  // returns' centroid lands on the hull, and the largest heading difference (deg).
  double tied_position_spread = 0;
  double tied_heading_spread_deg = 0;
  double best_score = 0;  // truncated RMS point-to-mesh distance of the winner (m)
  Pose start;             // the winning hypothesis before any refinement
};

struct ModelAlignment {
  Pose x_gM;          // the aligned model pose
  Pose initial_x_gM;  // the guess it started from (the coarse search's start when no guess was given)
  GicpResult gicp;    // transform = (-)x_gM before the degeneracy guard: target (M) <- source (g)
  // Eigenvalues (ascending) of the returns' normalised point-to-plane
  // information at x_gM, and how many reach min_observability: the number of
  // pose directions the DVL returns fix (3 over a flat bottom: depth, roll
  // and pitch of the plane).
  Vector6d observability = Vector6d::Zero();
  int constrained_directions = 0;
  std::size_t dvl_points = 0;     // DVL returns used (source)
  std::size_t target_points = 0;  // mesh samples (target) before voxel reduction
  // Per beam with a return, in dvl.csv order.
  std::vector<DvlBeamResidual> residuals;
  // RMS of the residuals over the beams that hit the mesh both before and after.
  double residual_rms_before = 0;
  double residual_rms_after = 0;
  std::size_t residual_beams = 0;  // beams counted in the two RMS values
  // Truncated RMS point-to-mesh distance of the returns (m), before and after.
  double surface_rms_before = 0;
  double surface_rms_after = 0;
  CoarseSearchReport coarse;
};

// The bundle's model_pose_guess as a Pose, if it has one.
std::optional<Pose> ModelPoseGuess(const SurveyBundle& bundle);

// Aligns the bundle's DVL returns (from nav.csv's initial poses, corrected by
// the depth and IMU measurements as the options say, and its instrumented
// servo angles) to mesh_in_M. With initial_x_gM, GICP starts there; without it the
// coarse search runs first. Throws OptionError (options), InputError (a bundle
// with fewer DVL returns than GICP needs) and Cancelled (through progress).
ModelAlignment AlignDvlToModel(const SurveyBundle& bundle, const TriangleMesh& mesh_in_M,
                               std::optional<Pose> initial_x_gM, const ModelAlignmentOptions& options,
                               Progress& progress);

// Per-beam residuals of the returns against the mesh placed by x_gM (before =
// after = the same pose); a helper for later stages (e.g. after bundle
// adjustment, with the returns recomputed from the optimised poses).
std::vector<double> DvlRangeResiduals(const std::vector<DvlPoint>& returns, const MeshIndex& mesh_in_M,
                                      const Pose& x_gM, double max_beam_range = 30.0);

// Points on the surface of the mesh, about `spacing` apart on every face (a
// barycentric grid per face, so shared edges are sampled by both faces).
// Throws InputError naming the largest face when that would take more than
// max_samples points (a stray vertex far from the rest, a mesh in the wrong
// units), before allocating any.
std::vector<Eigen::Vector3d> SampleMeshSurface(const TriangleMesh& mesh, double spacing, double max_samples = 2e7);

}  // namespace hull
