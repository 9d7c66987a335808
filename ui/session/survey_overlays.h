// What the 3-D scene draws of a survey bundle, as plain geometry in the
// bundle's frame g (z down) or, for the true objects, in the model frame M:
// computed once in the loading job (off the GUI thread), Qt- and VTK-free.
//
// Sensor poses follow the contract's chain (../shared/survey-format.md):
//   x_g,cT = x_gv (+) x_vs(theta) (+) x_s_cT      (top camera)
//   x_gd   = x_gv (+) x_vs(theta) (+) x_s_d       (DVL head)
// and a DVL hit is the head's origin plus range times the unit beam.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "survey/survey.h"
#include "ui/session/model_placement.h"

namespace hull::ui {

Pose CameraPose(const SurveyManifest& manifest, const Vector6d& x_gv, double servo);
Pose DvlPose(const SurveyManifest& manifest, const Vector6d& x_gv, double servo);

enum class PoseSource { kInitial, kTruth };

struct DvlHit {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // in g
  int nav_index = 0;                                // row of nav.csv
  int beam = 0;                                     // 0..3
};

// The returns of every beam placed from the initial (nav.csv) or the true
// poses (keyframes without a true pose are skipped).
std::vector<DvlHit> ComputeDvlHits(const SurveyBundle& bundle, PoseSource source);

enum class LandmarkSource { kNone, kTruth, kInitial };
const char* LandmarkSourceName(LandmarkSource source);

struct LandmarkMarker {
  std::int64_t id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // in g
  bool has_truth = false;
  double deviation = 0;  // true signed distance to the CAD surface (m)
  std::string object;    // id of the foreign object it lies on, "" on the hull
  int observations = 0;  // rows of features.csv
  bool foreign() const { return !object.empty(); }
};

// A true object's outline in M: closed loops (the footprint on the hull and
// its top) and the segments joining them.
struct ObjectOutline {
  std::string id;
  ObjectKind kind = ObjectKind::kPatch;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  std::vector<std::vector<Eigen::Vector3d>> loops;
  std::vector<std::array<Eigen::Vector3d, 2>> segments;
};
ObjectOutline OutlineOf(const TrueObject& object);

struct Frustum {
  int nav_index = 0;
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, 4> corners;  // image corners at `depth`, clockwise from top-left
};
// The top camera's frustum at every `stride`th keyframe (initial poses),
// reaching as deep as the DVL returns of that keyframe (the standoff, along
// the head's axis; 1 m without a return), so that its base outlines the
// image on the hull.
std::vector<Frustum> ComputeFrusta(const SurveyBundle& bundle, int stride);

struct SurveyOverlays {
  std::vector<Eigen::Vector3d> trajectory;  // nav order
  std::vector<Eigen::Vector3d> true_trajectory;
  std::vector<int> true_nav_index;  // nav row of each true pose (-1 when absent)
  std::vector<DvlHit> dvl_hits;
  LandmarkSource landmark_source = LandmarkSource::kNone;
  std::vector<LandmarkMarker> landmarks;
  std::vector<ObjectOutline> objects;  // in M
  Eigen::AlignedBox3d bounds;          // of everything above that is in g
  double min_deviation = 0, max_deviation = 0;
};

SurveyOverlays ComputeSurveyOverlays(const SurveyBundle& bundle);

// Placements the bundle offers (identity always; the guess and the truth when
// present), best first: truth, guess, identity. Without a bundle: identity.
std::vector<ModelPlacement> AvailablePlacements(const SurveyBundle* bundle);
// The bundle's placements (identity for kAdjusted: the Session knows that one).
Pose PlacementPose(const SurveyBundle* bundle, ModelPlacement p);

}  // namespace hull::ui
