// The EKF of Mai et al., "3-D Reconstruction of Underwater Object Based on
// Extended Kalman Filter by Using Acoustic Camera Images": the state is the
// sonar pose and the features' 3-D positions,
//   X = [x_c (x, y, z, roll, pitch, yaw), l_1 ... l_n (x, y, z each)],
// with the full covariance P (eq. 1-5). Each step
//   predicts   X^ = g(u, X) = x_c (+) u,   P^ = G P G^T + R       (eq. 6-7)
//   updates    with every in-state feature measured at the step      (eq. 8-13)
// where R is the contract's motion noise (proportional to the motion,
// component by component) mapped through dg/du, the azimuth innovations are
// wrapped and the covariance update is the Joseph form, kept symmetric.
//
// A feature enters the state when first seen, in one of two ways:
//  - kPaper: at elevation 0 with sigma_phi = elevation_fov / 4, the
//    covariance built by propagating range, azimuth and elevation
//    uncertainty and the pose covariance through the inverse model (with the
//    cross-covariances to the rest of the state);
//  - kHypotheses (ours): a Gaussian sum over the elevation, delayed. The
//    first view fixes a 1-D family of points (range and azimuth known,
//    elevation not); K Gaussian hypotheses N(phi_k, (spacing/2)^2) tile the
//    elevation fan. Each later view re-weighs them by its likelihood (the
//    poses of the views are kept in the state as stochastic clones, so the
//    relative pose's uncertainty and correlations are exact) and the unlikely
//    ones are pruned. Once the best hypothesis and its neighbours hold
//    collapse_probability of the weight, the feature enters the state from
//    the first view with their merged Gaussian as elevation prior, and the
//    views of the waiting time are replayed as EKF updates against their
//    clones, so no measurement is lost. Every hypothesis is narrow, so the
//    linearisation stays valid where the paper's single wide Gaussian is
//    linearised far from the truth (e.g. a sonar above the object, where
//    every true elevation has the same sign). After max_delay_steps the
//    feature enters with the whole fan as prior (the paper's start, delayed).
// Cost per step: the update touches only the pose and the measured features'
// columns to form P H^T, then symmetric low-rank corrections of P, in blocks
// of update_block features (O(N^2 m) for a state of size N and m scalar
// measurements; the Joseph form costs twice the short form).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/pose.h"
#include "sonar/sonar_ekf_types.h"
#include "survey/acoustic_sequence.h"

namespace hull {

// The filter's arithmetic broke down at a step: an innovation covariance
// that is not positive definite, a covariance that lost positive
// definiteness, hypothesis weights that are not finite. On a sequence that
// passed the reader's plausibility bounds this should not happen; callers
// that know the sequence (RunSonarPipeline) turn it into an InputError
// naming the file and the fields that feed the filter's numbers.
class SonarNumericalError : public std::runtime_error {
 public:
  SonarNumericalError(std::int64_t step, const std::string& what)
      : std::runtime_error("SonarEkf at step " + std::to_string(step) + ": " + what), step_(step) {}
  std::int64_t step() const { return step_; }

 private:
  std::int64_t step_;
};

class SonarEkf {
 public:
  // Throws OptionError when options.Check() fails.
  SonarEkf(const SonarSensor& sensor, const SonarMotionNoise& motion_noise, const Vector6d& initial_pose,
           const Vector6d& initial_pose_sigma, SonarEkfOptions options = {});
  // Sensor, noise and initial pose from a sequence's manifest.
  explicit SonarEkf(const AcousticSequence& seq, SonarEkfOptions options = {});

  // One step of the filter, for online use: control is the motion from the
  // previous step (nullptr on the first call, required afterwards, its step
  // must be the next one); measurements are every feature seen at this step
  // (their step must be this step's, each feature once). Throws
  // std::invalid_argument on misuse. Returns the pose estimate after the step.
  SonarStepEstimate Step(const SonarControl* control, const std::vector<SonarMeasurement>& measurements);

  // The two halves of Step(), for data association in between: Predict moves
  // to the next step with its control (as Step), Correct then takes that
  // step's measurements. Throws std::invalid_argument when they do not alternate.
  void Predict(const SonarControl* control);
  SonarStepEstimate Correct(const std::vector<SonarMeasurement>& measurements);

  // Predicted measurements of in-state features at the current pose, for
  // gating: z = h(X) (range, azimuth per feature, in the order of ids) and
  // the joint covariance H P H^T (2n x 2n, without measurement noise).
  // Throws std::invalid_argument for an id not in the state.
  void PredictMeasurements(const std::vector<std::int64_t>& ids, Eigen::VectorXd* z, Eigen::MatrixXd* HPHt) const;
  // A waiting feature's predicted measurement, one Gaussian per surviving
  // elevation hypothesis: mean, covariance without the new measurement's
  // noise and normalised weight. Throws std::invalid_argument for an id not waiting.
  struct HypothesisPrediction {
    Eigen::Vector2d z = Eigen::Vector2d::Zero();
    Eigen::Matrix2d S = Eigen::Matrix2d::Identity();
    double weight = 0;
  };
  std::vector<HypothesisPrediction> PredictPending(std::int64_t id) const;
  // Ids in the state and waiting, ascending.
  std::vector<std::int64_t> FeatureIds() const;
  std::vector<std::int64_t> PendingIds() const;
  // Removes a feature from the state (marginalised out: the rest of the
  // estimate is unchanged) or from the waiting list. Returns false when unknown.
  bool DropFeature(std::int64_t id);

