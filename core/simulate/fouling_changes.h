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
  // Objects removed (cleaned off): the last `remove` placed of those at
  // least remove_min_height high. A lower one (the demo's last, a 0.06 m
  // patch) is at the limit of what a map detects, so its removal could not
  // be shown. The others keep their shapes (ApplyFoulingChanges returns the
  // index each object's shape is seeded by).
  int remove = 0;
  double remove_min_height = 0.08;
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
// patches are offset across it). Returns, per resulting object, its index
// in the list before the changes (new ones: that list's size + k), by which
// the simulator seeds its shape, so that a kept object keeps its shape.
std::vector<std::size_t> ApplyFoulingChanges(std::vector<TrueObject>& objects, const MeshIndex& cad,
                                             const Eigen::Vector3d& forward, const FoulingChanges& changes);

}  // namespace hull
