#include "adjust/bundle_adjuster.h"

#include <ceres/ceres.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <memory_resource>
#include <optional>
#include <set>
#include <thread>
#include <unordered_map>

#include "adjust/cavity_label.h"
#include "adjust/factors/dvl_raycast_factor.h"
#include "adjust/factors/odometry_factor.h"
#include "adjust/factors/pose_prior_factor.h"
#include "adjust/factors/reprojection_factor.h"
#include "adjust/factors/surface_factor.h"
#include "adjust/factors/zpr_factor.h"
#include "adjust/triangulation.h"
#include "base/csv.h"
#include "base/error.h"
#include "geometry/mesh_index.h"
#include "geometry/query_bounds.h"
#include "survey/survey_plausibility.h"

namespace hull {
namespace {
using adjust::BlockToPose;
using adjust::kPoseSize;
using adjust::PoseToBlock;
using Clock = std::chrono::steady_clock;

// The states, every parameter block in one buffer allocated in a fixed order
// (extrinsic, model, poses, servo angles, landmarks). Ceres orders the
// covariance's columns by the blocks' addresses
// (CovarianceImpl::ComputeCovarianceSparsity sorts them by pointer): blocks
// in separately allocated vectors were ordered by wherever malloc put them,
// which varies from run to run with other threads' allocations (Embree's
// TBB workers), and the covariances' last digits varied with it (the other
// cause: landmark_covariance.cc's aligned SuiteSparse allocations).
class State {
 public:
  // max_landmarks bounds the landmarks pushed (the buffer never grows).
  State(std::size_t keyframes, std::size_t max_landmarks)
      : buffer_(Bytes(keyframes, max_landmarks)),
        arena_(buffer_.data(), buffer_.size(), std::pmr::null_memory_resource()),
        extrinsic(kPoseSize, 0.0, &arena_),
        model(kPoseSize, 0.0, &arena_),
        pose(keyframes, std::array<double, kPoseSize>{}, &arena_),
        servo(keyframes, 0.0, &arena_),
        landmark(&arena_) {
    landmark.reserve(max_landmarks);
  }
  State(const State&) = delete;
  State& operator=(const State&) = delete;

 private:
  static std::size_t Bytes(std::size_t keyframes, std::size_t max_landmarks) {
    constexpr std::size_t kSlack = 64;  // alignment padding per allocation
    return sizeof(double) * (2 * kPoseSize + keyframes * (kPoseSize + 1) + 3 * max_landmarks) + 5 * kSlack;
  }
  std::vector<std::byte> buffer_;
  std::pmr::monotonic_buffer_resource arena_;

 public:
  std::pmr::vector<double> extrinsic;
  // The model pose is optimised as x_gC, a frame with M's orientation at the
  // centroid of the surveyed region: x_gM = x_gC (+) x_CM. Parameterised at
  // M's own origin (often the stern, ~100 m away), a rotation of the prior's
  // size would swing the surveyed region across the hull, and a flat hull
  // patch would leave that swing unobserved; about the region, yaw and
  // translation mean what they say. The prior (eq. 8) applies to x_gC.
  std::pmr::vector<double> model;
  std::pmr::vector<std::array<double, kPoseSize>> pose;
  std::pmr::vector<double> servo;
  std::pmr::vector<std::array<double, 3>> landmark;
  Pose model_offset;  // x_CM (a pure translation)
  Pose ModelPose() const { return BlockToPose(model.data()) * model_offset; }
  std::vector<std::int64_t> landmark_id;
  std::vector<int> landmark_views;
};

// Fraction of landmarks whose max-mixture label is 1 at the current state.
// off: per landmark, labelled off by its cavity estimate (LabelRule::kCavity).
double FractionOnSurface(const State& s, const MeshIndex& index, const AdjustmentOptions& o, std::vector<int>* hints,
                         const std::vector<char>& off) {
  if (s.landmark.empty()) return 0;
  const Pose x_gM = s.ModelPose();
  int on = 0;
  for (std::size_t i = 0; i < s.landmark.size(); ++i) {
    if (off[i]) continue;
    const Eigen::Vector3d l(s.landmark[i][0], s.landmark[i][1], s.landmark[i][2]);
    on += MaxMixtureLabel(adjust::SurfaceDeviation(index, x_gM, l, o.lookup, &(*hints)[i]), o.sigma0, o.sigma1);
  }
  return static_cast<double>(on) / static_cast<double>(s.landmark.size());
}

// Whether a landmark triangulated from the initial poses lies within
// o.max_initial_deviation of the prior mesh placed by x_gM: its signed
// distance, and along each of its rays, its depth against the depth where
// the ray meets the mesh. The second catches a point metres from where its
// rays see the hull yet near another part of the mesh (a wrong match
// triangulated far along or into the hull: its closest face is elsewhere).
bool NearTheMesh(const MeshIndex& index, const Pose& x_gM, const Eigen::Vector3d& p, const std::vector<ViewRay>& rays,
                 const std::vector<int>& inliers, const AdjustmentOptions& o) {
  const double limit = o.max_initial_deviation;
  if (!(std::abs(index.OrthogonalSignedDistance(x_gM, p, o.lookup).signed_distance) <= limit)) return false;
  const Pose Mg = x_gM.Inverse();
  for (int i : inliers) {
    const ViewRay& r = rays[static_cast<std::size_t>(i)];
    const double depth = (p - r.origin).dot(r.dir);
    const RayHit hit = index.Raycast(Mg * r.origin, Mg.Rotate(r.dir), 30.0);
    // A ray that meets no mesh (past its edge) is judged by the distance above.
    if (hit.hit && !(std::abs(hit.range - depth) <= limit)) return false;
  }
  return true;
}

}  // namespace

// The solve's share of its progress range after `iterations` iterations
// (counted across the outlier-rejection rounds, as the results record them).
// Nobody knows in advance how many iterations Levenberg-Marquardt takes, so
// the estimate approaches 1 as the count approaches the budget of one solve,
// 1 - exp(-3 n / max_iterations): it only rises, by at most 3 % of the range
// per iteration (what a user sees: a bar that moves steadily and never
// jumps), and reaches 95 % at the budget.
double SolveFraction(int iterations, int max_iterations) {
  if (iterations <= 0) return 0.0;
  return 1.0 - std::exp(-3.0 * iterations / std::max(1, max_iterations));
}

namespace {

class Observer : public ceres::IterationCallback {
 public:
  Observer(const State& s, const MeshIndex& index, const AdjustmentOptions& o, const std::vector<char>& off,
           Progress& progress, std::vector<IterationRecord>& log, std::size_t num_residuals)
      : s_(s),
        index_(index),
        o_(o),
        off_(off),
        progress_(progress),
        log_(log),
        hints_(s.landmark.size(), -1),
        watch_(o.watch, num_residuals) {}

