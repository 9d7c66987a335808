// Truth for feature tracks the visual front end made from a simulated
// survey's images. The simulator's truth/landmarks.csv describes ITS feature
// tracks (features.csv as written, same landmark ids); the front end's
// tracks are new, with new ids. Their truth comes from the geometry instead:
// each observation's pixel is cast as a ray from the TRUE camera (truth/poses.csv,
// truth/servo_to_top.json, truth/model_pose.json) onto the true surface
// (truth/scene.ply). A track's true point is the medoid of its observations'
// hits; an observation whose hit lies farther than `tolerance` from it is a
// wrong match (it shows another point of the hull). The landmark's truth is
// then what the simulator would have written: its point in g, its signed
// distance to the CAD surface (0 on the nominal hull) and the object it lies on.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "survey/survey.h"

namespace hull {

class TrueScene;

struct ImageTrackTruth {
  std::vector<TrueLandmark> landmarks;  // one per track whose observations hit the true surface
  double tolerance = 0.02;              // m
  std::size_t tracks = 0;
  std::size_t observations = 0;         // top-camera observations
  std::size_t observations_missed = 0;  // whose ray hit no surface
  std::size_t wrong_observations = 0;   // hit farther than tolerance from their track's true point
  std::size_t tracks_with_wrong = 0;    // tracks holding at least one wrong observation
  // Each track triangulated from all its rays (top and bottom) with the TRUE
  // cameras: how many land within tolerance of the true surface.
  std::size_t triangulated = 0;
  std::size_t triangulated_within = 0;

  double WrongObservationFraction() const;
  double TriangulatedWithinFraction() const;
  std::string ToString() const;  // a readable paragraph
};

// The true pose in M of a bundle's keyframe (index into truth.poses) top or
// bottom camera: truth poses, servo and extrinsic, the true model pose.
Pose TrueCameraPoseFromTruth(const SurveyBundle& bundle, std::size_t pose_index, bool bottom_camera);

// Truth for the bundle's feature tracks (bundle.features) from the true
// scene; cad is the prior mesh in M (the deviation's reference). Needs
// bundle.truth with its poses.
ImageTrackTruth DeriveImageTrackTruth(const SurveyBundle& bundle, const TrueScene& scene, const TriangleMesh& cad,
                                      double tolerance = 0.02);

// For a bundle whose tracks came from the front end (bundle.features_from_images)
// and that has truth: reads truth/scene.ply and the model hint, derives the
// tracks' truth and puts it into bundle.truth->landmarks. Returns nothing
// (and leaves the truth landmarks empty) when there is no truth/scene.ply.
// Throws InputError naming the file when a truth file is unreadable.
std::optional<ImageTrackTruth> AttachImageTrackTruth(SurveyBundle& bundle);

}  // namespace hull
