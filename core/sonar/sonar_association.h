// Data association between predicted features and detections, in
// measurement space (range, azimuth):
//  - individual compatibility: the Mahalanobis distance of the innovation
//    with the innovation covariance S = H P H^T + R within the chi-square
//    gate;
//  - joint compatibility branch and bound (JCBB; Neira and Tardos, "Data
//    association in stochastic mapping using the joint compatibility test",
//    2001): the largest set of pairings whose joint innovation passes the
//    joint chi-square gate (the features' predictions are correlated through
//    the pose), the smallest joint distance among equally large sets;
//  - the optimal assignment over individually gated pairs (Hungarian
//    method), each unpaired prediction costing the gate: the fallback when
//    the branch and bound would take too long.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hull {

// The chi-square distribution's quantile: P(X <= q) = p for dof degrees of
// freedom (the regularised incomplete gamma function, inverted by bisection).
double ChiSquareQuantile(double p, int dof);

struct AssociationInput {
  Eigen::VectorXd predicted;              // 2n: (range, azimuth) per prediction
  Eigen::MatrixXd covariance;             // 2n x 2n: H P H^T, joint over the predictions
  std::vector<Eigen::Vector2d> detected;  // m detections
  std::vector<Eigen::Matrix2d> noise;     // their covariances R
};

struct Association {
  std::vector<int> detection;  // per prediction: the detection paired with it, or -1
  int pairs = 0;
  double distance = 0;  // joint squared Mahalanobis distance of the pairings
  long nodes = 0;       // JCBB: nodes visited
  bool jcbb = false;    // found by JCBB (else by the optimal assignment)
};

// The squared Mahalanobis distance of every (prediction, detection) pair;
// infinity where the pair fails the individual gate.
Eigen::MatrixXd IndividualDistances(const AssociationInput& in, double gate_probability);

// JCBB; when it would visit more than max_nodes nodes the optimal
// assignment over the individually compatible pairs is returned instead.
Association JointCompatibility(const AssociationInput& in, double gate_probability, long max_nodes);

// Optimal assignment minimising the sum of distances over finite entries of
// `cost` (rows: predictions, columns: detections), leaving a row unpaired at
// the cost `unpaired`. Returns per row the column or -1.
std::vector<int> OptimalAssignment(const Eigen::MatrixXd& cost, double unpaired);

}  // namespace hull