  // Why the watch stopped the solve ("" when it did not).
  const std::string& stop_reason() const { return stop_reason_; }

  // Rounds after outlier rejection continue the iteration count.
  void set_iteration_offset(int offset) { offset_ = offset; }

  // The share of the whole job reached so far (never goes back).
  double fraction() const { return fraction_; }

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    if (offset_ > 0 && it.iteration == 0) return ceres::SOLVER_CONTINUE;  // same state as the last record
    // A rejected step leaves the parameters where they were; Ceres reports the
    // rejected candidate's cost (DBL_MAX when its evaluation failed), so the
    // record and the runaway watch keep the cost of the point the solver is at.
    const bool moved = it.iteration == 0 || it.step_is_successful || log_.empty();
    const double cost = moved ? it.cost : log_.back().cost;
    stop_reason_ = watch_.Observe(offset_ + it.iteration, cost);
    if (!stop_reason_.empty()) return ceres::SOLVER_ABORT;
    IterationRecord r;
    r.iteration = offset_ + it.iteration;
    r.cost = cost;
    r.seconds = it.cumulative_time_in_seconds;
    r.fraction_on_surface = FractionOnSurface(s_, index_, o_, &hints_, off_);
    log_.push_back(r);
    char msg[160];
    std::snprintf(msg, sizeof(msg), "%s adjustment: iteration %d, cost %.6g, lambda=1 for %.1f %%",
                  SurfaceModelName(o_.model), r.iteration, it.cost, 100.0 * r.fraction_on_surface);
    fraction_ = std::max(fraction_, 0.1 + 0.85 * SolveFraction(r.iteration, o_.max_iterations));
    progress_.Update(fraction_, msg);
    return progress_.Cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const State& s_;
  const MeshIndex& index_;
  const AdjustmentOptions& o_;
  const std::vector<char>& off_;
  Progress& progress_;
  std::vector<IterationRecord>& log_;
  std::vector<int> hints_;
  int offset_ = 0;
  double fraction_ = 0.1;
  CostWatch watch_;
  std::string stop_reason_;
};

// The block with the largest cost, named for the error that ends a runaway
// solve.
std::string LargestResidual(ceres::Problem& problem, const std::vector<ceres::ResidualBlockId>& ids,
                            const std::vector<ResidualLabel>& labels) {
  double worst = -1;
  std::size_t at = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    double cost = 0;
    if (!problem.EvaluateResidualBlock(ids[i], true, &cost, nullptr, nullptr)) cost = INFINITY;
    if (!(cost <= worst)) {  // NaN and inf count as worst
      worst = cost;
      at = i;
      if (std::isnan(cost)) break;
    }
  }
  if (ids.empty()) return "no residual";
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%.3g", worst);
  return labels[at].Describe() + ", cost " + buf;
}

// Defence in depth: what the validator refuses never reaches Ceres, even
// for a bundle built in memory (the plausibility rules, the noise bounds,
// a finite initial model pose).
void CheckAdjustable(const SurveyBundle& b, const Pose& x_gM_initial) {
  std::vector<Problem> found;
  CheckSurveyPlausibility(b, SurveyPlaces::ForBundle(b.directory), found);
  if (!found.empty()) throw InputError(found.front().where, found.front().message);
  const std::string manifest = (std::filesystem::path(b.directory) / "survey.json").string();
  NoiseModel noise = b.manifest.noise;
  const CameraRig& cam = b.manifest.camera;
  for (const plausible::SigmaBound& s : plausible::NoiseBounds(std::max(cam.width, cam.height))) {
    const double v = plausible::NoiseField(noise, s.key);
    if (!(v >= s.lo && v <= s.hi)) {
      throw InputError({manifest, 0, 0, s.key}, FormatDouble(v) + " is not plausible (" + s.why + ")");
    }
  }
  for (const PinholeIntrinsics& k : {cam.top, cam.bottom}) {
    if (!(k.fx > 0 && k.fy > 0 && std::isfinite(k.fx) && std::isfinite(k.fy) && std::isfinite(k.cx) &&
          std::isfinite(k.cy))) {
      throw InputError({manifest, 0, 0, "camera"}, "the intrinsics are not finite and positive");
    }
  }
  if (!Queryable(x_gM_initial.translation()) || !x_gM_initial.rotation().allFinite()) {
    throw InputError({manifest, 0, 0, "model_pose_guess"}, "the initial model pose is not finite or absurd");
  }
}

double Or(double override_value, double survey_value) { return override_value > 0 ? override_value : survey_value; }

// SuiteSparse (CHOLMOD's supernodal factorisation, SPQR) threads through
// OpenMP: the solve and the covariances use the adjustment's own thread
// count (--threads), whose team sums otherwise vary the last digits between
// runs. The previous count is restored.
class OpenMpThreads {
 public:
  explicit OpenMpThreads(int n) : saved_(omp_get_max_threads()) {
    if (n > 0) omp_set_num_threads(n);
  }
  ~OpenMpThreads() { omp_set_num_threads(saved_); }
  OpenMpThreads(const OpenMpThreads&) = delete;
  OpenMpThreads& operator=(const OpenMpThreads&) = delete;

