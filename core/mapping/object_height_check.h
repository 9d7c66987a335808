// Per true object: the fused model's height over the object's footprint
// against the truth of a simulated survey (issue 12, part 1). It does not
// go through the detected objects: a detected object may hold two adjacent
// true lumps or half of one, and its centroid lies wherever the adjustment
// put the model (the gauge), so "the nearest detected object" is no
// yardstick for a strip of touching lumps. Instead each true object's
// footprint is looked up in the fused model's height field:
//
// - the model is moved into the true model frame by the rigid fit of the
//   adjusted landmarks onto the true ones (GaugeFitToTruth);
// - the object's region is where it is the true surface: its footprint
//   less where an overlapping neighbour stands higher (the true surface is
//   the union of the objects' meshes, as the simulator built them); a model
//   vertex lies in it when the line along the object's normal through it
//   meets that surface first on the object's top;
// - the model's max and 95th percentile (nearest rank) of the `deviation`
//   of those vertices are compared with the true surface's highest point
//   in the region (the object's peak unless a neighbour buries it), found
//   on a 5 mm grid;
// - the features' robust maximum: the second-highest adjusted deviation of
//   the landmarks in its region (one feature alone cannot make it).
#pragma once

#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "mapping/detected_objects.h"
#include "mapping/mapping_input.h"
#include "mapping/shape_detection.h"
#include "survey/survey.h"

namespace hull {

struct ObjectHeightCheck {
  std::string id;  // the true object's
  ObjectKind kind = ObjectKind::kPatch;
  double height = 0;              // its own true height (its peak)
  double true_max = 0;            // the true surface's highest point in its region (NaN: buried)
  double model_max = 0;           // the fused model's highest vertex in its region (deviation, m)
  double model_p95 = 0;           // 95th percentile of those vertices' deviation (nearest rank)
  int model_max_vertex = -1;      // the model vertex of model_max (-1: none in its region)
  int model_vertices = 0;         // model vertices in its region
  int fused_vertices = 0;         // of them, moved by the fusion (fusions > 0)
  double feature_max = 0;         // the highest adjusted landmark deviation in its region
  double feature_robust_max = 0;  // the second highest (NaN with fewer than 2 landmarks)
  int features = 0;               // landmarks in its region
  // The highest of them that is a vertex of a shape (Algorithm 1) in at
  // least two keyframes: what the fusion can reach with support 2 (NaN: none).
  double shaped_max = 0;
  std::vector<int> landmarks;            // those landmarks (indices into MappingInput::landmarks), highest first
  std::vector<std::string> detected_as;  // detected objects with a vertex in its region
  double error() const { return model_max - true_max; }
};

// The rigid motion taking the adjusted model frame to the true one: the
// least-squares fit (Umeyama, no scale) of every adjusted landmark in the
// adjusted M onto the same landmark in the true M. Throws InputError when
// the bundle has no truth.
Pose GaugeFitToTruth(const SurveyBundle& bundle, const AdjustmentResult& adjustment);

// model: the fused model in the (adjusted) M with the vertex scalars
// "deviation" and "fusions"; objects: its detected objects; landmarks: the
// mapping input's (positions in g, x_gM the mapping input's model pose);
// model_to_true: GaugeFitToTruth (identity for a mapping from the truth);
// truth/object_meshes: the simulated objects and their true meshes in the
// true M (SimulatedSurvey::object_meshes); cad: the CAD mesh; shapes: the
// mapping's Algorithm 1 results (for shaped_max; optional).
std::vector<ObjectHeightCheck> CheckObjectHeights(const TriangleMesh& model, const std::vector<DetectedObject>& objects,
                                                  const MappingInput& input, const Pose& model_to_true,
                                                  const std::vector<TrueObject>& truth,
                                                  const std::vector<TriangleMesh>& object_meshes, const MeshIndex& cad,
                                                  const std::vector<KeyframeShapes>* shapes = nullptr);

// Found and false objects (issue 10's "every object >= 6 cm found, none
// false"): a true object of at least min_height is found when a detected
// object has a vertex in its region (so a detected object holding several
// touching lumps finds each of them); a detected object with a vertex in no
// true object's region is false.
struct FoundObjects {
  int required = 0, found = 0;
  std::vector<std::string> missed;         // true objects of at least min_height that no detected object covers
  std::vector<std::string> false_objects;  // detected objects on no true object
  std::string ToString() const;            // one line
};
FoundObjects CountFoundObjects(const std::vector<ObjectHeightCheck>& checks, const std::vector<DetectedObject>& objects,
                               double min_height);

// A table, one row per object, and a summary line counting the objects of
// at least `min_height` whose model max lies within `tolerance` of true_max.
std::string ObjectHeightTable(const std::vector<ObjectHeightCheck>& checks, double min_height, double tolerance);

}  // namespace hull
