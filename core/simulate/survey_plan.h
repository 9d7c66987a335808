// Survey planning for the simulator: HAUV lawnmower tracks at a fixed
// standoff under the hull bottom and along its sides, with the servoed sensor
// tray pointing at the hull.
#pragma once

#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "simulate/random.h"
#include "survey/survey.h"

namespace hull {

// Hull-relative axes in the model frame M.
struct HullAxes {
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX();  // toward the bow
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  double waterline = 0;  // coordinate along `up` of the waterline
  Eigen::Vector3d port() const { return up.cross(forward); }
};

// x_gM that turns the hull upright in g (up -> -z, i.e. depth), puts the
// waterline at depth 0 and a chosen model point `centre` at g's origin
// horizontally, the ship heading `heading` (rad from north).
Pose ShipPlacement(const HullAxes& axes, const Eigen::Vector3d& centre, double heading);

enum class SurveyCoverage {
  kBottomPatch,  // a stretch of the bottom (e.g. around the keel)
  kFullHull,     // the whole bottom and both sides below the waterline
};

struct LawnmowerOptions {
  SurveyCoverage coverage = SurveyCoverage::kBottomPatch;
  // Along the hull (metres along `forward` from the model's aftmost point).
  double start = 80.0, end = 92.0;
  // Bottom tracks: lateral offsets within +-half_width of the centreline (m, along port).
  double half_width = 2.4;
  double standoff = 1.5;               // camera to hull (m)
  double standoff_jitter = 0.1;        // slow variation (m)
  double track_spacing = 0.8;          // m between bottom tracks
  double side_track_spacing = 1.5;     // m between side tracks (depth)
  double side_standoff = 2.0;          // m on the sides
  double keyframe_spacing = 0.3;       // m along a track
  double speed = 0.25;                 // m/s
  double wobble_deg = 1.0;             // slow roll/pitch oscillation amplitude
  double max_bottom_slope_deg = 35.0;  // bottom stations: normal within this of straight down
};

struct PlannedKeyframe {
  double t = 0;
  Pose x_gv;         // true vehicle pose
  double servo = 0;  // true servo angle
  int track = 0;     // track index (-1: transit between tracks)
};

// The camera's pose in the vehicle frame for a servo angle:
// x_vs(theta) (+) x_s_cT.
Pose VehicleToCamera(const SurveyManifest& rig, const Pose& x_s_cT, double servo);

// Plans the keyframes. Stations where the hull cannot be found are skipped.
std::vector<PlannedKeyframe> PlanLawnmower(const MeshIndex& cad, const HullAxes& axes, const Pose& x_gM,
                                           const SurveyManifest& rig, const Pose& x_s_cT,
                                           const LawnmowerOptions& options, Rng& rng);

}  // namespace hull