 private:
  int saved_;
};

// The noise of each factor family: the option's override, else the survey's.
struct FactorSigmas {
  double pixel, dvl_range, depth, roll_pitch, servo, model_pose;
};

FactorSigmas SigmasOf(const AdjustmentOptions& o, const NoiseModel& nz) {
  return {Or(o.pixel_sigma, nz.pixel_sigma), Or(o.dvl_range_sigma, nz.dvl_range_sigma),
          Or(o.depth_sigma, nz.depth_sigma), Or(o.roll_pitch_sigma, nz.roll_pitch_sigma),
          Or(o.servo_sigma, nz.servo_sigma), Or(o.model_pose_sigma, nz.model_pose_sigma)};
}

// A reprojection residual block, with the landmark (its index in State) and
// the keyframe it ties: what the outlier rejection judges.
struct ReprojectionBlock {
  ceres::ResidualBlockId id;
  std::size_t landmark;
  std::int64_t keyframe;
};

// The adjustment as stages (COLMAP's BundleAdjuster is the model): the
// initial state (vehicle states, landmarks, the model pose's pivot), the
// problem (one Add...ToProblem per factor family), the solve rounds with the
// outlier rejection and the cavity label step, and the result. RunAdjustment
// calls them in that order; each stage fills the members the next reads.
class BundleAdjuster {
 public:
  BundleAdjuster(const SurveyBundle& b, const MeshIndex& index, const AdjustmentOptions& o, Progress& progress)
      : b_(b),
        man_(b.manifest),
        index_(index),
        o_(o),
        progress_(progress),
        sigma_(SigmasOf(o, b.manifest.noise)),
        kf_index_(b.KeyframeIndex()),
        K_(static_cast<int>(b.nav.size())),
        s_(static_cast<std::size_t>(K_), b.features.size()),  // at most one landmark per observation
        problem_(ProblemOptions()),
        ordering_(std::make_shared<ceres::ParameterBlockOrdering>()) {
    cam_.mount = Pose::FromVector(man_.servo_mount);
    cam_.top_to_bottom = Pose::FromVector(man_.camera.top_to_bottom);
    cam_.top = man_.camera.top;
    cam_.bottom = man_.camera.bottom;
    dvl_model_.mesh = &index_;
    dvl_model_.mount = cam_.mount;
    dvl_model_.servo_to_dvl = Pose::FromVector(man_.servo_to_dvl);
    extrinsic_nominal_ = Pose::FromVector(man_.camera.servo_to_top);
    result_.options = o;
  }

  // ---- the initial state ----
  void InitialiseVehicleStates(const AdjustmentResult* warm);
  void InitialiseLandmarks(const Pose& x_gM_start, const AdjustmentResult* warm);
  void PlaceModelPivot(const Pose& x_gM_start);
  // ---- the problem ----
  void BuildProblem(const Pose& x_gM_initial);
  // The DVL residuals at the initial alignment (initial poses and servo
  // angles against x_gM_initial), whatever state a warm start began from.
  void RecordInitialDvlResiduals(const Pose& x_gM_initial, bool warm);
  // ---- the solve rounds ----
  void Solve();
  // ---- the result ----
  AdjustmentResult CollectResults(const Pose& x_gM_initial);

 private:
  static ceres::Problem::Options ProblemOptions() {
    ceres::Problem::Options po;
    po.enable_fast_removal = true;
    po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return po;
  }
  std::size_t At(int k) const { return static_cast<std::size_t>(k); }
  // g <- top camera at keyframe index k, with the extrinsic the landmarks are initialised from.
  Pose TopCamera(int k) const {
    return BlockToPose(s_.pose[At(k)].data()) * man_.VehicleToServo(s_.servo[At(k)]) * x_s_cT0_;
  }
  bool StereoObservation(const FeatureObservation& f) const { return f.has_bottom && man_.camera.stereo(); }
  std::optional<Eigen::Vector3d> Triangulate(const std::vector<int>& observations, const Pose& x_gM0);
  bool KeepObservationsInFront(const Eigen::Vector3d& p, std::vector<int>* used, std::set<std::int64_t>* views);
  void Label(ceres::ResidualBlockId id, ResidualLabel::Kind kind, std::int64_t a = 0, std::int64_t b = 0) {
    block_ids_.push_back(id);
    block_labels_.push_back({kind, a, b});
  }
  void AddParameterBlocks();
  void AddPriorsToProblem(const Pose& x_gM_initial);
  void AddOdometryToProblem();
  void AddReprojectionToProblem();
  void AddDvlToProblem();
  void AddSurfaceToProblem();
  void RecordDvlResiduals(bool initial);
  ceres::Solver::Options SolverOptions();
  void ThrowIfSolveFailed(const Observer& observer, const ceres::Solver::Summary& summary);
  std::size_t CavityStep();
  struct Rejected {
    std::size_t observations = 0, landmarks = 0;
  };
  Rejected RejectOutliers();
  std::size_t DropLandmarksWithFewViews(std::vector<ReprojectionBlock>* kept, std::set<ceres::ResidualBlockId>* gone);
  void ForgetLabelsOf(const std::set<ceres::ResidualBlockId>& gone);
  void CollectLandmarks(const LandmarkCovariances& cov);

