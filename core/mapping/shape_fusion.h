// Algorithm 2 of Ozog et al.: the shapes of every keyframe fused into the
// mesh. For every pose and every shape, the ray from the top camera's centre
// through each model vertex within fusion_radius is cast against the shape;
// where it meets it at p, the vertex is updated by the moving average of
// eq. 15, v_{n+1} = (p + n v_n) / (n + 1) (so a fused vertex is the mean of
// its hits, and an unhit one keeps its prior position). Rays go through the
// prior vertex positions, as in the paper. The hits are then combined by a
// FusionRule: eq. 15's mean, or (the default) the peak-keeping rule below.
//
// Two departures from the paper's text, both documented in docs/mapping.md:
// the ray is the whole ray through the vertex (up to fusion_radius), not the
// segment from the camera to it, so that a shape slightly behind the CAD
// surface (noise, or a dent) pulls the vertex as one in front of it does;
// and a vertex whose normal faces away from the camera (the far side of the
// hull, which the camera cannot see) is not fused.
//
// By default (FusionRule::along_normal) the line cast is not the camera's
// ray but the line through the prior vertex along its
// outward normal (the segment within NormalReach of the vertex, shape_raycast.h): a camera ray puts a narrow peak over
// a different vertex for each view (parallax), the normal puts it over the same vertex for every view, so the views'
// hits at the peak support each other.
//
// FuseShapes finds, per shape, only the vertices whose rays (or normal
// segments) can reach it (a cone around the shape, or a ball around it
// grown by the reach, over a tree of the vertices, then a 2-D grid over the
// shape's footprint on the normalised image plane) and runs keyframes in
// parallel, applying the updates in keyframe and shape order: its result is
// bit-identical to FuseShapesBruteForce, the paper's loops literally.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "geometry/point_index.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "mapping/point_cone_tree.h"
#include "mapping/shape_detection.h"

