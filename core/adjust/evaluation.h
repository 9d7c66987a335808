// Judging an adjustment against a simulated survey's truth. Positions are
// compared in the model frame M (the gauge -- x, y and yaw of the first pose
// held at their dead-reckoned values -- makes errors in g meaningless):
// an estimate l in g maps to M by the estimated x_gM, the truth by the true x_gM.
//
// Where the surveyed part of the hull cannot fix the model pose (a flat
// patch of bottom is unchanged by sliding or turning the hull in its own
// plane; a parallel midbody by sliding along it), only the prior of eq. 8
// places the estimate in those directions, so raw errors in M there measure
// the initial guess, not the adjustment. The "gauge-aligned" figures remove
// exactly those motions: the rigid motions (rotation about the landmarks'
// centroid, translation) that move no true hull landmark off the CAD surface
// to first order, found from the surface normals.
#pragma once

#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "geometry/triangle_mesh.h"
#include "survey/survey.h"

namespace hull {

struct ObjectDeviation {
  std::string id;
  std::string kind;
  double height = 0;               // true height
  double mean_deviation = 0;       // mean estimated deviation of its landmarks
  double true_mean_deviation = 0;  // mean true deviation of the same landmarks
  int landmarks = 0;
};

struct AdjustmentEvaluation {
  std::size_t landmarks = 0;
  int unobservable_dof = 0;      // motions of M the surveyed hull does not observe (0..6)
  double landmark_rmse_raw = 0;  // m, all landmarks, in M, no alignment
  // m, the mean of estimate - truth in M over the same landmarks, no
  // alignment: where the map sits as a whole (e.g. slid along a flat bottom,
  // the direction it leaves free).
  Eigen::Vector3d landmark_mean_error_raw = Eigen::Vector3d::Zero();
  double landmark_rmse = 0;          // m, all landmarks, in M, gauge-aligned
  double landmark_rmse_hull = 0;     // on the nominal hull
  double landmark_rmse_objects = 0;  // on foreign structure
  // Labels against truth, for landmarks whose true |deviation| < 2 cm or > 8 cm.
  std::size_t labels_checked = 0;
  double label_agreement = 0;
  // Where the features put the hull relative to the mesh placed by the
  // estimated x_gM (which the DVL ties to the range returns): the median
  // estimated deviation of landmarks truly on the hull. Near 0 when features
  // and DVL agree on where the hull is (the paper's Fig. 14).
  double hull_feature_offset = 0;
  double hull_feature_spread = 0;  // 1.4826 * MAD of the same
  std::vector<ObjectDeviation> objects;
  // DVL range residuals (measured - predicted), initial alignment vs after.
  double dvl_std_initial = 0, dvl_std_final = 0;
  double dvl_mad_initial = 0, dvl_mad_final = 0;  // 1.4826 * MAD: robust spread
  double dvl_mean_initial = 0, dvl_mean_final = 0;
  // Servo angle error (deg, mean absolute) and the camera extrinsic error.
  double servo_error_initial_deg = 0, servo_error_final_deg = 0;
  double extrinsic_error_initial_m = 0, extrinsic_error_final_m = 0;
  double extrinsic_error_initial_deg = 0, extrinsic_error_final_deg = 0;

  const ObjectDeviation* Object(const std::string& id) const;
  std::string ToString() const;  // a readable multi-line report
};

// mesh: the prior mesh in M. Throws InputError when the bundle has no truth.
AdjustmentEvaluation EvaluateAdjustment(const SurveyBundle& bundle, const TriangleMesh& mesh,
                                        const AdjustmentResult& result);

}  // namespace hull