  const SurveyBundle& b_;
  const SurveyManifest& man_;
  const MeshIndex& index_;
  const AdjustmentOptions& o_;
  Progress& progress_;
  const FactorSigmas sigma_;
  const std::unordered_map<std::int64_t, int> kf_index_;
  const int K_;
  State s_;
  adjust::CameraModel cam_;
  adjust::DvlModel dvl_model_;
  Pose extrinsic_nominal_;
  Pose x_s_cT0_;                                // the extrinsic the landmarks are initialised with
  std::vector<std::vector<int>> landmark_obs_;  // observations used, per landmark of s_
  AdjustmentResult result_;                     // filled by every stage
  // The problem.
  ceres::Problem problem_;
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> se3_;
  std::unique_ptr<ceres::HuberLoss> huber_;
  std::vector<ceres::ResidualBlockId> block_ids_;  // with labels, to name the likely input of a runaway
  std::vector<ResidualLabel> block_labels_;
  std::vector<ReprojectionBlock> reprojection_;
  std::vector<ceres::ResidualBlockId> surface_block_;  // per landmark (null: none)
  // Per landmark: labelled off the model by its cavity estimate (the E-step
  // between solves, LabelRule::kCavity); the factors read it, so it is never
  // resized.
  std::vector<char> cavity_off_;
  bool cavity_labels_ = false;
  // The solve.
  std::shared_ptr<ceres::ParameterBlockOrdering> ordering_;
  int num_threads_ = 1;
  std::vector<char> dropped_;  // per landmark: removed by the outlier rejection
  int label_rounds_ = 0;
  double initial_cost_ = -1, solver_seconds_ = 0;
  ceres::Solver::Summary summary_;
};

// ---- the initial state ------------------------------------------------------------

// Poses and servo angles from nav.csv (or a warm start's, per keyframe it
// holds), the extrinsic at its nominal value (or the warm start's).
void BundleAdjuster::InitialiseVehicleStates(const AdjustmentResult* warm) {
  std::unordered_map<std::int64_t, int> warm_kf;
  if (warm) {
    for (std::size_t i = 0; i < warm->keyframes.size(); ++i) warm_kf[warm->keyframes[i]] = static_cast<int>(i);
  }
  for (int i = 0; i < K_; ++i) {
    const NavRecord& n = b_.nav[At(i)];
    auto w = warm_kf.find(n.keyframe);
    if (w != warm_kf.end()) {
      PoseToBlock(Pose::FromVector(warm->poses[At(w->second)]), s_.pose[At(i)].data());
      s_.servo[At(i)] = warm->servo[At(w->second)];
    } else {
      PoseToBlock(Pose::FromVector(n.x_gv), s_.pose[At(i)].data());
      s_.servo[At(i)] = n.servo;
    }
  }
  PoseToBlock(warm ? Pose::FromVector(warm->x_s_cT) : extrinsic_nominal_, s_.extrinsic.data());
  x_s_cT0_ = BlockToPose(s_.extrinsic.data());
}

// A landmark's initial point triangulated from the rays of its observations
// (nullopt: not triangulable, or a wrong match far from the prior mesh;
// counted in result_).
std::optional<Eigen::Vector3d> BundleAdjuster::Triangulate(const std::vector<int>& observations, const Pose& x_gM0) {
  std::vector<ViewRay> rays;
  for (int fi : observations) {
    const FeatureObservation& f = b_.features[At(fi)];
    const Pose g_cT = TopCamera(kf_index_.at(f.keyframe));
    auto add = [&](const Pose& g_c, const PinholeIntrinsics& k, const Eigen::Vector2d& uv) {
      ViewRay r;
      r.origin = g_c.translation();
      r.dir = g_c.Rotate(k.Unproject(uv)).normalized();
      r.g_c = g_c;
      r.pixel = uv;
      r.fx = k.fx;
      r.fy = k.fy;
      r.cx = k.cx;
      r.cy = k.cy;
      rays.push_back(r);
    };
    add(g_cT, cam_.top, f.top);
    if (StereoObservation(f)) add(g_cT * cam_.top_to_bottom, cam_.bottom, f.bottom);
  }
  const auto t = TriangulateLandmark(rays, TriangulationOptions{}, &index_, x_gM0);
  if (!t) {
    ++result_.num_landmarks_skipped;
    return std::nullopt;
  }
  if (o_.max_initial_deviation > 0 && !t->from_mesh && !NearTheMesh(index_, x_gM0, t->point, rays, t->inliers, o_)) {
    ++result_.num_landmarks_skipped;
    ++result_.num_landmarks_off_model;
    return std::nullopt;
  }
  return t->point;
}

// Observations whose camera sees the initial point from behind cannot be
// evaluated (Ceres needs every residual at the start): leaves them out of
// *used (counted in result_) and *views the keyframes of the rest. False when
// fewer than min_observations keyframes remain.
bool BundleAdjuster::KeepObservationsInFront(const Eigen::Vector3d& p, std::vector<int>* used,
                                             std::set<std::int64_t>* views) {
  std::vector<int> in_front;
  std::set<std::int64_t> kept_views;
  for (int fi : *used) {
    const FeatureObservation& f = b_.features[At(fi)];
    const Pose g_cT = TopCamera(kf_index_.at(f.keyframe));
    const bool front = (g_cT.Inverse() * p).z() > 0.05 &&
                       (!StereoObservation(f) || ((g_cT * cam_.top_to_bottom).Inverse() * p).z() > 0.05);
    if (front) {
      in_front.push_back(fi);
      kept_views.insert(f.keyframe);
    } else {
      ++result_.observations_rejected;
    }
  }
  if (static_cast<int>(kept_views.size()) < o_.min_observations) return false;
  used->swap(in_front);
  views->swap(kept_views);
  return true;
}

// Every landmark seen in min_observations keyframes, in id order: at a warm
// start's point, else landmarks.csv's, else triangulated.
void BundleAdjuster::InitialiseLandmarks(const Pose& x_gM_start, const AdjustmentResult* warm) {
  std::unordered_map<std::int64_t, std::vector<int>> obs_of;
  for (int i = 0; i < static_cast<int>(b_.features.size()); ++i) obs_of[b_.features[At(i)].landmark].push_back(i);
  std::unordered_map<std::int64_t, Eigen::Vector3d> given;
  if (b_.landmarks) {
    for (const auto& l : *b_.landmarks) given[l.landmark] = l.p;
  }
  std::unordered_map<std::int64_t, Eigen::Vector3d> warm_lm;
  if (warm) {
    for (const auto& l : warm->landmarks) warm_lm[l.id] = l.p;
  }
  progress_.Update(0.03, "initialising landmarks");
  std::vector<std::int64_t> ids;
  ids.reserve(obs_of.size());
  for (const auto& [id, list] : obs_of) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  for (std::int64_t id : ids) {
    const std::vector<int>& list = obs_of[id];
    std::set<std::int64_t> views;
    for (int fi : list) views.insert(b_.features[At(fi)].keyframe);
    if (static_cast<int>(views.size()) < o_.min_observations) {
      ++result_.num_landmarks_skipped;
      continue;
    }
    std::optional<Eigen::Vector3d> p;
    if (auto w = warm_lm.find(id); w != warm_lm.end()) {
      p = w->second;
    } else if (auto g = given.find(id); g != given.end()) {
      p = g->second;
    } else {
      p = Triangulate(list, x_gM_start);
      if (!p) continue;
    }
    std::vector<int> used = list;
    if (!KeepObservationsInFront(*p, &used, &views)) {
      ++result_.num_landmarks_skipped;
      continue;
    }
    s_.landmark.push_back({p->x(), p->y(), p->z()});
    s_.landmark_id.push_back(id);
    s_.landmark_views.push_back(static_cast<int>(views.size()));
    landmark_obs_.push_back(used);
  }
  if (s_.landmark.empty() && !b_.features.empty()) {
    throw InputError({b_.directory, 0, 0, "features.csv"}, "no landmark could be initialised");
  }
}

// The pivot of the model pose: the centroid of the landmarks (or of the
// vehicle positions); see State::model.
void BundleAdjuster::PlaceModelPivot(const Pose& x_gM_start) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  if (!s_.landmark.empty()) {
    for (const auto& l : s_.landmark) c += Eigen::Vector3d(l[0], l[1], l[2]);
    c /= static_cast<double>(s_.landmark.size());
  } else {
    for (const auto& p : s_.pose) c += Eigen::Vector3d(p[4], p[5], p[6]);
    c /= static_cast<double>(s_.pose.size());
  }
  const Pose x_gC(x_gM_start.quaternion(), c);
  s_.model_offset = x_gC.Inverse() * x_gM_start;
  PoseToBlock(x_gC, s_.model.data());
  dvl_model_.model_offset = s_.model_offset;
}

