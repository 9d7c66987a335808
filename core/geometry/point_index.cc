#include "geometry/point_index.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>

namespace hull {

struct PointIndex::Impl {
  // nanoflann's dataset adaptor over our own copy of the points.
  struct Cloud {
    std::vector<Eigen::Vector3d> pts;
    std::size_t kdtree_get_point_count() const { return pts.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t dim) const { return pts[i][static_cast<int>(dim)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox& /*bb*/) const {
      return false;
    }
  };
  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::uint32_t>;

  explicit Impl(std::vector<Eigen::Vector3d> points)
      : cloud{std::move(points)}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
  }

  Cloud cloud;
  Tree tree;
};

PointIndex::PointIndex(std::vector<Eigen::Vector3d> points) : impl_(std::make_unique<Impl>(std::move(points))) {}

PointIndex::~PointIndex() = default;

std::size_t PointIndex::size() const { return impl_->cloud.pts.size(); }

const Eigen::Vector3d& PointIndex::point(std::size_t i) const { return impl_->cloud.pts[i]; }

std::vector<std::pair<int, double>> PointIndex::Nearest(const Eigen::Vector3d& q, int k) const {
  std::vector<std::pair<int, double>> out;
  if (k <= 0 || impl_->cloud.pts.empty()) return out;
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(k), impl_->cloud.pts.size());
  std::vector<std::uint32_t> idx(n);
  std::vector<double> d2(n);
  const std::size_t found = impl_->tree.knnSearch(q.data(), n, idx.data(), d2.data());
  out.reserve(found);
  for (std::size_t i = 0; i < found; ++i) out.emplace_back(static_cast<int>(idx[i]), d2[i]);
  return out;
}

std::pair<int, double> PointIndex::NearestOne(const Eigen::Vector3d& q) const {
  if (impl_->cloud.pts.empty()) return {-1, std::numeric_limits<double>::infinity()};
  std::uint32_t index = 0;
  double d2 = 0;
  nanoflann::KNNResultSet<double, std::uint32_t> result(1);
  result.init(&index, &d2);
  impl_->tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
  return {static_cast<int>(index), d2};
}

std::vector<std::pair<int, double>> PointIndex::Within(const Eigen::Vector3d& q, double radius, bool sorted) const {
  std::vector<std::pair<int, double>> out;
  if (!(radius >= 0) || impl_->cloud.pts.empty()) return out;
  std::vector<std::pair<std::uint32_t, double>> matches;
  // nanoflann's L2_Simple metric works on squared distances.
  impl_->tree.radiusSearch(q.data(), radius * radius, matches, nanoflann::SearchParams(32, 0.0f, sorted));
  out.reserve(matches.size());
  for (const auto& [i, d2] : matches) {
    if (d2 <= radius * radius) out.emplace_back(static_cast<int>(i), d2);
  }
  return out;
}

}  // namespace hull
