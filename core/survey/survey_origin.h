// Large coordinates (navigation in UTM-scale metres, as real surveys
// arrive): a survey's frame g moved to a local origin near the survey.
//
// Positions of 10^5 - 10^7 m carry only ~10^-9 m of double precision, but
// what is computed from them degrades long before: a solver's relative
// tolerances (Ceres' parameter tolerance is relative to the norm of the
// state, so a step of centimetres counts as converged at 5,000 km), and
// anything single precision (Embree's BVH, PCL's clouds). The estimators
// (RunAdjustment, AlignDvlToModel) therefore work in the local frame
// g' = g - origin and write their results back in the user's g; with the
// origin on a round grid, a survey already near g's origin (|x|, |y| < 500 m)
// is left exactly as it is.
#pragma once

#include <Eigen/Core>

#include "geometry/pose.h"
#include "survey/survey.h"

namespace hull {

// The spacing of the grid a local origin is put on (m).
constexpr double kLocalOriginGrid = 1000.0;

// The local origin of a survey's g: its first keyframe's horizontal position
// (nav.csv) rounded to kLocalOriginGrid, at z = 0 (depth keeps its meaning);
// zero for a survey without keyframes.
Eigen::Vector3d LocalOrigin(const SurveyBundle& bundle);

// x_gX with g moved by delta (every position in g gains delta): T(delta) * x_gX.
Pose ShiftedFrame(const Pose& x_gX, const Eigen::Vector3d& delta);
Vector6d ShiftedFrame(const Vector6d& x_gX, const Eigen::Vector3d& delta);

// Adds delta to every position the bundle holds in g: the initial poses
// (nav.csv), the model pose guess, landmarks.csv and the truth's poses,
// landmarks and model pose. Everything else (relative measurements, the
// truth's objects in M) is unchanged. ShiftSurvey(b, -LocalOrigin(b))
// makes the local survey; ShiftSurvey(b, {4e5, 5e6, 0}) the demo in
// UTM-scale coordinates (`hullinspect-cli simulate --shift`).
void ShiftSurvey(SurveyBundle& bundle, const Eigen::Vector3d& delta);

}  // namespace hull