// ---- the problem ------------------------------------------------------------------

void BundleAdjuster::BuildProblem(const Pose& x_gM_initial) {
  progress_.Update(0.06, "building the factor graph");
  huber_ = std::make_unique<ceres::HuberLoss>(o_.huber_sigmas);
  AddParameterBlocks();
  AddPriorsToProblem(x_gM_initial);
  AddOdometryToProblem();
  AddReprojectionToProblem();
  AddDvlToProblem();
  AddSurfaceToProblem();
}

// Poses (on SE(3)) with their servo angles, the extrinsic, the model pose,
// the landmarks; held where the options say.
void BundleAdjuster::AddParameterBlocks() {
  for (int i = 0; i < K_; ++i) {
    problem_.AddParameterBlock(s_.pose[At(i)].data(), kPoseSize, &se3_);
    problem_.AddParameterBlock(&s_.servo[At(i)], 1);
    if (!o_.estimate_servo) problem_.SetParameterBlockConstant(&s_.servo[At(i)]);
  }
  problem_.AddParameterBlock(s_.extrinsic.data(), kPoseSize, &se3_);
  problem_.AddParameterBlock(s_.model.data(), kPoseSize, &se3_);
  if (!o_.estimate_extrinsic) problem_.SetParameterBlockConstant(s_.extrinsic.data());
  if (!o_.estimate_model_pose) problem_.SetParameterBlockConstant(s_.model.data());
  for (auto& l : s_.landmark) problem_.AddParameterBlock(l.data(), 3);
}

// Priors: the gauge, depth/pitch/roll and servo per keyframe, the extrinsic,
// the model pose (eq. 8, on x_gC).
void BundleAdjuster::AddPriorsToProblem(const Pose& x_gM_initial) {
  Label(
      problem_.AddResidualBlock(adjust::GaugePriorFactor::Create(b_.nav[0].x_gv, o_.gauge_sigma_xy, o_.gauge_sigma_yaw),
                                nullptr, s_.pose[0].data()),
      ResidualLabel::kGauge, b_.nav[0].keyframe);
  for (int i = 0; i < K_; ++i) {
    const NavRecord& n = b_.nav[At(i)];
    Label(problem_.AddResidualBlock(
              adjust::ZprFactor::Create(n.depth, n.pitch_meas, n.roll_meas, sigma_.depth, sigma_.roll_pitch), nullptr,
              s_.pose[At(i)].data()),
          ResidualLabel::kZpr, n.keyframe);
    Label(problem_.AddResidualBlock(adjust::ServoPriorFactor::Create(n.servo, sigma_.servo), nullptr, &s_.servo[At(i)]),
          ResidualLabel::kServo, n.keyframe);
  }
  Label(problem_.AddResidualBlock(adjust::PosePriorFactor::Create(extrinsic_nominal_, man_.noise.servo_to_top_sigma),
                                  nullptr, s_.extrinsic.data()),
        ResidualLabel::kExtrinsic);
  const Pose x_gC_prior = x_gM_initial * s_.model_offset.Inverse();
  Label(problem_.AddResidualBlock(adjust::PosePriorFactor::Create(x_gC_prior, Vector6d::Constant(sigma_.model_pose)),
                                  nullptr, s_.model.data()),
        ResidualLabel::kModelPose);
}

// Odometry between keyframes, its sigma growing with the time between them.
void BundleAdjuster::AddOdometryToProblem() {
  for (const OdometryRecord& od : b_.odometry) {
    const int i = kf_index_.at(od.from), j = kf_index_.at(od.to);
    const double dt = std::max(1e-3, std::abs(b_.nav[At(j)].t - b_.nav[At(i)].t));
    Vector6d sigma;
    sigma.head<3>().setConstant(man_.noise.odometry_translation_rate * dt);
    sigma.tail<3>().setConstant(man_.noise.odometry_rotation_rate * dt);
    Label(problem_.AddResidualBlock(adjust::OdometryFactor::Create(od.z, sigma), nullptr, s_.pose[At(i)].data(),
                                    s_.pose[At(j)].data()),
          ResidualLabel::kOdometry, od.from, od.to);
  }
}

