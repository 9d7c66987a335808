#include "mapping/peak_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "geometry/convex_hull_2d.h"
#include "geometry/point_index.h"

namespace hull {
namespace {

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Strictly inside a counter-clockwise convex polygon.
bool Inside(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& q) {
  if (hull.size() < 3) return false;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    if (!(Cross(hull[i], hull[(i + 1) % hull.size()], q) > 0)) return false;
  }
  return true;
}

}  // namespace

PeakFitOptions PeakFitOptionsFor(const MappingOptions& options) {
  PeakFitOptions o;
  o.support = options.fusion_support;
  o.min_height = options.object_min_height;
  return o;
}

bool FitQuadricApex(const std::vector<Eigen::Vector3d>& uvh, bool isotropic, Eigen::Vector2d* apex_uv, double* apex_h,
                    double* rms, std::string* reason, std::vector<double>* fitted) {
  const Eigen::Index n = static_cast<Eigen::Index>(uvh.size());
  const Eigen::Index m = isotropic ? 4 : 6;
  if (n < m + 1) {
    *reason = "fewer features than the model has unknowns, plus one";
    return false;
  }
  // Coordinates scaled to about 1 for the conditioning of the system.
  double s = 0;
  for (const auto& p : uvh) s = std::max({s, std::abs(p.x()), std::abs(p.y())});
  if (!(s > 0)) {
    *reason = "features at one point";
    return false;
  }
  Eigen::MatrixXd A(n, m);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = uvh[static_cast<std::size_t>(i)].x() / s, v = uvh[static_cast<std::size_t>(i)].y() / s;
    if (isotropic) {
      A.row(i) << 1, u, v, u * u + v * v;
    } else {
      A.row(i) << 1, u, v, u * u, u * v, v * v;
    }
    y(i) = uvh[static_cast<std::size_t>(i)].z();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  if (!(sv(m - 1) > 1e-6 * sv(0))) {
    *reason = "features do not determine the model";
    return false;
  }
  const Eigen::VectorXd x = svd.solve(y);
  *rms = std::sqrt((A * x - y).squaredNorm() / static_cast<double>(n));
  // Gradient (b, c) and Hessian in the scaled coordinates.
  Eigen::Matrix2d H;
  if (isotropic) {
    H << 2 * x(3), 0, 0, 2 * x(3);
  } else {
    H << 2 * x(3), x(4), x(4), 2 * x(5);
  }
  const Eigen::Vector2d g(x(1), x(2));
  if (!(H(0, 0) < 0 && H.determinant() > 0)) {
    *reason = "not concave";
    return false;
  }
  const Eigen::Vector2d a = -H.inverse() * g;
  *apex_h = x(0) + 0.5 * g.dot(a);
  *apex_uv = a * s;
  if (fitted) {
    const Eigen::VectorXd f = A * x;
    fitted->assign(f.data(), f.data() + f.size());
  }
  std::vector<Eigen::Vector2d> uv;
  for (const auto& p : uvh) uv.push_back(p.head<2>());
  if (!Inside(ConvexHull(uv), *apex_uv)) {
    *reason = "apex outside the features";
    return false;
  }
  reason->clear();
  return true;
}

