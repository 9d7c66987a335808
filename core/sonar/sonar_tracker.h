// Feature tracking for the sonar EKF from image detections (Mai et al.'s
// future work: "automatic ... correspondences of features"). Each step:
//  1. the EKF predicts the pose with the control;
//  2. the features in the state that the prediction puts inside the image
//     are associated with the detections by joint compatibility (JCBB over
//     the individually gated pairs, with the joint innovation covariance
//     H P H^T + R; the optimal assignment when the search grows too large);
//  3. features still waiting to enter the state (SonarEkf's elevation
//     hypotheses: a Gaussian per hypothesis) take the remaining detections
//     by optimal assignment, gated by their best hypothesis;
//  4. every detection left starts a new, tentative feature;
//  5. the EKF is corrected with all of them: a tentative feature enters the
//     state once seen in SonarEkfOptions::confirm_views views (with the EKF's
//     own initialisation, elevation hypotheses or the paper's);
//  6. a tentative feature missed at tentative_misses consecutive steps, and a
//     feature in the state predicted well inside the view but missed at
//     drop_misses consecutive steps, are dropped.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "sonar/sonar_detector.h"
#include "sonar/sonar_ekf.h"

namespace hull {

struct SonarTrackerOptions {
  // Probability of the chi-square gates (individual and joint compatibility).
  double gate_probability = 0.99;
  // Joint compatibility (JCBB) for the features in the state; false: the
  // optimal assignment over individually gated pairs only.
  bool joint_compatibility = true;
  // JCBB's search budget (nodes); beyond it the optimal assignment is used.
  long max_jcbb_nodes = 200000;
  // A tentative feature missed at this many consecutive steps is dropped.
  int tentative_misses = 2;
  // A feature in the state predicted well inside the view but missed at
  // this many consecutive steps is dropped (it was not a point, or it is
  // hidden for good).
  int drop_misses = 8;
  // "Well inside": the predicted elevation within (1 - view_margin) of the
  // fan's half width, range and azimuth at least 2 bins and 2 beams inside
  // the image.
  double view_margin = 0.2;
  // Ids of new features count up from here.
  std::int64_t first_id = 0;

  bool Check(std::string* why = nullptr) const;
};

// What became of a detection.
enum class SonarPairing {
  kInState,  // measured a feature in the state
  kWaiting,  // measured a tentative feature
  kNew,      // started a new tentative feature
};

// What the EKF predicted for a feature at a step, before the correction
// (for display: the fan view draws it with its 2-sigma ellipse).
struct SonarPrediction {
  std::int64_t id = 0;
  Eigen::Vector2d z = Eigen::Vector2d::Zero();               // (range m, azimuth rad)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // H P H^T, without measurement noise
  bool waiting = false;  // a tentative feature: its most likely elevation hypothesis
  int detection = -1;    // the detection paired with it, or -1
};

struct SonarTrackStep {
  SonarStepEstimate estimate;
  // The in-state features predicted inside the image (the association's
  // candidates, in ascending id) and then the waiting ones whose most likely
  // hypothesis falls inside it.
  std::vector<SonarPrediction> predictions;
  std::vector<std::int64_t> feature;  // per detection: the feature it measured or started
  std::vector<SonarPairing> pairing;  // per detection
  int candidates = 0;                 // in-state features predicted inside the image
  int paired_in_state = 0;
  int paired_waiting = 0;
  int started = 0;
  std::vector<std::int64_t> dropped;  // features dropped after this step
  long jcbb_nodes = 0;
  bool jcbb_gave_up = false;  // the optimal assignment was used instead
};

class SonarTracker {
 public:
  // Throws OptionError when options.Check() fails.
  explicit SonarTracker(const SonarTrackerOptions& options = {});

  // One step: predict with the control (nullptr at the first step), associate
  // the step's detections, correct. image gives the polar image's geometry.
  SonarTrackStep Step(SonarEkf& ekf, const SonarControl* control, const std::vector<SonarDetection>& detections,
                      const SonarImageFormat& image);

  const SonarTrackerOptions& options() const { return options_; }

 private:
  SonarTrackerOptions options_;
  std::int64_t next_id_ = 0;
  std::unordered_map<std::int64_t, int> misses_;  // consecutive misses per feature
};

}  // namespace hull