// Reprojection: one stereo (or mono) block per observation kept at the
// initialisation, Huber-robust.
void BundleAdjuster::AddReprojectionToProblem() {
  for (std::size_t li = 0; li < s_.landmark.size(); ++li) {
    for (int fi : landmark_obs_[li]) {
      const FeatureObservation& f = b_.features[At(fi)];
      const int k = kf_index_.at(f.keyframe);
      ceres::CostFunction* cf = StereoObservation(f)
                                    ? adjust::StereoReprojectionFactor::Create(&cam_, f.top, f.bottom, sigma_.pixel)
                                    : adjust::MonoReprojectionFactor::Create(&cam_, f.top, sigma_.pixel);
      const ceres::ResidualBlockId id = problem_.AddResidualBlock(
          cf, huber_.get(), s_.pose[At(k)].data(), &s_.servo[At(k)], s_.extrinsic.data(), s_.landmark[li].data());
      reprojection_.push_back({id, li, f.keyframe});
      Label(id, ResidualLabel::kReprojection, s_.landmark_id[li], f.keyframe);
    }
  }
}

// DVL raycasts: one block per beam with a return, Huber-robust.
void BundleAdjuster::AddDvlToProblem() {
  if (!o_.use_dvl) return;
  for (const DvlRecord& d : b_.dvl) {
    const int k = kf_index_.at(d.keyframe);
    for (int beam = 0; beam < 4; ++beam) {
      const double r = d.range[At(beam)];
      if (!DvlRecord::HasReturn(r)) continue;
      Label(problem_.AddResidualBlock(
                adjust::DvlRaycastFactor::Create(&dvl_model_, man_.BeamDirection(beam), r, sigma_.dvl_range),
                huber_.get(), s_.pose[At(k)].data(), &s_.servo[At(k)], s_.model.data()),
            ResidualLabel::kDvl, d.keyframe, beam + 1);
    }
  }
}

// The surface constraint of every landmark (surface_factor.h), unless naive.
void BundleAdjuster::AddSurfaceToProblem() {
  surface_block_.assign(s_.landmark.size(), nullptr);
  cavity_off_.assign(s_.landmark.size(), 0);
  cavity_labels_ = o_.model == SurfaceModel::kMaxMixture && o_.labels == LabelRule::kCavity;
  if (o_.model == SurfaceModel::kNaive) return;
  for (std::size_t li = 0; li < s_.landmark.size(); ++li) {
    surface_block_[li] = problem_.AddResidualBlock(
        adjust::SurfaceFactor::Create(&index_, &s_.model_offset, o_.lookup, o_.model, o_.sigma0, o_.sigma1,
                                      cavity_labels_ ? &cavity_off_[li] : nullptr),
        nullptr, s_.model.data(), s_.landmark[li].data());
    Label(surface_block_[li], ResidualLabel::kSurface, s_.landmark_id[li]);
  }
}

// Per DVL beam with a return, measured minus predicted range at the current
// state: appended (initial) or filled in as the final residual.
void BundleAdjuster::RecordDvlResiduals(bool initial) {
  std::size_t n = 0;
  for (const DvlRecord& d : b_.dvl) {
    const int k = kf_index_.at(d.keyframe);
    for (int beam = 0; beam < 4; ++beam) {
      const double r = d.range[At(beam)];
      if (!DvlRecord::HasReturn(r)) continue;
      const double pred = adjust::DvlRaycastFactor::PredictRange(dvl_model_, s_.pose[At(k)].data(), &s_.servo[At(k)],
                                                                 s_.model.data(), man_.BeamDirection(beam));
      if (initial) {
        result_.dvl.push_back({d.keyframe, beam + 1, r, r - pred, std::nan("")});
      } else {
        result_.dvl[n++].final = r - pred;
      }
    }
  }
}

void BundleAdjuster::RecordInitialDvlResiduals(const Pose& x_gM_initial, bool warm) {
  const std::vector<double> saved(s_.model.begin(), s_.model.end());
  PoseToBlock(x_gM_initial * s_.model_offset.Inverse(), s_.model.data());
  std::vector<std::array<double, kPoseSize>> saved_pose;
  std::vector<double> saved_servo;
  if (warm) {
    saved_pose.assign(s_.pose.begin(), s_.pose.end());
    saved_servo.assign(s_.servo.begin(), s_.servo.end());
    for (int i = 0; i < K_; ++i) {
      PoseToBlock(Pose::FromVector(b_.nav[At(i)].x_gv), s_.pose[At(i)].data());
      s_.servo[At(i)] = b_.nav[At(i)].servo;
    }
  }
  RecordDvlResiduals(true);
  std::copy(saved.begin(), saved.end(), s_.model.begin());
  if (warm) {
    std::copy(saved_pose.begin(), saved_pose.end(), s_.pose.begin());
    std::copy(saved_servo.begin(), saved_servo.end(), s_.servo.begin());
  }
}

// ---- the solve rounds ----------------------------------------------------------------

// Levenberg-Marquardt with the sparse (or iterative) Schur complement, the
// landmarks eliminated first.
ceres::Solver::Options BundleAdjuster::SolverOptions() {
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  const bool iterative = o_.linear_solver == AdjustmentOptions::LinearSolver::kIterativeSchur;
  so.linear_solver_type = iterative ? ceres::ITERATIVE_SCHUR : ceres::SPARSE_SCHUR;
  so.preconditioner_type = ceres::SCHUR_JACOBI;
  so.use_explicit_schur_complement = false;
  so.max_num_iterations = o_.max_iterations;
  if (o_.max_solver_seconds > 0) so.max_solver_time_in_seconds = o_.max_solver_seconds;
  so.function_tolerance = o_.function_tolerance;
  so.gradient_tolerance = o_.gradient_tolerance;
  so.parameter_tolerance = o_.parameter_tolerance;
  so.num_threads =
      o_.num_threads > 0 ? o_.num_threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  num_threads_ = so.num_threads;
  so.minimizer_progress_to_stdout = o_.verbose;
  so.logging_type = o_.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  so.update_state_every_iteration = true;
  for (auto& l : s_.landmark) ordering_->AddElementToGroup(l.data(), 0);
  for (int i = 0; i < K_; ++i) {
    ordering_->AddElementToGroup(s_.pose[At(i)].data(), 1);
    ordering_->AddElementToGroup(&s_.servo[At(i)], 1);
  }
  ordering_->AddElementToGroup(s_.extrinsic.data(), 1);
  ordering_->AddElementToGroup(s_.model.data(), 1);
  so.linear_solver_ordering = ordering_;
  return so;
}

