// The photomosaic's visibility stage (photomosaic_internal.h): which views
// see which faces. The rule is per (view, face) pair; what makes it fast is
// which pairs are looked at: only the faces whose centroid lies in the
// grid cells a view's range ball touches, and of those only the ones whose
// centroid the view's pinhole frustum holds get their corners projected
// and their rays cast. Both culls are conservative, so the result is the
// rule applied to every pair (tests/unit/mosaic: SeenFacesEqualsTheRuleOnEveryPair).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "mosaic/photomosaic_internal.h"

namespace hull {
namespace mosaic_internal {
namespace {

constexpr int kBits = 21;  // per axis in a cell key
constexpr std::int64_t kMaxCell = (std::int64_t{1} << kBits) - 1;

std::uint64_t Key(std::int64_t x, std::int64_t y, std::int64_t z) {
  return static_cast<std::uint64_t>(x) << (2 * kBits) | static_cast<std::uint64_t>(y) << kBits |
         static_cast<std::uint64_t>(z);
}

// The cell index of a coordinate, clamped to the key's range.
std::int64_t CellOf(double x, double origin, double cell) {
  const double i = std::floor((x - origin) / cell);
  if (!(i > 0)) return 0;  // and NaN
  return static_cast<std::int64_t>(std::min(i, static_cast<double>(kMaxCell)));
}

}  // namespace

std::array<Eigen::Vector3d, kSamples> FaceSamples(const TriangleMesh& m, int f) {
  const Face& F = m.faces[static_cast<std::size_t>(f)];
  const Eigen::Vector3d a = m.vertices[static_cast<std::size_t>(F[0])], b = m.vertices[static_cast<std::size_t>(F[1])],
                        c = m.vertices[static_cast<std::size_t>(F[2])];
  const Eigen::Vector3d g = (a + b + c) / 3.0;
  return {g, g + 0.85 * (a - g), g + 0.85 * (b - g), g + 0.85 * (c - g)};
}

CentroidGrid::CentroidGrid(const std::vector<Eigen::Vector3d>& centroids, double cell) : cell_(cell) {
  if (!(cell > 0)) throw std::invalid_argument("CentroidGrid: the cell size must be positive");
  // A centroid that is not finite is never within range of anything: left out.
  origin_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -origin_;
  for (const Eigen::Vector3d& g : centroids) {
    if (g.allFinite()) origin_ = origin_.cwiseMin(g), hi = hi.cwiseMax(g);
  }
  if (!origin_.allFinite()) origin_.setZero(), hi.setZero();
  // Grow the cell until the extent fits the key (a model kilometres across).
  while ((hi - origin_).maxCoeff() / cell_ >= static_cast<double>(kMaxCell)) cell_ *= 2;
  std::vector<std::pair<std::uint64_t, int>> keyed;
  keyed.reserve(centroids.size());
  for (std::size_t f = 0; f < centroids.size(); ++f) {
    const Eigen::Vector3d& g = centroids[f];
    if (!g.allFinite()) continue;
    keyed.emplace_back(
        Key(CellOf(g.x(), origin_.x(), cell_), CellOf(g.y(), origin_.y(), cell_), CellOf(g.z(), origin_.z(), cell_)),
        static_cast<int>(f));
  }
  std::sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    order_[i] = keyed[i].second;
    if (i == 0 || keyed[i].first != keyed[i - 1].first) cells_[keyed[i].first] = {i, i};
    cells_[keyed[i].first].second = i + 1;
  }
}

void CentroidGrid::Near(const Eigen::Vector3d& c, double r, std::vector<int>* faces) const {
  // A little slack (a millionth of a cell) against rounding at the cell borders.
  const double slack = 1e-6 * cell_;
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = CellOf(c[a] - r - slack, origin_[a], cell_);
    hi[a] = CellOf(c[a] + r + slack, origin_[a], cell_);
  }
  const double r2 = (r + slack) * (r + slack);
  for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        // Distance from c to the cell's box (grown by the slack).
        const Eigen::Vector3d box_lo =
            origin_ + cell_ * Eigen::Vector3d(static_cast<double>(x), static_cast<double>(y), static_cast<double>(z));
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
          const double below = box_lo[a] - slack - c[a], above = c[a] - (box_lo[a] + cell_ + slack);
          const double out = std::max({below, above, 0.0});
          d2 += out * out;
        }
        if (d2 > r2) continue;
        const auto it = cells_.find(Key(x, y, z));
        if (it == cells_.end()) continue;
        faces->insert(faces->end(), order_.begin() + static_cast<std::ptrdiff_t>(it->second.first),
                      order_.begin() + static_cast<std::ptrdiff_t>(it->second.second));
      }
    }
  }
}

