// The only translation unit that includes PCL (its registration templates
// compile slowly and must not leak into our headers).
#include "registration/gicp.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "base/csv.h"
#include "base/error.h"
#include "geometry/query_bounds.h"

namespace hull {
namespace {

// PCL's GICP, with the iteration count it keeps protected made readable.
// Scalar = double: the transform is composed and returned in double (the
// point clouds and their k-d tree stay in float, as PointXYZ is).
class PclGicp : public pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ, double> {
 public:
  int iterations() const { return nr_iterations_; }
};

pcl::PointCloud<pcl::PointXYZ>::Ptr ToCloud(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& shift) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(pts.size());
  for (const Eigen::Vector3d& p : pts) {
    const Eigen::Vector3d q = p - shift;
    cloud->push_back(pcl::PointXYZ(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())));
  }
  return cloud;
}

Eigen::Vector3d Centroid(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : pts) c += p;
  return pts.empty() ? c : Eigen::Vector3d(c / static_cast<double>(pts.size()));
}

Pose Translation(const Eigen::Vector3d& t) { return Pose(Eigen::Quaterniond::Identity(), t); }

}  // namespace

void GicpOptions::Check() const {
  if (!(voxel_size >= 0 && std::isfinite(voxel_size)))
    throw OptionError("voxel_size", "must be >= 0 (0: no reduction)");
  if (!(max_correspondence_distance > 0 && std::isfinite(max_correspondence_distance))) {
    throw OptionError("max_correspondence_distance", "must be a positive distance (m)");
  }
  if (!(coarse_voxel_size >= 0 && std::isfinite(coarse_voxel_size))) {
    throw OptionError("coarse_voxel_size", "must be >= 0 (0: no coarse stage)");
  }
  if (coarse_voxel_size > 0 && !(coarse_voxel_size > voxel_size)) {
    throw OptionError("coarse_voxel_size", "must exceed voxel_size (or be 0: no coarse stage)");
  }
  if (coarse_voxel_size > 0 &&
      !(coarse_max_correspondence_distance > 0 && std::isfinite(coarse_max_correspondence_distance))) {
    throw OptionError("coarse_max_correspondence_distance", "must be a positive distance (m)");
  }
  if (max_iterations < 1) throw OptionError("max_iterations", "must be >= 1");
  if (!(transformation_epsilon > 0)) throw OptionError("transformation_epsilon", "must be positive");
  if (!(rotation_epsilon > 0)) throw OptionError("rotation_epsilon", "must be positive");
  if (correspondence_randomness < 3) {
    throw OptionError("correspondence_randomness", "needs >= 3 neighbours to estimate a covariance");
  }
  if (max_optimizer_iterations < 1) throw OptionError("max_optimizer_iterations", "must be >= 1");
  if (!(translation_gradient_tolerance > 0)) throw OptionError("translation_gradient_tolerance", "must be positive");
  if (!(rotation_gradient_tolerance > 0)) throw OptionError("rotation_gradient_tolerance", "must be positive");
}

const char* GicpStatusName(GicpStatus s) {
  switch (s) {
    case GicpStatus::kConverged:
      return "converged";
    case GicpStatus::kMaxIterations:
      return "stopped at max_iterations";
    case GicpStatus::kTooFewPoints:
      return "too few points";
    case GicpStatus::kSolverFailed:
      return "solver failed";
  }
  return "?";
}

std::vector<Eigen::Vector3d> VoxelDownsample(const std::vector<Eigen::Vector3d>& points, double voxel) {
  if (!(voxel > 0)) return points;
  struct Cell {
    Eigen::Vector3d sum;
    int n;
  };
  struct KeyHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (std::int64_t v : k) h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::size_t, KeyHash> index;
  std::vector<Cell> cells;
  index.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const std::array<std::int64_t, 3> key = {static_cast<std::int64_t>(std::floor(p.x() / voxel)),
                                             static_cast<std::int64_t>(std::floor(p.y() / voxel)),
                                             static_cast<std::int64_t>(std::floor(p.z() / voxel))};
    const auto [it, fresh] = index.emplace(key, cells.size());
    if (fresh) {
      cells.push_back({p, 1});
    } else {
      cells[it->second].sum += p;
      ++cells[it->second].n;
    }
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(cells.size());
  for (const Cell& c : cells) out.push_back(c.sum / c.n);
  return out;
}