std::vector<FittedPeak> FitPeaks(const MappingInput& input, const MeshIndex& cad,
                                 const std::vector<KeyframeShapes>& shapes, const PeakFitOptions& o) {
  const Pose x_Mg = input.x_gM.Inverse();
  const std::size_t nl = input.landmarks.size();
  // Per landmark: the keyframes whose shapes hold it.
  std::vector<std::vector<int>> held(nl);
  for (const KeyframeShapes& ks : shapes) {
    for (const DetectedShape& sh : ks.shapes) {
      for (const int pi : sh.points) {
        auto& k = held[static_cast<std::size_t>(ks.points[static_cast<std::size_t>(pi)].landmark)];
        if (k.empty() || k.back() != ks.keyframe) k.push_back(ks.keyframe);
      }
    }
  }
  std::vector<Eigen::Vector3d> p_M(nl);
  for (std::size_t l = 0; l < nl; ++l) p_M[l] = x_Mg * input.landmarks[l].p_g;
  auto supported = [&](std::size_t l) {
    return static_cast<int>(held[l].size()) >= o.support && input.landmarks[l].deviation > o.min_height;
  };
  std::vector<int> tops;  // supported features, highest first
  for (std::size_t l = 0; l < nl; ++l) {
    if (supported(l)) tops.push_back(static_cast<int>(l));
  }
  std::sort(tops.begin(), tops.end(), [&](int a, int b) {
    const double da = input.landmarks[static_cast<std::size_t>(a)].deviation,
                 db = input.landmarks[static_cast<std::size_t>(b)].deviation;
    return da > db || (da == db && a < b);
  });
  std::vector<FittedPeak> out;
  if (tops.empty()) return out;
  const PointIndex index(p_M);
  std::vector<char> covered(nl, 0);  // within radius of a higher supported feature
  for (const int top : tops) {
    const std::size_t t = static_cast<std::size_t>(top);
    if (covered[t]) continue;
    const ClosestPoint cp = cad.Closest(p_M[t]);
    const Eigen::Vector3d n = cad.mesh().face_normals[static_cast<std::size_t>(cp.face)].normalized();
    const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    FittedPeak peak;
    peak.landmark = top;
    peak.top = input.landmarks[t].deviation;
    // The features around it (tangent-plane distance within the radius).
    std::vector<Eigen::Vector3d> uvh;
    std::vector<int> members;
    // In landmark order (a deterministic order for the fits).
    std::vector<std::pair<int, double>> near = index.Within(p_M[t], 2 * o.radius, false);
    std::sort(near.begin(), near.end());
    for (const auto& [l, d2] : near) {
      (void)d2;
      const Eigen::Vector3d q = p_M[static_cast<std::size_t>(l)] - cp.point;
      const Eigen::Vector2d uv(q.dot(e1), q.dot(e2));
      if (uv.norm() > o.radius) continue;
      if (supported(static_cast<std::size_t>(l))) covered[static_cast<std::size_t>(l)] = 1;  // not a local maximum
      if (o.cap > 0 && input.landmarks[static_cast<std::size_t>(l)].deviation < input.landmarks[t].deviation - o.cap)
        continue;
      uvh.emplace_back(uv.x(), uv.y(), input.landmarks[static_cast<std::size_t>(l)].deviation);
      members.push_back(l);
    }
    peak.features = static_cast<int>(members.size());
    std::set<int> keyframes;
    double top_supported = -std::numeric_limits<double>::infinity();
    for (const int l : members) {
      keyframes.insert(held[static_cast<std::size_t>(l)].begin(), held[static_cast<std::size_t>(l)].end());
      if (supported(static_cast<std::size_t>(l)))
        top_supported = std::max(top_supported, input.landmarks[static_cast<std::size_t>(l)].deviation);
    }
    peak.keyframes = static_cast<int>(keyframes.size());
    auto reject = [&](const std::string& why) {
      peak.reason = why;
      out.push_back(peak);
    };
    if (peak.features < o.min_features) {
      reject("fewer than " + std::to_string(o.min_features) + " features");
      continue;
    }
    if (peak.keyframes < o.min_keyframes) {
      reject("features in fewer than " + std::to_string(o.min_keyframes) + " keyframes' shapes");
      continue;
    }
    // Each fit gives two bounds on the apex: its own apex, and the feature
    // nearest that apex raised by the rise the fit predicts from it to the
    // apex (the fit's curvature times their distance: where features are
    // dense one lies at the apex and is raised by little, so the fit cannot
    // lift a well-measured top by its misfit). Its estimate is the lower.
    struct Fit {
      Eigen::Vector2d apex_uv;
      double apex = 0, rms = 0, estimate = 0, rise = 0;
    };
    std::string why;
    auto fit = [&](const std::vector<Eigen::Vector3d>& set, Fit* f) {
      std::vector<double> fitted;
      if (!FitQuadricApex(set, o.isotropic, &f->apex_uv, &f->apex, &f->rms, &why, &fitted)) return false;
      // The features nearest the apex, each raised by the rise the fit
      // predicts from it to the apex.
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t i = 0; i < set.size(); ++i) near.push_back({(set[i].head<2>() - f->apex_uv).norm(), i});
      std::sort(near.begin(), near.end());
      f->estimate = f->apex;
      for (std::size_t k = 0; k < near.size() && static_cast<int>(k) < o.near_features; ++k) {
        const std::size_t i = near[k].second;
        f->estimate = std::min(f->estimate, set[i].z() + std::max(0.0, f->apex - fitted[i]));
      }
      f->rise = f->apex - fitted[near.front().second];
      return true;
    };
    Fit all;
    if (!fit(uvh, &all)) {
      reject(why);
      continue;
    }
    peak.full_height = all.apex;
    peak.rms = all.rms;
    peak.rise = all.rise;
    if (!(all.rms <= o.max_rms)) {
      reject("residual RMS too large");
      continue;
    }
    // Leave-one-out: every fit without one feature must pass too; the apex
    // is the lowest estimate of them all, so no single feature can raise it
    // above what the others support.
    double lo = all.estimate, hi = all.apex;
    Eigen::Vector2d lo_uv = all.apex_uv;
    bool ok = true;
    for (std::size_t i = 0; ok && i < uvh.size(); ++i) {
      std::vector<Eigen::Vector3d> without = uvh;
      without.erase(without.begin() + static_cast<std::ptrdiff_t>(i));
      Fit f;
      if (!fit(without, &f) || !(f.rms <= o.max_rms)) {
        if (why.empty()) why = "residual RMS too large";
        why = "without one feature: " + why;
        ok = false;
        break;
      }
      if (f.estimate < lo) {
        lo = f.estimate;
        lo_uv = f.apex_uv;
      }
      hi = std::max(hi, f.apex);
    }
    if (!ok) {
      reject(why);
      continue;
    }
    if (!(hi - std::min(lo, all.apex) <= o.loo_spread)) {
      reject("leave-one-out apexes disagree");
      continue;
    }
    if (!(lo <= top_supported + o.max_rise)) {
      reject("apex too far above the features");
      continue;
    }
    if (!(lo > top_supported)) {
      reject("apex not above the highest feature");
      continue;
    }
    const ClosestPoint foot = cad.Closest(cp.point + lo_uv.x() * e1 + lo_uv.y() * e2);
    peak.foot = foot.point;
    peak.normal = cad.mesh().face_normals[static_cast<std::size_t>(foot.face)].normalized();
    peak.height = lo;
    peak.accepted = true;
    out.push_back(peak);
  }
  return out;
}

}  // namespace hull