// A runaway (the cost watch), a cancel or a solver failure ends the adjustment.
void BundleAdjuster::ThrowIfSolveFailed(const Observer& observer, const ceres::Solver::Summary& summary) {
  if (!observer.stop_reason().empty()) {
    throw InputError({b_.directory, 0, 0, ""},
                     "the adjustment stopped: " + observer.stop_reason() + ". The largest residual is " +
                         LargestResidual(problem_, block_ids_, block_labels_) + ": the likely input at fault");
  }
  if (summary.termination_type == ceres::USER_FAILURE || progress_.Cancelled()) throw Cancelled();
  if (summary.termination_type == ceres::FAILURE) {
    throw std::runtime_error("bundle adjustment failed: " + summary.message);
  }
}

// Solve; after each solve the cavity E-step and, for rejection_rounds
// rounds, the outlier rejection; solved again while either changed the
// problem (after the rejection rounds: while the labels change, at most
// label_rounds E-steps in all).
void BundleAdjuster::Solve() {
  ceres::Solver::Options so = SolverOptions();
  Observer observer(s_, index_, o_, cavity_off_, progress_, result_.iterations,
                    static_cast<std::size_t>(problem_.NumResiduals()));
  so.callbacks.push_back(&observer);
  progress_.Update(0.1, std::string(SurfaceModelName(o_.model)) + " adjustment: solving");
  dropped_.assign(s_.landmark.size(), 0);
  for (int round = 0;; ++round) {
    observer.set_iteration_offset(result_.iterations.empty() ? 0 : result_.iterations.back().iteration);
    ceres::Solve(so, &problem_, &summary_);
    if (o_.verbose) std::printf("%s\n", summary_.FullReport().c_str());
    ThrowIfSolveFailed(observer, summary_);
    if (initial_cost_ < 0) initial_cost_ = summary_.initial_cost;
    solver_seconds_ += summary_.total_time_in_seconds;
    const std::size_t relabelled = CavityStep();
    if (round >= o_.rejection_rounds) {
      if (relabelled == 0) break;
      progress_.Update(observer.fraction(),
                       std::to_string(relabelled) + " landmarks off the model by their cavity estimate; solving again");
      continue;
    }
    const Rejected rejected = RejectOutliers();
    if (rejected.observations == 0 && relabelled == 0) break;
    progress_.Update(observer.fraction(), "removed " + std::to_string(rejected.observations) +
                                              " outlying observations and " + std::to_string(rejected.landmarks) +
                                              " landmarks, " + std::to_string(relabelled) +
                                              " landmarks off the model by their cavity estimate; solving again");
  }
}

// The E-step by the cavity estimate (cavity_label.h, CavityLabelOff) over
// every landmark still in the problem; returns how many labels changed.
std::size_t BundleAdjuster::CavityStep() {
  if (!cavity_labels_ || label_rounds_ >= o_.label_rounds) return 0;
  ++label_rounds_;
  const Pose x_gM_now = s_.ModelPose();
  std::size_t n = 0;
  for (std::size_t li = 0; li < s_.landmark.size(); ++li) {
    if (dropped_[li]) continue;
    const Eigen::Vector3d l(s_.landmark[li][0], s_.landmark[li][1], s_.landmark[li][2]);
    const double h = adjust::SurfaceDeviation(index_, x_gM_now, l, o_.lookup);
    const char off = adjust::CavityLabelOff(problem_, s_.landmark[li].data(), surface_block_[li], h,
                                            cavity_off_[li] != 0, o_.sigma0, o_.sigma1);
    n += off != cavity_off_[li];
    cavity_off_[li] = off;
  }
  return n;
}

// Removes the observations beyond outlier_sigmas (the 2-D error in either
// camera), then the landmarks left with too few views.
BundleAdjuster::Rejected BundleAdjuster::RejectOutliers() {
  const double limit2 = o_.outlier_sigmas * o_.outlier_sigmas;
  Rejected rejected;
  std::vector<ReprojectionBlock> kept;
  std::set<ceres::ResidualBlockId> gone;
  for (const ReprojectionBlock& rb : reprojection_) {
    double r[4];
    problem_.EvaluateResidualBlock(rb.id, false, nullptr, r, nullptr);
    const int n = problem_.GetCostFunctionForResidualBlock(rb.id)->num_residuals();
    bool bad = r[0] * r[0] + r[1] * r[1] > limit2;
    if (n == 4) bad = bad || r[2] * r[2] + r[3] * r[3] > limit2;
    if (bad) {
      problem_.RemoveResidualBlock(rb.id);
      gone.insert(rb.id);
      ++rejected.observations;
    } else {
      kept.push_back(rb);
    }
  }
  rejected.landmarks = DropLandmarksWithFewViews(&kept, &gone);
  reprojection_.swap(kept);
  ForgetLabelsOf(gone);
  result_.observations_rejected += static_cast<int>(rejected.observations);
  result_.num_landmarks_skipped += static_cast<int>(rejected.landmarks);
  return rejected;
}

// Drops the landmarks whose kept observations span fewer than
// min_observations keyframes (their blocks join *gone and leave *kept);
// updates every landmark's view count; returns how many were dropped.
std::size_t BundleAdjuster::DropLandmarksWithFewViews(std::vector<ReprojectionBlock>* kept,
                                                      std::set<ceres::ResidualBlockId>* gone) {
  std::vector<std::set<std::int64_t>> views(s_.landmark.size());
  for (const ReprojectionBlock& rb : *kept) views[rb.landmark].insert(rb.keyframe);
  std::size_t lost = 0;
  for (std::size_t li = 0; li < s_.landmark.size(); ++li) {
    if (dropped_[li] || static_cast<int>(views[li].size()) >= o_.min_observations) continue;
    std::vector<ceres::ResidualBlockId> with;
    problem_.GetResidualBlocksForParameterBlock(s_.landmark[li].data(), &with);
    gone->insert(with.begin(), with.end());
    problem_.RemoveParameterBlock(s_.landmark[li].data());
    ordering_->Remove(s_.landmark[li].data());
    dropped_[li] = 1;
    ++lost;
  }
  if (lost) {
    std::vector<ReprojectionBlock> still;
    for (const ReprojectionBlock& rb : *kept) {
      if (!dropped_[rb.landmark]) still.push_back(rb);
    }
    kept->swap(still);
  }
  for (std::size_t li = 0; li < s_.landmark.size(); ++li) s_.landmark_views[li] = static_cast<int>(views[li].size());
  return lost;
}

