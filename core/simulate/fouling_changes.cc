#include "simulate/fouling_changes.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "simulate/foreign_objects.h"

namespace hull {

void FoulingChanges::Check() const {
  if (grow < 0) throw OptionError("changes.grow", "must be >= 0");
  if (!(std::isfinite(growth) && growth > 0 && growth < 1)) throw OptionError("changes.growth", "must be in (0, 1) m");
  if (remove < 0) throw OptionError("changes.remove", "must be >= 0");
  if (add < 0) throw OptionError("changes.add", "must be >= 0");
  if (!(std::isfinite(new_offset) && new_offset > 0.3)) throw OptionError("changes.new_offset", "must exceed 0.3 m");
  if (!(std::isfinite(new_height) && new_height > 0 && new_height < 1)) {
    throw OptionError("changes.new_height", "must be in (0, 1) m");
  }
}

void ApplyFoulingChanges(std::vector<TrueObject>& objects, const MeshIndex& cad, const Eigen::Vector3d& forward,
                         const FoulingChanges& c) {
  c.Check();
  std::vector<std::size_t> patches;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].kind == ObjectKind::kPatch) patches.push_back(i);
  }
  // New patches beside existing ones (placed before anything is removed or grown).
  std::vector<TrueObject> added;
  for (int k = 0; k < c.add && !patches.empty(); ++k) {
    const TrueObject& near = objects[patches[static_cast<std::size_t>(k) % patches.size()]];
    const double side = (k / static_cast<int>(patches.size())) % 2 == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d across = forward.cross(near.normal).normalized();  // along the surface, across the hull
    const Eigen::Vector3d at = near.center + side * c.new_offset * across;
    added.push_back(PlaceObject(cad, "new-" + std::to_string(k + 1), ObjectKind::kPatch, at, 0.15, c.new_height));
  }
  // The last objects placed are removed, so every other keeps its index
  // (the simulator seeds each object's shape by it).
  const std::size_t keep = objects.size() - std::min(objects.size(), static_cast<std::size_t>(c.remove));
  objects.resize(keep);
  patches.erase(std::remove_if(patches.begin(), patches.end(), [&](std::size_t i) { return i >= keep; }),
                patches.end());
  for (int k = 0; k < c.grow && k < static_cast<int>(patches.size()); ++k) {
    objects[patches[static_cast<std::size_t>(k)]].height += c.growth;
  }
  objects.insert(objects.end(), added.begin(), added.end());
}

}  // namespace hull
