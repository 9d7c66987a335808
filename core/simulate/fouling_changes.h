// The second survey of a pair: the same hull months later, its fouling
// changed. Applied to the objects the simulator placed (same seed: same
// hull, same objects, then changed), so that `hullinspect-cli compare` has
// a known answer: which objects are new, which grew by how much, which
// were removed.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/mesh_index.h"
#include "survey/survey.h"

namespace hull {

struct FoulingChanges {
  // Patches that grow (the first `grow` fouling patches, in placement
  // order, among those not removed) and by how much (m, added to their height).
  int grow = 0;
  double growth = 0.05;
  // Objects removed (the last `remove` placed: cleaned off; the others keep
  // their places in the list, so their shapes do not change).
  int remove = 0;
  // New patches, each placed `new_offset` m across the hull from an
  // existing patch (cycling through them), with height new_height (m).
  int add = 0;
  double new_offset = 0.8;
  double new_height = 0.10;

  bool any() const { return grow > 0 || remove > 0 || add > 0; }
  // Throws OptionError naming the field.
  void Check() const;
};

// Changes `objects` in place: grown patches keep their id, new ones are
// "new-1", "new-2", ...; `forward` is the hull's forward axis in M (new
// patches are offset across it).
void ApplyFoulingChanges(std::vector<TrueObject>& objects, const MeshIndex& cad, const Eigen::Vector3d& forward,
                         const FoulingChanges& changes);

}  // namespace hull
