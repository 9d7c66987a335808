// Algorithm 1 of Ozog et al.: the shapes of foreign structure seen at one
// keyframe. The landmarks the keyframe observed whose |deviation| exceeds
// tau become points (x, y, |d|), x and y in the top-camera frame; DBSCAN
// clusters them (with hysteresis, MappingOptions::shape_grow_height, the
// points above a lower level join too, and only clusters holding seeds
// above tau are kept); each cluster is meshed as a 2-D alpha shape over camera
// (x, y) and lifted to 2.5-D by each vertex's camera z. The results keep
// everything the GUI's keyframe view draws (the paper's Fig. 11): every
// observed feature with its pixel, deviation and cluster, and each shape in
// the camera frame, in g and in image coordinates.
#pragma once

#include <cstdint>
#include <vector>

#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "mapping/dbscan.h"
#include "mapping/mapping_input.h"
#include "mapping/mapping_options.h"

namespace hull {

// One landmark observed at the keyframe.
struct ShapePoint {
  // |deviation| <= tau and in no cluster (with hysteresis, a point between
  // shape_grow_height and tau that no kept cluster grew through): not clustered
  static constexpr int kBelowTau = -2;
  static constexpr int kNoise = -1;  // clustered, but DBSCAN found it isolated

  int landmark = 0;                                 // index into MappingInput::landmarks
  Eigen::Vector3d p_c = Eigen::Vector3d::Zero();    // in the top-camera frame (x right, y down, z forward)
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // projected into the top image
  double deviation = 0;                             // signed distance to the CAD surface (m)
  int cluster = kBelowTau;                          // DBSCAN cluster, kNoise or kBelowTau
};

// A 2.5-D triangle mesh over one cluster.
struct DetectedShape {
  int cluster = 0;
  std::vector<int> points;  // per shape vertex: index into KeyframeShapes::points
  // Triangles over the shape's vertices (0 .. points.size() - 1), wound so
  // that their normals face the camera.
  std::vector<Face> triangles;
  std::vector<Eigen::Vector3d> vertices_c;  // camera frame: the features' camera (x, y, z)
  std::vector<Eigen::Vector3d> vertices_g;  // the same vertices in g
  std::vector<Eigen::Vector2d> pixels;      // the same vertices in the top image
  std::vector<double> deviation;            // the vertices' signed deviation (m)
  double area = 0;                          // of the lifted mesh (m^2)
};

struct KeyframeShapes {
  int keyframe = 0;                   // index into MappingInput::keyframes
  std::int64_t id = 0;                // the keyframe's id
  std::vector<ShapePoint> points;     // every observed landmark in front of the camera, by landmark index
  std::vector<DetectedShape> shapes;  // clusters that gave at least one triangle, by cluster
};

// Peak points (with MappingOptions::fusion_keep_peaks, after DBSCAN on the
// points (x, y, |d|)): a noise point that another point confirms (at least
// one more within eps, so one wrong match alone stays noise) and that
// stands above a cluster (a clustered point within eps of it on the image
// plane (x, y) has a lower |d|) joins the cluster of the nearest such
// point. Labels of clustered points do not change.
void AdmitPeakPoints(const std::vector<Eigen::Vector3d>& points, double eps, DbscanResult& db);

// Hysteresis (MappingOptions::shape_grow_height): clusters holding fewer
// than min_seeds seeds (seed[i]: point i stands above tau) are dropped (their
// points become noise); the rest are renumbered 0 .. in their order.
void KeepSeededClusters(const std::vector<char>& seed, int min_seeds, DbscanResult& db);

// The landmarks (per index into input.landmarks: 1) that some keyframe's
// DBSCAN cluster holding a seed holds (with hysteresis; all 0 without):
// the features Algorithm 1 connects to a feature above tau in at least one
// view (MappingOptions::shape_seed_across_views).
std::vector<char> SeededLandmarks(const MappingInput& input, const MappingOptions& options);

// Algorithm 1 for one keyframe (index into input.keyframes). options.Check()
// is the caller's business. With hysteresis, a cluster is kept when it holds
// a seed or, with `seeded` (SeededLandmarks), a landmark seeded in any view.
KeyframeShapes DetectShapes(const MappingInput& input, int keyframe, const MappingOptions& options,
                            const std::vector<char>* seeded = nullptr);

// Algorithm 1 for every keyframe, in parallel (the result does not depend on
// the number of threads). Throws hull::Cancelled when progress asks.
std::vector<KeyframeShapes> DetectAllShapes(const MappingInput& input, const MappingOptions& options,
                                            Progress& progress);

}  // namespace hull
