// The 3-D photomosaic (issue 10; Ozog et al., Fig. 23): the remeshed model
// textured from the survey's camera images with the adjusted poses.
//
// 1. Views: every keyframe camera (top, and bottom for stereo) placed by the
//    adjusted vehicle pose, servo angle, camera extrinsic and model pose,
//    projecting through the bundle adjustment's own reprojection code
//    (adjust/factors/reprojection_factor.h), so a texel lands where the
//    adjustment says the point is seen.
//    Faces within max_range of a camera with edges longer than max_edge
//    are split first (conforming edge bisection), so that one image can hold
//    a whole face; the mosaic's model is the split one.
// 2. Candidates per face: all three corners inside the image, the face
//    turned toward the camera within max_incidence_deg, within max_range, and
//    not occluded: Embree rays from four points of the face to the camera
//    centre (MeshIndex::OccludedToward) must all be free.
// 3. Choice: score s = cos(incidence) / distance^2 (the face's area in the
//    image, in pixels, up to a constant: near and frontal views resolve it
//    best), then a Potts labelling by iterated conditional modes,
//    E = sum_f -ln(s_f(v) / s_f,max) + seam_weight * #(neighbours on another view),
//    which keeps neighbouring faces on one view when scores are close.
// 4. Gain normalisation: the rig's photometric model (the underwater
//    renderer's: strobe beam, inverse-square fall-off, Lambert, Beer-Lambert
//    attenuation, backscatter veil, vignetting; UnderwaterCamera::ResponseAt)
//    turns every pixel into an albedo estimate; then a gain per image,
//    estimated by robust least squares on the log albedo of faces that
//    several images see, absorbs what the model misses (another water, a
//    weaker strobe). The survey bundle carries no photometric calibration, so
//    the model's parameters are options (defaults: the simulator's HAUV rig).
// 5. Seams: per-vertex view weights (area share of the incident faces'
//    views), smoothed over feather_rings one-rings, interpolated per texel:
//    across a view boundary texels blend the views visible there.
// 6. Atlas: one rectangle per textured face (the triangle laid out flat at
//    texel_size, one texel of border), shelf-packed into one image.
// 7. Truth: with the bundle's truth/scene.ply and truth/albedo.json, the
//    per-face error of the estimated albedo against the true albedo.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

#include "base/progress.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "mosaic/mosaic_options.h"
#include "simulate/image_renderer.h"
#include "simulate/true_scene.h"
#include "survey/survey.h"

namespace hull {

// What the mosaic is made from; the adjusted estimates in the survey's frames.
struct MosaicInput {
  SurveyManifest manifest;              // camera rig and servo mount
  std::vector<std::int64_t> keyframes;  // ids
  std::vector<Vector6d> poses;          // adjusted x_gv per keyframe
  std::vector<double> servo;            // adjusted servo angle per keyframe
  Vector6d x_gM = Vector6d::Zero();     // adjusted model pose
  Vector6d x_s_cT = Vector6d::Zero();   // adjusted camera extrinsic
  TriangleMesh model;                   // the remeshed model in M
  // Whether keyframe index k has an image of the top (bottom) camera, and
  // reading it (8/16-bit, 1 or 3 channels; throws InputError naming the file).
  // read_image is called from several threads at once (a chunk of views is
  // read in parallel).
  std::function<bool(std::size_t k, bool bottom)> has_image;
  std::function<cv::Mat(std::size_t k, bool bottom)> read_image;
  // The file an image comes from, for messages (empty: "keyframe K's top
  // image").
  std::function<std::string(std::size_t k, bool bottom)> image_name;
};

struct MosaicView {
  std::int64_t keyframe = 0;
  bool bottom = false;
  Pose x_Mc;           // the camera in M
  double gain = 1;     // the per-image gain applied
  int faces = 0;       // faces textured mainly from it
  int candidates = 0;  // faces it sees (visible, unoccluded)
};

struct MosaicFace {
  int view = -1;       // index into views; -1: no view sees it (untextured)
  double score = 0;    // cos(incidence) / distance^2 of that view (1/m^2)
  int candidates = 0;  // views that see it
  float albedo = 0;    // mean estimated value over the face
  // Against the true albedo (NaN without truth): mean |estimate - truth|
  // over truth_samples texels, and |mean estimate - mean truth| over them.
  float error = std::numeric_limits<float>::quiet_NaN();
  float mean_error = std::numeric_limits<float>::quiet_NaN();
  float truth = std::numeric_limits<float>::quiet_NaN();  // mean true albedo over the samples
};

struct MosaicSummary {
  std::size_t faces = 0, faces_textured = 0, views_used = 0, seam_edges = 0, interior_edges = 0;
  double texel_size = 0;     // m, as used (may exceed the option to fit the atlas)
  double atlas_fill = 0;     // share of atlas texels inside a face rectangle
  double textured_area = 0;  // m^2
  double gain_min = 1, gain_median = 1, gain_max = 1;
  std::size_t faces_scored = 0;
  double error_median = 0, error_p95 = 0, mean_error_median = 0, mean_error_p95 = 0;
  // The visibility stage's work: (view, face) pairs the centroid grid
  // returned, pairs whose corners were projected, rays cast.
  std::size_t visibility_pairs_near = 0, visibility_pairs_projected = 0, visibility_rays = 0;
  struct Seconds {
    double visibility = 0, labelling = 0, gains = 0, texturing = 0, scoring = 0, total = 0;
  } seconds;
};

struct MosaicResult {
  MosaicOptions options;
  MosaicNormalisation normalisation = MosaicNormalisation::kModelAndGains;
  TriangleMesh model;  // the input model with the faces near the cameras split to max_edge
  std::vector<MosaicView> views;
  std::vector<MosaicFace> faces;
  // Per face corner: position in atlas pixels (texel (i, j) covers
  // [i, i+1) x [j, j+1), its centre at (i + 0.5, j + 0.5)).
  std::vector<std::array<Eigen::Vector2f, 3>> corners;
  cv::Mat atlas;                     // CV_8UC1 or CV_8UC3 (BGR): estimated albedo x 255 (raw values with kNone)
  std::vector<float> vertex_values;  // per vertex and channel, same scale as the atlas / 255
  int channels = 1;
  std::vector<std::pair<std::string, std::string>> inputs;  // recorded in mosaic.json
  MosaicSummary summary;

  // Texture coordinate of a corner as written to the OBJ (v up).
  Eigen::Vector2f Uv(int face, int corner) const;
};

// Builds the mosaic; `truth` (optional) scores it. Progress and
// cancellation (throws Cancelled) between chunks of 64 views.
MosaicResult BuildMosaic(const MosaicInput& input, const MosaicOptions& options, Progress& progress,
                         const TrueScene* truth = nullptr);

}  // namespace hull