Visibility SeenFaces(const TriangleMesh& model, const MeshIndex& index, const std::vector<MosaicCamera>& cameras,
                     int width, int height, const MosaicOptions& options, Progress& progress) {
  const std::size_t nf = model.num_faces();
  std::vector<Eigen::Vector3d> centroid(nf);
  for (std::size_t f = 0; f < nf; ++f) centroid[f] = model.FaceCentroid(static_cast<int>(f));
  // Cells a quarter of the range: a view's ball touches at most 9^3 of them,
  // and their corners add little volume to it.
  const CentroidGrid grid(centroid, options.max_range / 4);
  const double cos_max = std::cos(options.max_incidence_deg * M_PI / 180.0);
  const double margin = options.image_margin;
  const int nviews = static_cast<int>(cameras.size());
  Visibility out;
  out.seen.resize(cameras.size());
  std::atomic<std::size_t> near{0}, projected{0}, rays{0};
  tbb::parallel_for(0, nviews, [&](int vi) {
    if (progress.Cancelled()) return;
    const MosaicCamera& cam = cameras[static_cast<std::size_t>(vi)];
    const Eigen::Vector3d o = cam.centre();
    const Eigen::Matrix3d Rt = cam.x_Mc().rotation().transpose();
    const PinholeIntrinsics& k = cam.intrinsics();
    std::vector<int> faces;
    grid.Near(o, options.max_range, &faces);
    std::vector<std::pair<int, float>> pass;
    std::vector<Eigen::Vector3d> points;
    std::size_t tested = 0;
    for (const int fi : faces) {
      const auto f = static_cast<std::size_t>(fi);
      const Eigen::Vector3d& g = centroid[f];
      const Eigen::Vector3d to = o - g;
      const double d = to.norm();
      if (!(d > 1e-6 && d <= options.max_range)) continue;
      const double cosi = model.face_normals[f].dot(to) / d;
      if (cosi < cos_max) continue;
      // Frustum cull on the centroid: a pinhole maps the triangle (in front
      // of the camera) onto the triangle of its corners' pixels, so when
      // the corners are inside the margin, so is the centroid. One pixel of
      // slack for x_Mc against the adjustment's chain of rotations.
      const Eigen::Vector3d pc = Rt * (g - o);
      if (!(pc.z() > 0)) continue;
      const double u = k.fx * pc.x() / pc.z() + k.cx, v = k.fy * pc.y() / pc.z() + k.cy;
      constexpr double kSlack = 1.0;
      if (!(u >= margin - kSlack && v >= margin - kSlack && u <= width - 1 - margin + kSlack &&
            v <= height - 1 - margin + kSlack)) {
        continue;
      }
      ++tested;
      bool in_image = true;
      for (int i = 0; i < 3 && in_image; ++i) {
        Eigen::Vector2d uv;
        in_image = cam.Project(model.vertices[static_cast<std::size_t>(model.faces[f][i])], &uv) && uv.x() >= margin &&
                   uv.y() >= margin && uv.x() <= width - 1 - margin && uv.y() <= height - 1 - margin;
      }
      if (!in_image) continue;
      pass.emplace_back(fi, static_cast<float>(cosi / (d * d)));
    }
    std::sort(pass.begin(), pass.end());  // the list (and the rays) in face order
    for (const auto& fs : pass) {
      for (const Eigen::Vector3d& p : FaceSamples(model, fs.first)) points.push_back(p);
    }
    std::unique_ptr<bool[]> blocked(new bool[points.size() + 1]);
    index.OccludedToward(points.data(), static_cast<int>(points.size()), o, 1e-3, blocked.get());
    auto& seen = out.seen[static_cast<std::size_t>(vi)];
    for (std::size_t i = 0; i < pass.size(); ++i) {
      bool free = true;
      for (int s = 0; s < kSamples; ++s) free = free && !blocked[i * kSamples + static_cast<std::size_t>(s)];
      if (free) seen.push_back(pass[i]);
    }
    near += faces.size();
    projected += tested;
    rays += points.size();
  });
  out.near = near;
  out.projected = projected;
  out.rays = rays;
  return out;
}

}  // namespace mosaic_internal
}  // namespace hull
