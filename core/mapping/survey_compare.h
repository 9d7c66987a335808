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
  // The widest disc (m) read about a peak, and the footprint's radius cap
  // for objects read without their vertex list.
  double match_radius = 0.30;
  // Two local maxima of one map's objects closer than this (m, along the
  // CAD) are one peak; the registration matches objects' tops within it.
  double peak_spacing = 0.10;
  // Both maps' heights at a peak are their highest within this distance (m)
  // of it, widened by twice the registration's residual (at most
  // match_radius; match_radius itself where the registration neither found
  // a motion nor the maps in place).
  double peak_reach = 0.05;
  // An object grew (shrank) where a peak's height rose (fell) by at least
  // this much (m); a peak of one map where the other stands lower than this
  // and has no object is new (removed).
  double change_threshold = 0.03;
  // A vertex's change is significant when |change| > k sqrt(sigma_A^2 + sigma_B^2).
  double significance_k = 1.96;
  // Register B's map to A's first by the objects' peaks
  // (mapping/survey_registration.h): the two adjustments may place the CAD
  // model differently along the surface, by up to max_misplacement (m) at a
  // peak.
  bool register_surveys = true;
  double max_misplacement = 5.0;
  // Throws OptionError naming the field.
  void Check() const;
};

enum class ObjectChangeKind { kNew, kRemoved, kGrown, kShrunk, kUnchanged };
const char* ObjectChangeKindName(ObjectChangeKind k);  // "new", "removed", ...

// The change at the peaks of one object (or pair of objects, one of each
// map). Every peak of either map's objects (its highest vertex and other
// local maxima, mapping/survey_compare.cc) is a site, a peak of A and one of
// B within reach of each other one site; at each site both maps' heights
// are their highest vertices within reach. A site is new where A has no
// object there and stands below change_threshold while B stands at least
// that high, removed the other way round, else grown / shrunk / unchanged
// by the difference. Per pair of
// objects (id_a, id_b) and kind the site that changed most is kept, and
// the unchanged ones are dropped where the pair has a changed one: two maps
// split and join touching lumps differently, and a joined object's max
// height stands on one lump only.
struct ObjectChange {
  ObjectChangeKind kind = ObjectChangeKind::kUnchanged;
  std::string id_a, id_b;  // "" where that map has no object there
  // Where: B's peak (or B's highest vertex there when the site is a peak of
  // A only but B has an object there), else A's peak; in that map's M.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double height_a = 0, height_b = 0;  // heights at the site (m); 0 where new / removed
  double change = 0;                  // height_b - height_a
  // One map has no object at the site but stands at least change_threshold
  // high there: the object was there too, below that map's object
  // detection (each map's detection has its thresholds), and is classed by
  // the heights.
  bool from_height_field = false;
};

struct SurveyComparison {
  // B's model with vertex scalars "change" (m, B's deviation minus A's at
  // the same CAD point), "change_sigma" (m; NaN without sigmas) and
  // "change_significant" (1 or 0).
  TriangleMesh model;
  // Sites with an object of B first (in B's order; new ones last), then
  // those with an object of A only (removed, or found in B's height field).
  std::vector<ObjectChange> objects;
  std::size_t significant_vertices = 0;
  // m: the radius about a peak in which both maps' heights were read
  // (peak_reach widened by the registration's residual; match_radius
  // without a registration).
  double reach = 0;
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

}  // namespace hull
