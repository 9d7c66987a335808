// Registering two surveys of one hull to each other before comparing them.
//
// Each survey's adjustment places the CAD model in its own world frame, and a
// survey of a flat stretch of hull leaves the model's pose free in the
// directions the flat part cannot fix (along and across the hull, yaw about
// its normal: alignment.json's unconstrained directions). Two surveys' maps,
// both expressed in M, can therefore be shifted and turned against each other
// along the surface by metres and degrees (measured on the demo pair: the
// same objects' centroids 0.2-0.4 m apart after 1.6 m, 3.5 m and 2.2 deg of
// difference in x_gM). The objects that persist between the surveys fix that
// motion: a RANSAC over pairs of putative object correspondences, each pair
// giving a rigid motion (Umeyama on the two centroids and the points one
// metre out along their normals), scored by how many of B's objects it
// brings within the match radius of one of A's, then refined over its
// inliers.
#pragma once

#include <vector>

#include "geometry/pose.h"
#include "mapping/detected_objects.h"

namespace hull {

struct SurveyRegistrationOptions {
  double match_radius = 0.30;   // m: a registered B object this close to an A object is an inlier
  double max_offset = 5.0;      // m: how far apart one object's two centroids may lie before registration
  double max_rotation = 0.35;   // rad (20 deg): larger motions are not considered
  int min_inliers = 3;          // fewer objects in common: no registration (identity)
  int max_hypotheses = 200000;  // pairs of correspondences tried at most (sampled, seeded, when there are more)
  void Check() const;           // throws OptionError naming the field
};

struct SurveyRegistration {
  Pose a_from_b;             // x_AB: a point of B's map in M, as A's map has it: p_A = x_AB * p_B
  bool registered = false;   // false: too few objects in common, a_from_b is the identity
  int inliers = 0;           // B's objects within match_radius of one of A's under a_from_b
  int identity_inliers = 0;  // the same count without registration
  double rms = 0;            // m, centroid residual over the inliers
  double rotation = 0;       // rad, the angle of a_from_b's rotation
  double translation = 0;    // m, the length of its translation
};

// Deterministic (seeded sampling). a, b: the two surveys' objects with their
// centroids and normals in M.
SurveyRegistration RegisterSurveys(const std::vector<DetectedObject>& a, const std::vector<DetectedObject>& b,
                                   const SurveyRegistrationOptions& options);

}  // namespace hull
