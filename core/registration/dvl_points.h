// DVL returns as 3-D points in the navigation frame g.
//
// Beam b of keyframe i leaves the DVL head, whose pose in g is
//   x_gd = x_gv_i (+) x_vs(theta_i) (+) x_s_d,
// from its origin t_gd along the unit direction R_gd * beam_b / |beam_b|
// (survey contract: readers normalise the beams); a measured range r puts the
// return at t_gd + r * direction.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "geometry/pose.h"
#include "survey/survey.h"

namespace hull {

// One DVL beam with a return.
struct DvlPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       // the return, in g
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // the DVL head's origin, in g
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit beam direction, in g
  double range = 0;                                      // measured range (m)
  std::int64_t keyframe = 0;                             // keyframe id (nav.csv)
  int nav_index = 0;                                     // index into SurveyBundle::nav
  int beam = 0;                                          // 0..3, in the order of dvl.beams (dvl.csv r1..r4)
};

// x_vd(theta) = x_vs(theta) (+) x_s_d: the DVL head in the vehicle frame.
Pose VehicleToDvl(const SurveyManifest& manifest, double servo);

// The returns of every dvl.csv row (beams without a return are skipped), in
// file order, from the vehicle poses x_gv and servo angles given per nav
// record (both of size bundle.nav.size(), indexed like bundle.nav). Throws
// std::invalid_argument when the sizes differ and InputError (dvl.csv) when a
// row names a keyframe that nav.csv lacks.
std::vector<DvlPoint> DvlPointsInG(const SurveyBundle& bundle, const std::vector<Pose>& x_gv,
                                   const std::vector<double>& servo);

// The same from the bundle's initial estimates: nav.csv's x_gv (dead
// reckoning) and its instrumented servo angles.
std::vector<DvlPoint> DvlPointsFromInitialNav(const SurveyBundle& bundle);

// The initial vehicle poses with the absolute sensors folded in: nav.csv's
// dead-reckoned x_gv, with roll and pitch replaced by the IMU's roll_meas and
// pitch_meas (when measured_roll_pitch), and z corrected toward the pressure
// depth by the mean of (depth - z) over the keyframes within +-depth_window/2
// seconds (a complementary filter: dead reckoning is smooth but drifts, the
// depth sensor is noisy but absolute; depth_window <= 0 keeps z). Dead
// reckoning drifts by decimetres in depth over a survey, which tilts a
// lawnmower's DVL returns by a degree or more.
std::vector<Pose> InitialPosesWithZpr(const SurveyBundle& bundle, double depth_window, bool measured_roll_pitch);

// Just the points, for registration.
std::vector<Eigen::Vector3d> PointsOf(const std::vector<DvlPoint>& returns);

}  // namespace hull