namespace hull {

// How a vertex's hits become its fused position. The paper's eq. 15 (the
// mean of every hit) flattens a narrow peak: the peak reaches a vertex only
// through the rays of the views that see it over that vertex, the other
// views' rays land lower and pull it down. keep_peaks instead takes the
// height the hits support: heights are measured along the prior vertex's
// outward normal, h_k is the support-th highest hit, and the vertex moves to
// the mean of the hits whose heights lie in [h_k - band, h_k]. So a peak
// that at least `support` hits reach is kept (to within band), while one
// wrong hit above the rest (a wrong match) cannot raise the vertex, and a
// vertex with fewer than `support` hits stays where it was.
//
// along_normal chooses the line each vertex is fused along (the camera's ray
// through it, as in the paper, or its normal); it is part of the rule because
// it decides which hits a vertex gathers.
struct FusionRule {
  bool keep_peaks = true;    // false: eq. 15, the mean of every hit
  int support = 2;           // hits that must reach a height (keep_peaks)
  double band = 0.005;       // m, hits averaged below h_k (keep_peaks)
  bool along_normal = true;  // false: the camera's ray through the vertex (the paper's)
};

// Eq. 15: the running mean of a vertex's hits.
struct MovingAverage {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();  // v_n (v_0: the prior vertex)
  int n = 0;
  void Add(const Eigen::Vector3d& p) {
    value = (p + n * value) / (n + 1);
    ++n;
  }
};

struct FusionResult {
  std::vector<Eigen::Vector3d> vertices;  // fused positions (in M), the prior one where not moved
  std::vector<int> count;                 // hits per vertex (n of eq. 15)
  std::vector<int> support;               // hits at or above the fused height less the band (0: not moved)
  std::size_t hits = 0;                   // evaluations of line 11
};

// prior: the (refined) mesh in M, with vertex normals; prior_tree: a
// PointConeTree over prior.vertices. x_M_cT: the top camera in M per
// keyframe (indexed like MappingInput::keyframes); shapes: Algorithm 1's
// results (KeyframeShapes::keyframe indexes x_M_cT). Throws hull::Cancelled.
FusionResult FuseShapes(const TriangleMesh& prior, const PointConeTree& prior_tree, const std::vector<Pose>& x_M_cT,
                        const std::vector<KeyframeShapes>& shapes, double fusion_radius, const FusionRule& rule,
                        Progress& progress);

// The reference: for every keyframe, the vertices within fusion_radius (a
// k-d tree, the paper's nearby_vertices()), every shape, every vertex, every
// triangle. Slow; for tests.
FusionResult FuseShapesBruteForce(const TriangleMesh& prior, const std::vector<Pose>& x_M_cT,
                                  const std::vector<KeyframeShapes>& shapes, double fusion_radius,
                                  const FusionRule& rule = FusionRule{});

// Peak features (with the fusion along normals and keep_peaks). A narrow
// lump's top features may be DBSCAN noise in every keyframe that saw them:
// a pass that saw the top but none of the flanks above the hysteresis level
// has nothing to cluster them with, while another pass's shapes cover the
// flanks (the demo's 0.18 m strip-8 from the images: its 0.169 and 0.131 m
// features, 4 cm apart, are seen by keyframes 155 and 156 only, each
// other's only neighbour there; keyframes 179-181 mesh the lump up to
// 0.122 m). The support rule then never sees them. A peak feature is a
// landmark that
//
// - stands above tau (a seed) and min_height in at least `support`
//   keyframes (views) but is a shape vertex in fewer (else the fusion
//   reaches it anyway), and
// - stands above every feature the fusion reaches (a shape vertex in
//   `support` keyframes) whose foot on the CAD lies within eps of its own:
//   a top the shapes missed, not a flank feature below what they reach, and
// - is confirmed by a second such landmark whose foot lies within eps of
//   its own (two features, each seen from two views: one wrong match, or one
//   landmark alone, raises nothing).
//
// Highest first. RaisePeakFeatures decides which of them reach the model.
// landmarks_M / deviation: every landmark's position in M and its signed
// distance to the CAD, indexed like ShapePoint::landmark.
struct PeakFeature {
  int landmark = 0;                                // index into the landmarks
  double deviation = 0;                            // its height above the CAD (m)
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();  // its closest point on the CAD (in M)
  int views = 0;                                   // keyframes where it stands above tau
  int shape_views = 0;                             // keyframes whose shapes hold it
  int confirmed_by = -1;                           // the nearest confirming peak feature's landmark
};
std::vector<PeakFeature> FindPeakFeatures(const std::vector<KeyframeShapes>& shapes,
                                          const std::vector<Eigen::Vector3d>& landmarks_M,
                                          const std::vector<double>& deviation, const MeshIndex& cad, double tau,
                                          double min_height, double eps, int support);

// Before the fusion along normals: a narrow peak reaches the model only
// where a vertex lies under its top feature (between vertices each view's
// triangulation interpolates it to a different, lower height). So the prior
// vertex nearest the foot on the CAD of each feature that is a shape vertex
// in at least `support` keyframes (the support rule's views) and stands more
// than min_height above the CAD moves onto that foot: highest feature
// first, each vertex once, only when the foot lies within max_move of it
// and none of its faces turns by more than 45 degrees. The vertex stays on
// the CAD (where it is not fused, its deviation stays 0), and every view's
// normal line through it meets the feature itself. prior_index indexes
// prior.vertices as given; normals are recomputed. Deterministic. Returns
// the number of vertices moved.
//
// apex_feet (in M, on the CAD): fitted apexes of lumps (FitPeaks,
// peak_fit.h), served before every feature, in their order, the same way;
// *apex_vertex gets the vertex moved onto each (-1: none could be).
//
// peaks (FindPeakFeatures): served with the features, highest first, the
// same way; *peak_vertex gets the vertex moved onto each one's foot (-1:
// none could be).
int SnapVerticesToFeatures(TriangleMesh& prior, const PointIndex& prior_index, const MeshIndex& cad,
                           const std::vector<KeyframeShapes>& shapes, const Pose& x_Mg, int support, double min_height,
                           double max_move, const std::vector<Eigen::Vector3d>& apex_feet = {},
                           std::vector<int>* apex_vertex = nullptr, const std::vector<PeakFeature>& peaks = {},
                           std::vector<int>* peak_vertex = nullptr);

// After the fusion: the vertex moved under each peak feature (peak_vertex,
// from SnapVerticesToFeatures) rises along its prior normal to the feature's
// height when the fusion left it lower and it joins an object the shapes
// made: one of its neighbours (over the mesh's edges) was fused above
// min_height. So a peak feature completes an object two views' shapes found
// and can never make one. prior: the mesh the fusion ran on. Returns how
// many vertices rose; *raised (optional) gets, per peak, whether its vertex
// rose.
int RaisePeakFeatures(const TriangleMesh& prior, const std::vector<PeakFeature>& peaks,
                      const std::vector<int>& peak_vertex, double min_height, FusionResult& fused,
                      std::vector<char>* raised = nullptr);

// A vertex's hits (in the order the loops meet them) combined by `rule`;
// prior/normal: the prior vertex and its outward normal. Sets *support.
Eigen::Vector3d CombineHits(const std::vector<Eigen::Vector3d>& hits, const Eigen::Vector3d& prior,
                            const Eigen::Vector3d& normal, const FusionRule& rule, int* support);

}  // namespace hull