namespace {

// One GICP run at a given resolution and reach.
GicpResult RunStage(const std::vector<Eigen::Vector3d>& source_in, const std::vector<Eigen::Vector3d>& target_in,
                    const Pose& initial, double voxel, double reach, const GicpOptions& o) {
  const std::vector<Eigen::Vector3d> source = VoxelDownsample(source_in, voxel);
  const std::vector<Eigen::Vector3d> target = VoxelDownsample(target_in, voxel);
  GicpResult res;
  res.transform = initial;
  res.source_points = source.size();
  res.target_points = target.size();
  const auto k = static_cast<std::size_t>(o.correspondence_randomness);
  if (source.size() < k || target.size() < k) {
    res.status = GicpStatus::kTooFewPoints;
    return res;
  }

  // Work in centred coordinates: p_t' = p_t - c_t, p_s' = p_s - c_s, so
  // x_target_source = T(c_t) * x' * T(-c_s).
  const Eigen::Vector3d c_s = Centroid(source), c_t = Centroid(target);
  const auto src = ToCloud(source, c_s);
  const auto tgt = ToCloud(target, c_t);
  const Pose guess = Translation(-c_t) * initial * Translation(c_s);

  PclGicp gicp;
  gicp.setInputSource(src);
  gicp.setInputTarget(tgt);
  gicp.setMaxCorrespondenceDistance(reach);
  gicp.setMaximumIterations(o.max_iterations);
  gicp.setTransformationEpsilon(o.transformation_epsilon);
  gicp.setRotationEpsilon(o.rotation_epsilon);
  gicp.setCorrespondenceRandomness(o.correspondence_randomness);
  gicp.setMaximumOptimizerIterations(o.max_optimizer_iterations);
  gicp.setTranslationGradientTolerance(o.translation_gradient_tolerance);
  gicp.setRotationGradientTolerance(o.rotation_gradient_tolerance);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  gicp.align(aligned, guess.Matrix());

  const Eigen::Matrix4d T = gicp.getFinalTransformation();
  // Re-orthonormalise: the rotation went through float products.
  const Eigen::Quaterniond q(Eigen::Matrix3d(T.topLeftCorner<3, 3>()));
  const Pose centred(q.normalized(), T.topRightCorner<3, 1>());
  res.transform = Translation(c_t) * centred * Translation(-c_s);
  res.iterations = gicp.iterations();
  if (!gicp.hasConverged()) {
    res.status = GicpStatus::kSolverFailed;
  } else if (res.iterations >= o.max_iterations) {
    res.status = GicpStatus::kMaxIterations;
  } else {
    res.status = GicpStatus::kConverged;
  }
  res.converged = res.status == GicpStatus::kConverged;

  // Fitness: RMS nearest-neighbour distance within the reach.
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(tgt);
  std::vector<int> nn(1);
  std::vector<float> d2(1);
  const double reach2 = reach * reach;
  double sum = 0;
  for (const Eigen::Vector3d& p : source) {
    const Eigen::Vector3d q_t = centred * (p - c_s);
    const pcl::PointXYZ query(static_cast<float>(q_t.x()), static_cast<float>(q_t.y()), static_cast<float>(q_t.z()));
    if (tree.nearestKSearch(query, 1, nn, d2) < 1) continue;
    // Recompute in double from the pair (the tree's distance is in float).
    const Eigen::Vector3d nearest = target[static_cast<std::size_t>(nn[0])] - c_t;
    const double e2 = (q_t - nearest).squaredNorm();
    if (e2 > reach2) continue;
    sum += e2;
    ++res.correspondences;
  }
  res.fitness = res.correspondences ? std::sqrt(sum / static_cast<double>(res.correspondences)) : 0.0;
  return res;
}

}  // namespace

GicpResult AlignGicp(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                     const Pose& initial, const GicpOptions& o) {
  o.Check();
  // No point PCL cannot work with reaches it (its k-d tree asserts on NaN;
  // far points overflow the voxel grid and float covariances).
  auto check = [](const std::vector<Eigen::Vector3d>& cloud, const char* name) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (!Queryable(cloud[i])) {
        throw InputError({"", 0, 0, std::string(name) + " point " + std::to_string(i)},
                         "GICP input coordinate is not finite or beyond " + FormatDouble(kMaxQueryCoordinate) +
                             " m; an absurd position in the survey or the mesh");
      }
    }
  };
  check(source, "source");
  check(target, "target");
  if (!initial.translation().allFinite() || !initial.rotation().allFinite()) {
    throw InputError({"", 0, 0, "initial pose"}, "the initial GICP pose is not finite");
  }
  Pose start = initial;
  int coarse_iterations = 0;
  if (o.coarse_voxel_size > 0) {
    // A coarse stage that fails (e.g. a small cloud reduced below k points)
    // leaves the fine stage to start from the caller's guess.
    const GicpResult coarse =
        RunStage(source, target, initial, o.coarse_voxel_size, o.coarse_max_correspondence_distance, o);
    if (coarse.status == GicpStatus::kConverged || coarse.status == GicpStatus::kMaxIterations) {
      start = coarse.transform;
    }
    coarse_iterations = coarse.iterations;
  }
  GicpResult res = RunStage(source, target, start, o.voxel_size, o.max_correspondence_distance, o);
  res.iterations += coarse_iterations;
  return res;
}

}  // namespace hull
