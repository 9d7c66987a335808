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
  if (!(std::isfinite(remove_min_height) && remove_min_height >= 0)) {
    throw OptionError("changes.remove_min_height", "must be >= 0 m");
  }
  if (add < 0) throw OptionError("changes.add", "must be >= 0");
  if (!(std::isfinite(new_offset) && new_offset > 0.3)) throw OptionError("changes.new_offset", "must exceed 0.3 m");
  if (!(std::isfinite(new_height) && new_height > 0 && new_height < 1)) {
    throw OptionError("changes.new_height", "must be in (0, 1) m");
  }
}

std::vector<std::size_t> ApplyFoulingChanges(std::vector<TrueObject>& objects, const MeshIndex& cad,
                                             const Eigen::Vector3d& forward, const FoulingChanges& c) {
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
  // The last objects placed that are high enough are removed; every other
  // keeps its place and its shape's seed index.
  std::vector<char> removed(objects.size(), 0);
  int left = c.remove;
  for (std::size_t i = objects.size(); i-- > 0 && left > 0;) {
    if (objects[i].Height() >= c.remove_min_height) {
      removed[i] = 1;
      --left;
    }
  }
  std::vector<TrueObject> kept;
  std::vector<std::size_t> seed_index;
  std::vector<std::size_t> kept_patches;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (removed[i]) continue;
    if (objects[i].kind == ObjectKind::kPatch) kept_patches.push_back(kept.size());
    seed_index.push_back(i);
    kept.push_back(objects[i]);
  }
  for (int k = 0; k < c.grow && k < static_cast<int>(kept_patches.size()); ++k) {
    kept[kept_patches[static_cast<std::size_t>(k)]].height += c.growth;
  }
  for (std::size_t k = 0; k < added.size(); ++k) seed_index.push_back(objects.size() + k);
  kept.insert(kept.end(), added.begin(), added.end());
  objects = std::move(kept);
  return seed_index;
}

}  // namespace hull