  // The step of the last Step() call (-1 before the first).
  std::int64_t step() const { return step_; }
  Vector6d pose() const { return x_.head<6>(); }
  Matrix6d pose_covariance() const { return P_.topLeftCorner<6, 6>(); }
  // Every feature seen so far (in the state and pending), by id.
  std::vector<SonarFeatureEstimate> Features() const;
  std::optional<SonarFeatureEstimate> Feature(std::int64_t id) const;
  int num_features_in_state() const { return static_cast<int>(features_.size()); }
  int num_pending() const { return static_cast<int>(pending_.size()); }

  // The raw state and covariance (pose first, then features and, with
  // kHypotheses, anchor-pose clones in the order they were added).
  const Eigen::VectorXd& state() const { return x_; }
  const Eigen::MatrixXd& covariance() const { return P_; }
  // Offset of a feature's 3 rows in the state, or -1 when it is not in the state.
  int FeatureOffset(std::int64_t id) const;

  const SonarEkfOptions& options() const { return options_; }
  const SonarSensor& sensor() const { return sensor_; }

 private:
  struct FeatureSlot {
    int offset = 0;
    int observations = 0;
    std::int64_t first_step = 0;
  };
  // A past pose kept in the state (stochastic cloning) while a waiting
  // feature has a measurement from it.
  struct Clone {
    std::int64_t step = 0;
    int offset = 0;
    int users = 0;
  };
  struct View {
    std::int64_t step = 0;
    double range = 0, azimuth = 0;
    Eigen::Vector2d sigma = Eigen::Vector2d::Zero();  // of range and azimuth
  };
  // A feature waiting for its elevation (kHypotheses).
  struct Pending {
    std::int64_t id = 0;
    std::vector<View> views;  // views[0] is the first (the anchor)
    std::vector<int> cell;    // surviving hypotheses: index into the fan
    std::vector<double> log_weight;
  };
  // One scalar-pair measurement for the update: the pose block it was taken
  // from (0: the current pose, else a clone) and the feature's block.
  struct Obs {
    int pose_offset = 0;
    int feature_offset = 0;
    double range = 0, azimuth = 0;
    Eigen::Vector2d sigma = Eigen::Vector2d::Zero();  // of range and azimuth
  };

  void PredictPose(const SonarControl& control);
  // Throws std::invalid_argument unless every measurement is of `step`, finite and of a distinct feature.
  void CheckMeasurements(const std::vector<SonarMeasurement>& measurements, std::int64_t step) const;
  // Standard deviations of a measurement's range and azimuth (the sensor's unless it gives its own).
  Eigen::Vector2d NoiseOf(const SonarMeasurement& m) const;
  // Batch EKF update; returns the normalised innovation squared.
  double Update(const std::vector<Obs>& obs);
  // Appends blocks to the state: mean b, covariance of the new block B_bb and
  // cross-covariance with the existing state C (rows: new, cols: old).
  // Returns the offset of the first new row.
  int Append(const Eigen::VectorXd& b, const Eigen::MatrixXd& C, const Eigen::MatrixXd& B_bb);
  void RemoveBlock(int offset, int size);
  // kPaper: every new feature of the step enters the state.
  void InitialisePaper(const std::vector<const SonarMeasurement*>& fresh);
  // kHypotheses.
  double Spacing() const { return sensor_.elevation_fov / options_.hypotheses; }
  double CellElevation(int cell) const { return -sensor_.elevation_fov / 2 + Spacing() * (cell + 0.5); }
  int CloneOffset(std::int64_t step) const;
  void EnsureClone();  // a clone of the current pose for this step
  void WeighPending(Pending& pd, const SonarMeasurement& m) const;
  // Per hypothesis: predicted measurement and its covariance without the new measurement's noise.
  std::vector<HypothesisPrediction> HypothesisPredictions(const Pending& pd) const;
  // The merged Gaussian (mean, sigma) of the hypotheses within one cell of the
  // best, and the share of the weight they hold.
  struct Collapse {
    double phi = 0, sigma = 0, mass = 0;
  };
  Collapse CollapseOf(const Pending& pd) const;
  // Moments (mean, sigma) of the whole prior fan.
  std::pair<double, double> FanMoments() const;
  // Enters the given pending features (indices into pending_) with the given
  // elevation priors and replays their views; returns the NIS of the replay
  // and its degrees of freedom.
  std::pair<double, int> PromotePending(const std::vector<std::size_t>& which,
                                        const std::vector<std::pair<double, double>>& priors);
  void ReleaseClones();
  SonarFeatureEstimate PendingEstimate(const Pending& pd) const;

  SonarSensor sensor_;
  SonarMotionNoise motion_noise_;
  SonarEkfOptions options_;
  std::int64_t step_ = -1;
  bool predicted_ = false;  // Predict() done, Correct() not yet
  Eigen::VectorXd x_;
  Eigen::MatrixXd P_;
  std::unordered_map<std::int64_t, FeatureSlot> features_;
  std::vector<Clone> clones_;
  std::vector<Pending> pending_;
};

}  // namespace hull
