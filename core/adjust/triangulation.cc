#include "adjust/triangulation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace hull {
namespace {

// Least-squares point closest to the rays: sum (I - d d^T)(X - c) = 0.
// Returns false when the normal matrix is ill-conditioned (small parallax).
bool SolveRays(const std::vector<ViewRay>& rays, const std::vector<int>& use, double min_parallax_rad,
               Eigen::Vector3d& X) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i : use) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - rays[i].dir * rays[i].dir.transpose();
    A += P;
    b += P * rays[i].origin;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A);
  // For two rays at angle a, the smallest eigenvalue of A is about 2 sin^2(a/2) ~ a^2 / 2.
  const double n = static_cast<double>(use.size());
  const double s = std::sin(0.5 * min_parallax_rad);
  if (es.eigenvalues()[0] < 2.0 * s * s * std::min(n / 2.0, 1.0)) return false;
  X = A.ldlt().solve(b);
  return X.allFinite();
}

double ReprojectionError(const ViewRay& r, const Eigen::Vector3d& X, double* depth) {
  const Eigen::Vector3d p = r.g_c.Inverse() * X;
  *depth = p.z();
  if (p.z() <= 1e-9) return 1e9;
  const Eigen::Vector2d uv(r.fx * p.x() / p.z() + r.cx, r.fy * p.y() / p.z() + r.cy);
  return (uv - r.pixel).norm();
}

}  // namespace

std::optional<Triangulated> TriangulateLandmark(const std::vector<ViewRay>& rays, const TriangulationOptions& o,
                                                const MeshIndex* mesh, const Pose& x_gM) {
  if (rays.empty()) return std::nullopt;
  std::vector<int> use(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) use[i] = static_cast<int>(i);
  const double min_par = o.min_parallax_deg * M_PI / 180.0;
  Eigen::Vector3d X;
  while (use.size() >= 2) {
    if (!SolveRays(rays, use, min_par, X)) break;
    // Drop the worst ray while any is beyond the reprojection limit or behind its camera.
    int worst = -1;
    double worst_err = -1;
    for (int i : use) {
      double depth = 0;
      const double e = ReprojectionError(rays[i], X, &depth);
      const double score = depth < o.min_depth ? 1e9 : e;
      if (score > worst_err) {
        worst_err = score;
        worst = i;
      }
    }
    if (worst_err <= o.max_reprojection_px) {
      Triangulated t;
      t.point = X;
      t.inliers = use;
      return t;
    }
    use.erase(std::find(use.begin(), use.end(), worst));
  }
  // Fallback: the first ray's hit on the prior mesh (model-assisted start).
  if (!mesh) return std::nullopt;
  const Pose Mg = x_gM.Inverse();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit hit = mesh->Raycast(Mg * rays[i].origin, Mg.Rotate(rays[i].dir), 30.0);
    if (!hit.hit) continue;
    Triangulated t;
    t.point = x_gM * hit.point;
    t.from_mesh = true;
    for (std::size_t j = 0; j < rays.size(); ++j) {
      double depth = 0;
      if (ReprojectionError(rays[j], t.point, &depth) <= o.max_reprojection_px && depth > o.min_depth) {
        t.inliers.push_back(static_cast<int>(j));
      }
    }
    if (!t.inliers.empty()) return t;
  }
  return std::nullopt;
}

}  // namespace hull
