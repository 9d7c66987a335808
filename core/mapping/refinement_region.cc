#include "mapping/refinement_region.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace hull {
namespace {

constexpr std::int64_t kBias = std::int64_t(1) << 20;  // cell indices in [-2^20, 2^20)
constexpr std::int64_t kMask = (std::int64_t(1) << 21) - 1;

std::int64_t Pack(std::int64_t i, std::int64_t j, std::int64_t k) {
  return ((i + kBias) & kMask) << 42 | ((j + kBias) & kMask) << 21 | ((k + kBias) & kMask);
}

void Unpack(std::int64_t key, std::int64_t& i, std::int64_t& j, std::int64_t& k) {
  i = ((key >> 42) & kMask) - kBias;
  j = ((key >> 21) & kMask) - kBias;
  k = (key & kMask) - kBias;
}

// The grid is shifted by an odd fraction of a cell on each axis, so that
// the planes CAD models are full of (z = 0 for a flat bottom, x = 87 for a
// station) do not lie on cell boundaries, where rounding at the level of
// 1e-15 would pick the cell on one side or the other.
constexpr double kShift[3] = {0.3183098861837907, 0.2718281828459045, 0.1414213562373095};

}  // namespace

std::int64_t RefinementRegion::Key(const Eigen::Vector3d& p) const {
  std::int64_t ijk[3];
  for (int a = 0; a < 3; ++a) ijk[a] = static_cast<std::int64_t>(std::floor(p[a] / cell_ + kShift[a]));
  return Pack(ijk[0], ijk[1], ijk[2]);
}

Eigen::Vector3d RefinementRegion::Centre(std::int64_t key) const {
  std::int64_t ijk[3];
  Unpack(key, ijk[0], ijk[1], ijk[2]);
  Eigen::Vector3d c;
  for (int a = 0; a < 3; ++a) c[a] = (static_cast<double>(ijk[a]) + 0.5 - kShift[a]) * cell_;
  return c;
}

void RefinementRegion::Add(const Eigen::Vector3d& p) { cells_.insert(Key(p)); }

bool RefinementRegion::Contains(const Eigen::Vector3d& p) const { return cells_.count(Key(p)) > 0; }

void RefinementRegion::Dilate(double margin) {
  const int r = static_cast<int>(std::floor(margin / cell_ + 1e-9));
  if (r <= 0) return;
  std::vector<std::int64_t> offsets;
  for (int i = -r; i <= r; ++i) {
    for (int j = -r; j <= r; ++j) {
      for (int k = -r; k <= r; ++k) {
        if (i * i + j * j + k * k <= r * r && (i || j || k)) offsets.push_back(Pack(i, j, k) - Pack(0, 0, 0));
      }
    }
  }
  const std::vector<std::int64_t> seeds(cells_.begin(), cells_.end());
  for (const std::int64_t s : seeds) {
    for (const std::int64_t o : offsets) cells_.insert(s + o);
  }
}

bool RefinementRegion::Includes(const RefinementRegion& other) const {
  if (other.cell_ != cell_) return false;
  for (const std::int64_t c : other.cells_) {
    if (!cells_.count(c)) return false;
  }
  return true;
}

void RefinementRegion::Merge(const RefinementRegion& other) {
  for (const std::int64_t c : other.cells_) cells_.insert(c);
}

std::vector<Eigen::Vector3d> RefinementRegion::CellCentres() const {
  std::vector<std::int64_t> keys(cells_.begin(), cells_.end());
  std::sort(keys.begin(), keys.end());
  std::vector<Eigen::Vector3d> out;
  out.reserve(keys.size());
  for (const std::int64_t k : keys) out.push_back(Centre(k));
  return out;
}

RefinementRegion DepartureRegion(const std::vector<KeyframeShapes>& shapes, const std::vector<Pose>& x_M_cT,
                                 const MeshIndex& cad, const MappingOptions& o, Progress& progress) {
  RefinementRegion region;
  std::vector<std::vector<Eigen::Vector3d>> hits(shapes.size());
  std::vector<std::vector<int>> departing(shapes.size());
  const double alpha2 = o.alpha * o.alpha;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, shapes.size(), 8), [&](const tbb::blocked_range<std::size_t>& r) {
        if (progress.Cancelled()) return;
        std::vector<std::vector<int>> clusters;
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
          const KeyframeShapes& ks = shapes[k];
          const Pose& cam = x_M_cT[static_cast<std::size_t>(ks.keyframe)];
          // Departing members of each cluster.
          clusters.clear();
          for (std::size_t i = 0; i < ks.points.size(); ++i) {
            const ShapePoint& p = ks.points[i];
            if (p.cluster < 0 || !(std::abs(p.deviation) > o.refine_threshold)) continue;
            if (static_cast<std::size_t>(p.cluster) >= clusters.size())
              clusters.resize(static_cast<std::size_t>(p.cluster) + 1);
            clusters[static_cast<std::size_t>(p.cluster)].push_back(static_cast<int>(i));
          }
          for (const auto& members : clusters) {
            for (const int i : members) {
              const ShapePoint& p = ks.points[static_cast<std::size_t>(i)];
              int near = 0;
              for (const int j : members) {
                near +=
                    j != i &&
                    (ks.points[static_cast<std::size_t>(j)].p_c.head<2>() - p.p_c.head<2>()).squaredNorm() <= alpha2;
              }
              if (near < 2) continue;
              departing[k].push_back(p.landmark);
              const RayHit h = cad.Raycast(cam.translation(), cam.Rotate(p.p_c), o.fusion_radius);
              if (h.hit) hits[k].push_back(h.point);
            }
          }
        }
      });
  progress.ThrowIfCancelled();
  std::vector<int> landmarks;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    for (const auto& p : hits[k]) region.Add(p);
    landmarks.insert(landmarks.end(), departing[k].begin(), departing[k].end());
  }
  // Closest points on the CAD, once per landmark (its position in M from any
  // keyframe that saw it).
  std::sort(landmarks.begin(), landmarks.end());
  landmarks.erase(std::unique(landmarks.begin(), landmarks.end()), landmarks.end());
  std::vector<Eigen::Vector3d> where(landmarks.size());
  std::vector<char> found(landmarks.size(), 0);
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const Pose& cam = x_M_cT[static_cast<std::size_t>(shapes[k].keyframe)];
    for (const ShapePoint& p : shapes[k].points) {
      const auto it = std::lower_bound(landmarks.begin(), landmarks.end(), p.landmark);
      if (it == landmarks.end() || *it != p.landmark) continue;
      const std::size_t i = static_cast<std::size_t>(it - landmarks.begin());
      if (found[i]) continue;
      found[i] = 1;
      where[i] = cam * p.p_c;
    }
  }
  for (const auto& p : where) region.Add(cad.Closest(p).point);
  region.Dilate(o.refine_margin + o.alpha);
  return region;
}

}  // namespace hull
