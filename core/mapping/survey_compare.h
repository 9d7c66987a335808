// Change between two surveys of one hull: both mapped against the same CAD
// mesh, the per-vertex change in height on survey B's model (with its
// significance where both results carry a per-vertex sigma), and the
// detected objects matched by position and classed new, removed, grown,
// shrunk or unchanged.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "mapping/detected_objects.h"
#include "mapping/survey_registration.h"

namespace hull {

struct SurveyCompareOptions {
  // Objects of A and B whose centroids lie within this distance (m) are the
  // same object (matched closest pair first).
  double match_radius = 0.30;
  // A matched object grew (shrank) when its max height rose (fell) by at
  // least this much (m).
  double change_threshold = 0.03;
  // A vertex's change is significant when |change| > k sqrt(sigma_A^2 + sigma_B^2).
  double significance_k = 1.96;
  // Register B's map to A's first (mapping/survey_registration.h): the two
  // adjustments may place the CAD model differently along the surface, by up
  // to max_misplacement (m) at an object.
  bool register_surveys = true;
  double max_misplacement = 5.0;
  // Throws OptionError naming the field.
  void Check() const;
};

enum class ObjectChangeKind { kNew, kRemoved, kGrown, kShrunk, kUnchanged };
const char* ObjectChangeKindName(ObjectChangeKind k);  // "new", "removed", ...

struct ObjectChange {
  ObjectChangeKind kind = ObjectChangeKind::kUnchanged;
  std::string id_a, id_b;                              // "" where absent
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // B's (A's when removed), in M
  double height_a = 0, height_b = 0;                   // max heights (m); 0 where absent
  double change = 0;                                   // height_b - height_a
  // An object detected in one survey only is looked up in the other's
  // height field (its highest vertex over the object's footprint, a disc of
  // its area, at most match_radius): where
  // the other survey saw a bump of at least change_threshold there, the
  // object was there too, below that map's object detection, and is
  // classed by the heights (height_a or height_b is then that field's
  // height, id_a or id_b empty). Also set for a matched pair whose
  // footprints differ by more than 1.5 times in area (one map joined
  // touching lumps the other split): both heights are then the maps' over
  // the smaller footprint, so a neighbour's peak in the joined object does
  // not stand in for the object's own.
  bool from_height_field = false;
};

struct SurveyComparison {
  // B's model with vertex scalars "change" (m, B's deviation minus A's at
  // the same CAD point), "change_sigma" (m; NaN without sigmas) and
  // "change_significant" (1 or 0).
  TriangleMesh model;
  // Matched first (from the bow aft as B lists them; then B's objects found in
  // A's height field), then new, then A's unmatched (removed, or found in B's
  // height field).
  std::vector<ObjectChange> objects;
  std::size_t significant_vertices = 0;
  // How B's map was placed on A's before the comparison (identity when not
  // registered). Vertices and centroids keep B's own coordinates.
  SurveyRegistration registration;
};

// cad: the CAD mesh in M both results were mapped against; model_a/b: the
// fused models with the scalar "deviation" (and optionally "sigma").
// Throws std::invalid_argument when a model lacks "deviation".
SurveyComparison CompareSurveys(const TriangleMesh& cad, const TriangleMesh& model_a,
                                const std::vector<DetectedObject>& objects_a, const TriangleMesh& model_b,
                                const std::vector<DetectedObject>& objects_b, const SurveyCompareOptions& options);
// The same, reporting progress over B's vertices; throws hull::Cancelled when
// progress asks.
SurveyComparison CompareSurveys(const TriangleMesh& cad, const TriangleMesh& model_a,
                                const std::vector<DetectedObject>& objects_a, const TriangleMesh& model_b,
                                const std::vector<DetectedObject>& objects_b, const SurveyCompareOptions& options,
                                Progress& progress);

// A mapping results folder as the comparison needs it: model.ply with its
// scalars and objects.json (id, centroid, max_height). Throws InputError.
struct MappingResultsOnDisk {
  TriangleMesh model;
  std::vector<DetectedObject> objects;
  std::string mesh_path;  // the CAD mapping.json names ("" if none)
};
MappingResultsOnDisk ReadMappingResultsForCompare(const std::string& dir);

// The mapping results folder of `results`: itself when it holds model.ply,
// else its mapping/ (a pipeline's results folder); nullopt when neither.
std::optional<std::string> FindMappingResults(const std::string& results);

// The whole comparison of two results folders (mapping or pipeline results):
// both read, the CAD mesh loaded (`mesh`, or the one A's mapping.json names,
// scaled by mesh_scale) and compared. Throws InputError naming the file at
// fault (a folder without mapping results, no mesh named), hull::Cancelled
// when progress asks.
struct SurveyComparisonRun {
  std::string folder_a, folder_b;  // the mapping results folders read
  std::string mesh;                // the CAD mesh used
  std::vector<DetectedObject> objects_a, objects_b;
  SurveyComparison comparison;
};
SurveyComparisonRun RunSurveyComparison(const std::string& results_a, const std::string& results_b,
                                        const std::string& mesh, double mesh_scale, const SurveyCompareOptions& options,
                                        Progress& progress);

// Writes DIR (replaced as a whole): model.ply (B's model with the change
// scalars), objects.csv and compare.json.
void WriteSurveyComparison(const SurveyComparison& c, const std::string& dir);

}  // namespace hull
