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
  const SurveyManifest& man = b.manifest;
  const NoiseModel& nz = man.noise;
  const double pixel_sigma = Or(o.pixel_sigma, nz.pixel_sigma);
  const double dvl_sigma = Or(o.dvl_range_sigma, nz.dvl_range_sigma);
  const double depth_sigma = Or(o.depth_sigma, nz.depth_sigma);
  const double rp_sigma = Or(o.roll_pitch_sigma, nz.roll_pitch_sigma);
  const double servo_sigma = Or(o.servo_sigma, nz.servo_sigma);
  const double model_sigma = Or(o.model_pose_sigma, nz.model_pose_sigma);
  const auto kf_index = b.KeyframeIndex();
  const int K = static_cast<int>(b.nav.size());

  // ---- initial state ------------------------------------------------------------
  // Landmarks: at most one per observation.
  State s(static_cast<std::size_t>(K), b.features.size());
  std::unordered_map<std::int64_t, int> warm_kf;
  if (warm) {
    for (std::size_t i = 0; i < warm->keyframes.size(); ++i) warm_kf[warm->keyframes[i]] = static_cast<int>(i);
  }
  for (int i = 0; i < K; ++i) {
    const NavRecord& n = b.nav[static_cast<std::size_t>(i)];
    auto w = warm_kf.find(n.keyframe);
    if (w != warm_kf.end()) {
      PoseToBlock(Pose::FromVector(warm->poses[static_cast<std::size_t>(w->second)]), s.pose[i].data());
      s.servo[static_cast<std::size_t>(i)] = warm->servo[static_cast<std::size_t>(w->second)];
    } else {
      PoseToBlock(Pose::FromVector(n.x_gv), s.pose[i].data());
      s.servo[static_cast<std::size_t>(i)] = n.servo;
    }
  }
  const Pose extrinsic_nominal = Pose::FromVector(man.camera.servo_to_top);
  PoseToBlock(warm ? Pose::FromVector(warm->x_s_cT) : extrinsic_nominal, s.extrinsic.data());
  const Pose x_gM_start = warm ? Pose::FromVector(warm->x_gM) : x_gM_initial;

  adjust::CameraModel cam;
  cam.mount = Pose::FromVector(man.servo_mount);
  cam.top_to_bottom = Pose::FromVector(man.camera.top_to_bottom);
  cam.top = man.camera.top;
  cam.bottom = man.camera.bottom;
  adjust::DvlModel dvl_model;
  dvl_model.mesh = &index;
  dvl_model.mount = cam.mount;
  dvl_model.servo_to_dvl = Pose::FromVector(man.servo_to_dvl);

  // Observations per landmark.
  std::unordered_map<std::int64_t, std::vector<int>> obs_of;
  for (int i = 0; i < static_cast<int>(b.features.size()); ++i)
    obs_of[b.features[static_cast<std::size_t>(i)].landmark].push_back(i);
  std::unordered_map<std::int64_t, Eigen::Vector3d> given;
  if (b.landmarks) {
    for (const auto& l : *b.landmarks) given[l.landmark] = l.p;
  }
  std::unordered_map<std::int64_t, Eigen::Vector3d> warm_lm;
  if (warm) {
    for (const auto& l : warm->landmarks) warm_lm[l.id] = l.p;
  }
  progress.Update(0.03, "initialising landmarks");
  std::vector<std::int64_t> ids;
  ids.reserve(obs_of.size());
  for (const auto& [id, list] : obs_of) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  const Pose x_s_cT0 = BlockToPose(s.extrinsic.data());
  const Pose x_gM0 = x_gM_start;
  std::vector<std::vector<int>> lm_obs;  // observations used, per kept landmark
  int skipped = 0, behind = 0, off_model = 0;
  for (std::int64_t id : ids) {
    const std::vector<int>& list = obs_of[id];
    std::set<std::int64_t> views;
    for (int fi : list) views.insert(b.features[static_cast<std::size_t>(fi)].keyframe);
    if (static_cast<int>(views.size()) < o.min_observations) {
      ++skipped;
      continue;
    }
    Eigen::Vector3d p;
    std::vector<int> used = list;
    if (auto w = warm_lm.find(id); w != warm_lm.end()) {
      p = w->second;
    } else if (auto g = given.find(id); g != given.end()) {
      p = g->second;
    } else {
      std::vector<ViewRay> rays;
      std::vector<int> ray_obs;
      for (int fi : list) {
        const FeatureObservation& f = b.features[static_cast<std::size_t>(fi)];
        const int k = kf_index.at(f.keyframe);
        const Pose g_cT = BlockToPose(s.pose[static_cast<std::size_t>(k)].data()) *
                          man.VehicleToServo(s.servo[static_cast<std::size_t>(k)]) * x_s_cT0;
        auto add = [&](const Pose& g_c, const PinholeIntrinsics& K_, const Eigen::Vector2d& uv) {
          ViewRay r;
          r.origin = g_c.translation();
          r.dir = g_c.Rotate(K_.Unproject(uv)).normalized();
          r.g_c = g_c;
          r.pixel = uv;
          r.fx = K_.fx;
          r.fy = K_.fy;
          r.cx = K_.cx;
          r.cy = K_.cy;
          rays.push_back(r);
          ray_obs.push_back(fi);
        };
        add(g_cT, cam.top, f.top);
        if (f.has_bottom && man.camera.stereo()) add(g_cT * cam.top_to_bottom, cam.bottom, f.bottom);
      }
      const auto t = TriangulateLandmark(rays, TriangulationOptions{}, &index, x_gM0);
      if (!t) {
        ++skipped;
        continue;
      }
      p = t->point;
      if (o.max_initial_deviation > 0 && !t->from_mesh && !NearTheMesh(index, x_gM0, p, rays, t->inliers, o)) {
        ++skipped;
        ++off_model;
        continue;
      }
    }
    // Observations whose camera sees the initial point from behind cannot be
    // evaluated (Ceres needs every residual at the start): leave them out.
    {
      std::vector<int> in_front;
      std::set<std::int64_t> kept_views;
      for (int fi : used) {
        const FeatureObservation& f = b.features[static_cast<std::size_t>(fi)];
        const int k = kf_index.at(f.keyframe);
        const Pose g_cT = BlockToPose(s.pose[static_cast<std::size_t>(k)].data()) *
                          man.VehicleToServo(s.servo[static_cast<std::size_t>(k)]) * x_s_cT0;
        const bool front = (g_cT.Inverse() * p).z() > 0.05 && (!(f.has_bottom && man.camera.stereo()) ||
                                                               ((g_cT * cam.top_to_bottom).Inverse() * p).z() > 0.05);
        if (front) {
          in_front.push_back(fi);
          kept_views.insert(f.keyframe);
        } else {
          ++behind;
        }
      }
      if (static_cast<int>(kept_views.size()) < o.min_observations) {
        ++skipped;
        continue;
      }
      used.swap(in_front);
      views.swap(kept_views);
    }
    s.landmark.push_back({p.x(), p.y(), p.z()});
    s.landmark_id.push_back(id);
    s.landmark_views.push_back(static_cast<int>(views.size()));
    lm_obs.push_back(used);
  }
  if (s.landmark.empty() && !b.features.empty()) {
    throw InputError({b.directory, 0, 0, "features.csv"}, "no landmark could be initialised");
  }
  // The pivot of the model pose: the centroid of the landmarks (or of the vehicle positions).
  {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    if (!s.landmark.empty()) {
      for (const auto& l : s.landmark) c += Eigen::Vector3d(l[0], l[1], l[2]);
      c /= static_cast<double>(s.landmark.size());
    } else {
      for (const auto& p : s.pose) c += Eigen::Vector3d(p[4], p[5], p[6]);
      c /= static_cast<double>(s.pose.size());
    }
    const Pose x_gC(x_gM_start.quaternion(), c);
    s.model_offset = x_gC.Inverse() * x_gM_start;
    PoseToBlock(x_gC, s.model.data());
    dvl_model.model_offset = s.model_offset;
  }
  progress.ThrowIfCancelled();

  // ---- the problem ------------------------------------------------------------------
  progress.Update(0.06, "building the factor graph");
  ceres::Problem::Options po;
  po.enable_fast_removal = true;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> se3;
  ceres::HuberLoss huber(o.huber_sigmas);
  std::vector<ceres::ResidualBlockId> block_ids;  // with labels, to name the likely input of a runaway
  std::vector<ResidualLabel> block_labels;
  auto label = [&](ceres::ResidualBlockId id, ResidualLabel::Kind kind, std::int64_t a = 0, std::int64_t b_ = 0) {
    block_ids.push_back(id);
    block_labels.push_back({kind, a, b_});
  };
  for (int i = 0; i < K; ++i) {
    problem.AddParameterBlock(s.pose[static_cast<std::size_t>(i)].data(), kPoseSize, &se3);
    problem.AddParameterBlock(&s.servo[static_cast<std::size_t>(i)], 1);
    if (!o.estimate_servo) problem.SetParameterBlockConstant(&s.servo[static_cast<std::size_t>(i)]);
  }
  problem.AddParameterBlock(s.extrinsic.data(), kPoseSize, &se3);
  problem.AddParameterBlock(s.model.data(), kPoseSize, &se3);
  if (!o.estimate_extrinsic) problem.SetParameterBlockConstant(s.extrinsic.data());
  if (!o.estimate_model_pose) problem.SetParameterBlockConstant(s.model.data());
  for (auto& l : s.landmark) problem.AddParameterBlock(l.data(), 3);

  // Priors: gauge, zpr, servo, extrinsic, model pose.
  label(problem.AddResidualBlock(adjust::GaugePriorFactor::Create(b.nav[0].x_gv, o.gauge_sigma_xy, o.gauge_sigma_yaw),
                                 nullptr, s.pose[0].data()),
        ResidualLabel::kGauge, b.nav[0].keyframe);
  for (int i = 0; i < K; ++i) {
    const NavRecord& n = b.nav[static_cast<std::size_t>(i)];
    label(problem.AddResidualBlock(adjust::ZprFactor::Create(n.depth, n.pitch_meas, n.roll_meas, depth_sigma, rp_sigma),
                                   nullptr, s.pose[static_cast<std::size_t>(i)].data()),
          ResidualLabel::kZpr, n.keyframe);
    label(problem.AddResidualBlock(adjust::ServoPriorFactor::Create(n.servo, servo_sigma), nullptr,
                                   &s.servo[static_cast<std::size_t>(i)]),
          ResidualLabel::kServo, n.keyframe);
  }
  label(problem.AddResidualBlock(adjust::PosePriorFactor::Create(extrinsic_nominal, nz.servo_to_top_sigma), nullptr,
                                 s.extrinsic.data()),
        ResidualLabel::kExtrinsic);
  const Pose x_gC_prior = x_gM_initial * s.model_offset.Inverse();
  label(problem.AddResidualBlock(adjust::PosePriorFactor::Create(x_gC_prior, Vector6d::Constant(model_sigma)), nullptr,
                                 s.model.data()),
        ResidualLabel::kModelPose);
  // Odometry.
  for (const OdometryRecord& od : b.odometry) {
    const int i = kf_index.at(od.from), j = kf_index.at(od.to);
    const double dt =
        std::max(1e-3, std::abs(b.nav[static_cast<std::size_t>(j)].t - b.nav[static_cast<std::size_t>(i)].t));
    Vector6d sigma;
    sigma.head<3>().setConstant(nz.odometry_translation_rate * dt);
    sigma.tail<3>().setConstant(nz.odometry_rotation_rate * dt);
    label(problem.AddResidualBlock(adjust::OdometryFactor::Create(od.z, sigma), nullptr,
                                   s.pose[static_cast<std::size_t>(i)].data(),
                                   s.pose[static_cast<std::size_t>(j)].data()),
          ResidualLabel::kOdometry, od.from, od.to);
  }
  // Reprojection.
  struct ReprojectionBlock {
    ceres::ResidualBlockId id;
    std::size_t landmark;
    std::int64_t keyframe;
  };
  std::vector<ReprojectionBlock> reprojection;
  for (std::size_t li = 0; li < s.landmark.size(); ++li) {
    for (int fi : lm_obs[li]) {
      const FeatureObservation& f = b.features[static_cast<std::size_t>(fi)];
      const int k = kf_index.at(f.keyframe);
      ceres::CostFunction* cf = (man.camera.stereo() && f.has_bottom)
                                    ? adjust::StereoReprojectionFactor::Create(&cam, f.top, f.bottom, pixel_sigma)
                                    : adjust::MonoReprojectionFactor::Create(&cam, f.top, pixel_sigma);
      const ceres::ResidualBlockId id =
          problem.AddResidualBlock(cf, &huber, s.pose[static_cast<std::size_t>(k)].data(),
                                   &s.servo[static_cast<std::size_t>(k)], s.extrinsic.data(), s.landmark[li].data());
      reprojection.push_back({id, li, f.keyframe});
      label(id, ResidualLabel::kReprojection, s.landmark_id[li], f.keyframe);
    }
  }
  // DVL raycasts.
  if (o.use_dvl) {
    for (const DvlRecord& d : b.dvl) {
      const int k = kf_index.at(d.keyframe);
      for (int beam = 0; beam < 4; ++beam) {
        const double r = d.range[static_cast<std::size_t>(beam)];
        if (!DvlRecord::HasReturn(r)) continue;
        label(problem.AddResidualBlock(
                  adjust::DvlRaycastFactor::Create(&dvl_model, man.BeamDirection(beam), r, dvl_sigma), &huber,
                  s.pose[static_cast<std::size_t>(k)].data(), &s.servo[static_cast<std::size_t>(k)], s.model.data()),
              ResidualLabel::kDvl, d.keyframe, beam + 1);
      }
    }
  }
  // Surface constraints.
  std::vector<ceres::ResidualBlockId> surface_block(s.landmark.size(), nullptr);
  // Per landmark: labelled off the model by its cavity estimate (the E-step
  // between solves, LabelRule::kCavity); the factors read it, so it is never
  // resized.
  std::vector<char> cavity_off(s.landmark.size(), 0);
  const bool cavity_labels = o.model == SurfaceModel::kMaxMixture && o.labels == LabelRule::kCavity;
  if (o.model != SurfaceModel::kNaive) {
    for (std::size_t li = 0; li < s.landmark.size(); ++li) {
      surface_block[li] =
          problem.AddResidualBlock(adjust::SurfaceFactor::Create(&index, &s.model_offset, o.lookup, o.model, o.sigma0,
                                                                 o.sigma1, cavity_labels ? &cavity_off[li] : nullptr),
                                   nullptr, s.model.data(), s.landmark[li].data());
      label(surface_block[li], ResidualLabel::kSurface, s.landmark_id[li]);
    }
  }

  // ---- DVL residuals at the start (the initial alignment) ---------------------------
  AdjustmentResult result;
  result.options = o;
  result.num_landmarks_skipped = skipped;
  result.num_landmarks_off_model = off_model;
  result.observations_rejected = behind;
  auto dvl_residuals = [&](bool initial) {
    std::size_t n = 0;
    for (const DvlRecord& d : b.dvl) {
      const int k = kf_index.at(d.keyframe);
      for (int beam = 0; beam < 4; ++beam) {
        const double r = d.range[static_cast<std::size_t>(beam)];
        if (!DvlRecord::HasReturn(r)) continue;
        const double pred = adjust::DvlRaycastFactor::PredictRange(
            dvl_model, s.pose[static_cast<std::size_t>(k)].data(), &s.servo[static_cast<std::size_t>(k)],
            s.model.data(), man.BeamDirection(beam));
        if (initial) {
          result.dvl.push_back({d.keyframe, beam + 1, r, r - pred, std::nan("")});
        } else {
          result.dvl[n++].final = r - pred;
        }
      }
    }
  };
  {
    // The initial alignment: initial poses and servo angles against x_gM_initial.
    const std::vector<double> saved(s.model.begin(), s.model.end());
    PoseToBlock(x_gM_initial * s.model_offset.Inverse(), s.model.data());
    std::vector<std::array<double, kPoseSize>> saved_pose;
    std::vector<double> saved_servo;
    if (warm) {
      saved_pose.assign(s.pose.begin(), s.pose.end());
      saved_servo.assign(s.servo.begin(), s.servo.end());
      for (int i = 0; i < K; ++i) {
        PoseToBlock(Pose::FromVector(b.nav[static_cast<std::size_t>(i)].x_gv),
                    s.pose[static_cast<std::size_t>(i)].data());
        s.servo[static_cast<std::size_t>(i)] = b.nav[static_cast<std::size_t>(i)].servo;
      }
    }
    dvl_residuals(true);
    std::copy(saved.begin(), saved.end(), s.model.begin());
    if (warm) {
      std::copy(saved_pose.begin(), saved_pose.end(), s.pose.begin());
      std::copy(saved_servo.begin(), saved_servo.end(), s.servo.begin());
    }
  }

  // ---- solve ------------------------------------------------------------------------
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  const bool iterative = o.linear_solver == AdjustmentOptions::LinearSolver::kIterativeSchur;
  so.linear_solver_type = iterative ? ceres::ITERATIVE_SCHUR : ceres::SPARSE_SCHUR;
  so.preconditioner_type = ceres::SCHUR_JACOBI;
  so.use_explicit_schur_complement = false;
  so.max_num_iterations = o.max_iterations;
  if (o.max_solver_seconds > 0) so.max_solver_time_in_seconds = o.max_solver_seconds;
  so.function_tolerance = o.function_tolerance;
  so.gradient_tolerance = o.gradient_tolerance;
  so.parameter_tolerance = o.parameter_tolerance;
  so.num_threads =
      o.num_threads > 0 ? o.num_threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  so.minimizer_progress_to_stdout = o.verbose;
  so.logging_type = o.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  so.update_state_every_iteration = true;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (auto& l : s.landmark) ordering->AddElementToGroup(l.data(), 0);
  for (int i = 0; i < K; ++i) {
    ordering->AddElementToGroup(s.pose[static_cast<std::size_t>(i)].data(), 1);
    ordering->AddElementToGroup(&s.servo[static_cast<std::size_t>(i)], 1);
  }
  ordering->AddElementToGroup(s.extrinsic.data(), 1);
  ordering->AddElementToGroup(s.model.data(), 1);
  so.linear_solver_ordering = ordering;
  Observer observer(s, index, o, cavity_off, progress, result.iterations,
                    static_cast<std::size_t>(problem.NumResiduals()));
  so.callbacks.push_back(&observer);
  progress.Update(0.1, std::string(SurfaceModelName(o.model)) + " adjustment: solving");
  ceres::Solver::Summary summary;
  std::vector<char> dropped(s.landmark.size(), 0);
  double initial_cost = -1, solver_seconds = 0;
  // The E-step by the cavity estimate (cavity_label.h, CavityLabelOff) over
  // every landmark still in the problem; returns how many labels changed.
  int label_rounds = 0;
  auto cavity_step = [&]() -> std::size_t {
    if (!cavity_labels || label_rounds >= o.label_rounds) return 0;
    ++label_rounds;
    const Pose x_gM_now = s.ModelPose();
    std::size_t n = 0;
    for (std::size_t li = 0; li < s.landmark.size(); ++li) {
      if (dropped[li]) continue;
      const Eigen::Vector3d l(s.landmark[li][0], s.landmark[li][1], s.landmark[li][2]);
      const double h = adjust::SurfaceDeviation(index, x_gM_now, l, o.lookup);
      const char off = adjust::CavityLabelOff(problem, s.landmark[li].data(), surface_block[li], h, cavity_off[li] != 0,
                                              o.sigma0, o.sigma1);
      n += off != cavity_off[li];
      cavity_off[li] = off;
    }
    return n;
  };
  for (int round = 0;; ++round) {
    observer.set_iteration_offset(result.iterations.empty() ? 0 : result.iterations.back().iteration);
    ceres::Solve(so, &problem, &summary);
    if (o.verbose) std::printf("%s\n", summary.FullReport().c_str());
    if (!observer.stop_reason().empty()) {
      throw InputError({b.directory, 0, 0, ""},
                       "the adjustment stopped: " + observer.stop_reason() + ". The largest residual is " +
                           LargestResidual(problem, block_ids, block_labels) + ": the likely input at fault");
    }
    if (summary.termination_type == ceres::USER_FAILURE || progress.Cancelled()) throw Cancelled();
    if (summary.termination_type == ceres::FAILURE) {
      throw std::runtime_error("bundle adjustment failed: " + summary.message);
    }
    if (initial_cost < 0) initial_cost = summary.initial_cost;
    solver_seconds += summary.total_time_in_seconds;
    const std::size_t relabelled = cavity_step();
    if (round >= o.rejection_rounds) {
      if (relabelled == 0) break;
      progress.Update(observer.fraction(),
                      std::to_string(relabelled) + " landmarks off the model by their cavity estimate; solving again");
      continue;
    }
    // Remove observations beyond outlier_sigmas (the 2-D error in either camera).
    const double limit2 = o.outlier_sigmas * o.outlier_sigmas;
    std::size_t removed = 0;
    std::vector<ReprojectionBlock> kept;
    std::set<ceres::ResidualBlockId> gone;
    for (const ReprojectionBlock& rb : reprojection) {
      double r[4];
      problem.EvaluateResidualBlock(rb.id, false, nullptr, r, nullptr);
      const int n = problem.GetCostFunctionForResidualBlock(rb.id)->num_residuals();
      bool bad = r[0] * r[0] + r[1] * r[1] > limit2;
      if (n == 4) bad = bad || r[2] * r[2] + r[3] * r[3] > limit2;
      if (bad) {
        problem.RemoveResidualBlock(rb.id);
        gone.insert(rb.id);
        ++removed;
      } else {
        kept.push_back(rb);
      }
    }
    // Drop landmarks left with too few views.
    std::vector<std::set<std::int64_t>> views(s.landmark.size());
    for (const ReprojectionBlock& rb : kept) views[rb.landmark].insert(rb.keyframe);
    std::size_t lost = 0;
    for (std::size_t li = 0; li < s.landmark.size(); ++li) {
      if (dropped[li] || static_cast<int>(views[li].size()) >= o.min_observations) continue;
      std::vector<ceres::ResidualBlockId> with;
      problem.GetResidualBlocksForParameterBlock(s.landmark[li].data(), &with);
      gone.insert(with.begin(), with.end());
      problem.RemoveParameterBlock(s.landmark[li].data());
      ordering->Remove(s.landmark[li].data());
      dropped[li] = 1;
      ++lost;
    }
    if (lost) {
      std::vector<ReprojectionBlock> still;
      for (const ReprojectionBlock& rb : kept) {
        if (!dropped[rb.landmark]) still.push_back(rb);
      }
      kept.swap(still);
    }
    reprojection.swap(kept);
    if (!gone.empty()) {  // keep the labels of the blocks still in the problem
      std::size_t n = 0;
      for (std::size_t i = 0; i < block_ids.size(); ++i) {
        if (gone.count(block_ids[i])) continue;
        block_ids[n] = block_ids[i];
        block_labels[n++] = block_labels[i];
      }
      block_ids.resize(n);
      block_labels.resize(n);
    }
    result.observations_rejected += static_cast<int>(removed);
    result.num_landmarks_skipped += static_cast<int>(lost);
    for (std::size_t li = 0; li < s.landmark.size(); ++li) s.landmark_views[li] = static_cast<int>(views[li].size());
    if (removed == 0 && relabelled == 0) break;
    progress.Update(observer.fraction(), "removed " + std::to_string(removed) + " outlying observations and " +
                                             std::to_string(lost) + " landmarks, " + std::to_string(relabelled) +
                                             " landmarks off the model by their cavity estimate; solving again");
  }

  // ---- results ------------------------------------------------------------------------
  result.termination = std::string(ceres::TerminationTypeToString(summary.termination_type)) + ": " + summary.message;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.solver_seconds = solver_seconds;
  result.initial_cost = initial_cost;
  result.final_cost = summary.final_cost;
  result.num_residual_blocks = summary.num_residual_blocks;
  for (int i = 0; i < K; ++i) {
    result.keyframes.push_back(b.nav[static_cast<std::size_t>(i)].keyframe);
    result.poses.push_back(BlockToPose(s.pose[static_cast<std::size_t>(i)].data()).ToVector());
    result.servo.push_back(s.servo[static_cast<std::size_t>(i)]);
  }
  result.x_gM = s.ModelPose().ToVector();
  result.x_gM_initial = x_gM_initial.ToVector();
  result.x_s_cT = BlockToPose(s.extrinsic.data()).ToVector();
  result.x_s_cT_initial = extrinsic_nominal.ToVector();
  const Pose x_gM = s.ModelPose();
  // Landmark covariances (landmark_covariance.h), in the order of the kept landmarks.
  std::vector<double*> kept_blocks;
  std::vector<ceres::ResidualBlockId> kept_surface;
  for (std::size_t i = 0; i < s.landmark.size(); ++i) {
    if (dropped[i]) continue;
    kept_blocks.push_back(s.landmark[i].data());
    kept_surface.push_back(surface_block[i]);
  }
  if (o.covariance != CovarianceMethod::kNone) progress.Update(0.95, "landmark covariances");
  const LandmarkCovariances cov =
      ComputeLandmarkCovariances(problem, kept_blocks, o.covariance, so.num_threads, s.model.data(), &kept_surface);
  result.covariance_method = cov.method;
  result.covariance_note = cov.note;
  result.covariance_seconds = cov.seconds;
  result.covariance_cpu_seconds = cov.cpu_seconds;
  result.covariance_reduced_size = cov.reduced_size;
  result.covariance_factor_nonzeros = cov.factor_nonzeros;
  for (std::size_t i = 0, kept_index = 0; i < s.landmark.size(); ++i) {
    if (dropped[i]) continue;
    LandmarkEstimate e;
    e.id = s.landmark_id[i];
    e.p = {s.landmark[i][0], s.landmark[i][1], s.landmark[i][2]};
    e.deviation = adjust::SurfaceDeviation(index, x_gM, e.p, o.lookup);
    e.covariance = cov.covariance[kept_index];
    e.sigma_h =
        std::isfinite(cov.sigma_h[kept_index])
            ? cov.sigma_h[kept_index]
            : DeviationSigma(e.covariance, x_gM.Rotate(index.OrthogonalSignedDistance(x_gM, e.p, o.lookup).normal));
    ++kept_index;
    e.label = cavity_off[i] ? 0 : MaxMixtureLabel(e.deviation, o.sigma0, o.sigma1);
    result.num_labels_off_by_cavity += cavity_off[i];
    e.observations = s.landmark_views[i];
    result.landmarks.push_back(e);
  }
  dvl_residuals(false);
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  // The count adjustment.json records: every round's iterations.
  const int iterations = result.iterations.empty() ? 0 : result.iterations.back().iteration;
  progress.Update(
      1.0, std::string(SurfaceModelName(o.model)) + " adjustment done: " + std::to_string(iterations) + " iterations");
  return result;
}

}  // namespace hull
