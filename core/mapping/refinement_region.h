// Where the fused model needs more resolution than the CAD mesh has: the
// footprint on the CAD surface of the shape triangles that depart from it,
// as a set of cells of a sparse 3-D grid (so that regions compare, merge and
// grow cheaply: the refined mesh is cached by its region).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "mapping/mapping_options.h"
#include "mapping/shape_detection.h"

namespace hull {

class RefinementRegion {
 public:
  static constexpr double kDefaultCell = 0.05;  // m
  explicit RefinementRegion(double cell = kDefaultCell) : cell_(cell) {}

  double cell() const { return cell_; }
  std::size_t num_cells() const { return cells_.size(); }
  bool empty() const { return cells_.empty(); }

  // Marks the cell holding p.
  void Add(const Eigen::Vector3d& p);
  // Adds every cell whose centre lies within `margin` of a marked cell's centre.
  void Dilate(double margin);
  bool Contains(const Eigen::Vector3d& p) const;
  // True when every cell of other is in this region (same cell size).
  bool Includes(const RefinementRegion& other) const;
  void Merge(const RefinementRegion& other);
  // Centres of the cells, in a fixed (sorted) order.
  std::vector<Eigen::Vector3d> CellCentres() const;

 private:
  std::int64_t Key(const Eigen::Vector3d& p) const;
  Eigen::Vector3d Centre(std::int64_t key) const;
  double cell_;
  std::unordered_set<std::int64_t> cells_;
};

// The region where the shapes depart from the CAD surface (in M). A
// clustered feature of a keyframe departs when its |deviation| exceeds
// options.refine_threshold and at least two other features of its cluster
// that also exceed it lie within alpha of it (camera x, y): so one noisy
// feature alone refines nothing. Each departing feature marks where the
// camera's ray through it meets the CAD (where the fusion moves vertices)
// and its closest point on the CAD; the marks are grown by
// options.refine_margin + options.alpha (an alpha-shape triangle lies
// within alpha of its corners). The rule is monotone: raising tau (fewer
// features clustered) never grows the region, so the refined mesh cached
// for a lower tau serves every higher one. x_M_cT: the top camera in M per
// keyframe (indexed like MappingInput::keyframes).
RefinementRegion DepartureRegion(const std::vector<KeyframeShapes>& shapes, const std::vector<Pose>& x_M_cT,
                                 const MeshIndex& cad, const MappingOptions& options, Progress& progress);

}  // namespace hull
