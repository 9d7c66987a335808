// Loop-closure candidates of the visual front end: keyframe pairs far apart
// in nav order -- adjacent tracks of a lawnmower survey, revisits -- whose
// image footprints on the hull overlap under the navigation prior. These
// are where the bundle adjustment gets its cross-track constraints (Ozog et
// al., section 3: the pose graph's cross-track links).
//
// A keyframe's footprint is a set of surface points in its top camera frame:
// its triangulated stereo points, or (mono, or no stereo matches) a grid of
// pixel rays cut with the plane through its DVL returns. Two keyframes
// overlap by the smaller of the two shares of one's footprint points that
// project into the other's image under the prior relative pose. Candidates
// are verified by MatchKeyframes with LoopMatchingOptions: the search window
// and the prior tolerances grow with the navigation drift between the two
// keyframes.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "geometry/pose.h"
#include "survey/survey.h"
#include "vision/temporal_matching.h"
#include "vision/vision_options.h"

namespace hull {

struct KeyframeFootprint {
  enum class Source { kNone, kStereo, kDvl };
  Source source = Source::kNone;
  std::vector<Eigen::Vector3d> points;                 // on the hull, in the top camera frame
  Eigen::Vector3d centre_g = Eigen::Vector3d::Zero();  // mean of the points in g (prior pose)
  double radius = 0;                                   // largest distance of a point from centre_g (m)
  double depth = 0;                                    // median camera-frame z of the points (m)
  double min_depth = 0, max_depth = 0;                 // their smallest and largest z (m)
  bool empty() const { return points.empty(); }
};

// The footprint from a keyframe's triangulated stereo points (every k-th so
// that at most max_points remain); empty with fewer than 10 points.
KeyframeFootprint StereoFootprint(const KeyframeView& view, int max_points);

// The plane through a keyframe's DVL returns in its top camera frame
// (least squares with three or four returns, else fronto-parallel at their
// mean depth): normal . p = offset, the normal pointing away from the
// camera. False without returns or when the plane is not in front.
struct CameraPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0;                                 // m, > 0
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the mean of the returns
  // How far p (camera frame) stands in front of the plane, towards the camera (m).
  double HeightOf(const Eigen::Vector3d& p) const { return offset - normal.dot(p); }
};
bool DvlPlane(const SurveyManifest& manifest, const DvlRecord& dvl, CameraPlane& plane);

// The footprint from the DVL returns (the DVL rides on the camera's servo,
// so only the mounts place them in the camera frame): the plane through the
// returns (least squares with three or four, else the fronto-parallel plane
// at their mean depth) cut by a grid of about max_points pixel rays (up to
// three times the returns' depth); empty without returns or when the plane
// is not in front of the camera.
KeyframeFootprint DvlFootprint(const SurveyManifest& manifest, const DvlRecord& dvl, int max_points);

// Fills centre_g and radius from the points and the (prior) camera pose.
void PlaceFootprint(KeyframeFootprint& footprint, const Pose& x_g_c);

// Share of a's footprint points that, moved into b's camera with the prior
// relative pose, lie in front of it and inside its image.
double FootprintShareInView(const KeyframeFootprint& a, const Pose& x_g_ca, const Pose& x_g_cb, const CameraRig& rig);

// What the candidate search needs of each keyframe (indices into the
// front end's keyframes).
struct LoopKeyframe {
  Pose x_g_cT;                  // prior top camera pose
  double t = 0;                 // nav time (s)
  double path = 0;              // nav path length from the first keyframe (m)
  int order = 0;                // position among the keyframes with a top image
  KeyframeFootprint footprint;  // placed (PlaceFootprint)
};

struct LoopCandidate {
  std::size_t a = 0, b = 0;  // keyframe indices, a < b
  double overlap = 0;        // predicted footprint overlap
  double seconds = 0;        // nav time between them
  double path = 0;           // nav path between them (m)
};

// Loop candidates among keyframes: more than `neighbours` apart in `order`
// (closer pairs are matched as neighbours), nav path between them at least
// min_path_ratio x max(distance between the cameras, mean footprint
// radius), optical axes within max_view_angle_deg, predicted overlap at
// least min_overlap; each keyframe's `candidates` best (overlap, then order)
// are kept, a pair when either keyframe keeps it. Sorted by (a, b);
// deterministic. *considered (when given) gets the number of pairs whose
// overlap was predicted.
std::vector<LoopCandidate> FindLoopCandidates(const std::vector<LoopKeyframe>& keyframes, const CameraRig& rig,
                                              int neighbours, const LoopOptions& options,
                                              std::size_t* considered = nullptr);

// The temporal options for a loop pair: the drift between the keyframes,
//   sigma_rot = odometry_rotation_rate * seconds,
//   sigma_pos = odometry_translation_rate * seconds + sigma_rot * path / 2
// (a heading error growing along the path displaces the end by about half
// of it times the path), grows the window by drift_sigmas * f * (sigma_pos
// / depth + sigma_rot) px (at most max_window), the rotation tolerance by
// drift_sigmas * sigma_rot, the translation tolerance by drift_sigmas *
// sigma_pos and the mono direction tolerance by atan(drift_sigmas *
// sigma_pos / distance); min_inliers is the loop's. `a` is the first
// keyframe's footprint: its median depth scales the window, and the mono
// search along the epipolar line is narrowed to its depths / 1.5 .. x 1.5
// (within the base's mono_min_depth .. mono_max_depth): the grown window
// around the whole 0.3-6 m segment would cost a search of most of the image.
TemporalOptions LoopMatchingOptions(const TemporalOptions& base, const LoopOptions& loop, const NoiseModel& noise,
                                    double focal_px, const KeyframeFootprint& a, double seconds, double path,
                                    double distance);

}  // namespace hull