// Keeps the labels of the blocks still in the problem.
void BundleAdjuster::ForgetLabelsOf(const std::set<ceres::ResidualBlockId>& gone) {
  if (gone.empty()) return;
  std::size_t n = 0;
  for (std::size_t i = 0; i < block_ids_.size(); ++i) {
    if (gone.count(block_ids_[i])) continue;
    block_ids_[n] = block_ids_[i];
    block_labels_[n++] = block_labels_[i];
  }
  block_ids_.resize(n);
  block_labels_.resize(n);
}

// ---- the result ------------------------------------------------------------------------

AdjustmentResult BundleAdjuster::CollectResults(const Pose& x_gM_initial) {
  result_.termination =
      std::string(ceres::TerminationTypeToString(summary_.termination_type)) + ": " + summary_.message;
  result_.converged = summary_.termination_type == ceres::CONVERGENCE;
  result_.solver_seconds = solver_seconds_;
  result_.initial_cost = initial_cost_;
  result_.final_cost = summary_.final_cost;
  result_.num_residual_blocks = summary_.num_residual_blocks;
  for (int i = 0; i < K_; ++i) {
    result_.keyframes.push_back(b_.nav[At(i)].keyframe);
    result_.poses.push_back(BlockToPose(s_.pose[At(i)].data()).ToVector());
    result_.servo.push_back(s_.servo[At(i)]);
  }
  result_.x_gM = s_.ModelPose().ToVector();
  result_.x_gM_initial = x_gM_initial.ToVector();
  result_.x_s_cT = BlockToPose(s_.extrinsic.data()).ToVector();
  result_.x_s_cT_initial = extrinsic_nominal_.ToVector();
  // Landmark covariances (landmark_covariance.h), in the order of the kept landmarks.
  std::vector<double*> kept_blocks;
  std::vector<ceres::ResidualBlockId> kept_surface;
  for (std::size_t i = 0; i < s_.landmark.size(); ++i) {
    if (dropped_[i]) continue;
    kept_blocks.push_back(s_.landmark[i].data());
    kept_surface.push_back(surface_block_[i]);
  }
  if (o_.covariance != CovarianceMethod::kNone) progress_.Update(0.95, "landmark covariances");
  const LandmarkCovariances cov =
      ComputeLandmarkCovariances(problem_, kept_blocks, o_.covariance, num_threads_, s_.model.data(), &kept_surface);
  result_.covariance_method = cov.method;
  result_.covariance_note = cov.note;
  result_.covariance_seconds = cov.seconds;
  result_.covariance_cpu_seconds = cov.cpu_seconds;
  result_.covariance_reduced_size = cov.reduced_size;
  result_.covariance_factor_nonzeros = cov.factor_nonzeros;
  CollectLandmarks(cov);
  RecordDvlResiduals(false);
  return std::move(result_);
}

// The kept landmarks with their deviation, covariance, sigma of h and label.
void BundleAdjuster::CollectLandmarks(const LandmarkCovariances& cov) {
  const Pose x_gM = s_.ModelPose();
  for (std::size_t i = 0, kept_index = 0; i < s_.landmark.size(); ++i) {
    if (dropped_[i]) continue;
    LandmarkEstimate e;
    e.id = s_.landmark_id[i];
    e.p = {s_.landmark[i][0], s_.landmark[i][1], s_.landmark[i][2]};
    e.deviation = adjust::SurfaceDeviation(index_, x_gM, e.p, o_.lookup);
    e.covariance = cov.covariance[kept_index];
    e.sigma_h =
        std::isfinite(cov.sigma_h[kept_index])
            ? cov.sigma_h[kept_index]
            : DeviationSigma(e.covariance, x_gM.Rotate(index_.OrthogonalSignedDistance(x_gM, e.p, o_.lookup).normal));
    ++kept_index;
    e.label = cavity_off_[i] ? 0 : MaxMixtureLabel(e.deviation, o_.sigma0, o_.sigma1);
    result_.num_labels_off_by_cavity += cavity_off_[i];
    e.observations = s_.landmark_views[i];
    result_.landmarks.push_back(e);
  }
}

}  // namespace

AdjustmentResult RunAdjustment(const SurveyBundle& b, const TriangleMesh& mesh, const Pose& x_gM_initial,
                               const AdjustmentOptions& o, Progress& progress, const AdjustmentResult* warm) {
  o.Check();
  const auto t0 = Clock::now();
  const OpenMpThreads omp_threads(o.num_threads);
  if (b.nav.empty()) throw InputError({b.directory, 0, 0, "nav.csv"}, "the survey has no keyframes to adjust");
  CheckAdjustable(b, x_gM_initial);
  if (mesh.empty()) throw InputError({"mesh", 0, 0, ""}, "the prior mesh has no faces");
  progress.Update(0.0, "indexing the prior mesh");
  const MeshIndex index(mesh);
  BundleAdjuster adjuster(b, index, o, progress);
  adjuster.InitialiseVehicleStates(warm);
  const Pose x_gM_start = warm ? Pose::FromVector(warm->x_gM) : x_gM_initial;
  adjuster.InitialiseLandmarks(x_gM_start, warm);
  adjuster.PlaceModelPivot(x_gM_start);
  progress.ThrowIfCancelled();
  adjuster.BuildProblem(x_gM_initial);
  adjuster.RecordInitialDvlResiduals(x_gM_initial, warm != nullptr);
  adjuster.Solve();
  AdjustmentResult result = adjuster.CollectResults(x_gM_initial);
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  // The count adjustment.json records: every round's iterations.
  const int iterations = result.iterations.empty() ? 0 : result.iterations.back().iteration;
  progress.Update(
      1.0, std::string(SurfaceModelName(o.model)) + " adjustment done: " + std::to_string(iterations) + " iterations");
  return result;
}

}  // namespace hull
