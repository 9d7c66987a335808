// Object identity across runs: the id an inspector writes in a note
// ("obj-7, 174 mm, port side") stays with the object when the survey is
// mapped again with other parameters (tau, alpha, sigma, the object
// thresholds). A fresh run numbers its objects from the bow aft
// (DetectObjects); ObjectIdentity then gives each one the id of the object
// it is among those seen before, matched by position and footprint, and
// new ids (after the highest ever given) to the rest. Objects that a run
// does not find keep their id in the record, so that going back to earlier
// parameters brings them back under the same name.
//
// Matching: an object is a known one when the centroid of either lies on
// the other's footprint (within min_radius of one of its vertices, along
// the hull: a long object that splits into two lumps keeps them), or their
// centroids lie
// within the larger of their footprint radii (sqrt(area / pi), at least
// min_radius). Pairs are taken nearest centroids first, one to one: an
// object that splits in two (a higher h_min) keeps its id on the nearer
// part, the other part is new; two that merge take the id of the nearer one.
#pragma once

#include <string>
#include <vector>

#include "mapping/detected_objects.h"

namespace hull {

// N of an id "obj-N" (for sorting by id); 0 for any other string.
int ObjectIdNumber(const std::string& id);

class ObjectIdentity {
 public:
  struct Known {
    std::string id;
    Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();  // as last seen
    double radius = 0;                                     // m, the footprint's as a disc
    std::vector<Eigen::Vector3d> footprint;                // its vertices (in M) as last seen
  };

  // min_radius: m, the smallest footprint radius matched with (an object of
  // a few vertices has an area of a few square centimetres).
  explicit ObjectIdentity(double min_radius = 0.05) : min_radius_(min_radius) {}

  // Renames `objects` (one run's, in its order, which is kept) to the ids of
  // the known objects they are and to new ids, and records them. model: the
  // run's fused model, whose vertices DetectedObject::vertices index.
  void Assign(std::vector<DetectedObject>* objects, const TriangleMesh& model);

  // Forgets every object (another survey or mesh).
  void Clear();

  const std::vector<Known>& known() const { return known_; }

 private:
  double Radius(const DetectedObject& o) const;
  bool Same(const DetectedObject& o, const std::vector<Eigen::Vector3d>& footprint, const Known& k) const;

  double min_radius_;
  std::vector<Known> known_;
  int last_number_ = 0;  // the highest N of an "obj-N" given
};

}  // namespace hull
