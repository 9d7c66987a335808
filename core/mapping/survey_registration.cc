#include "mapping/survey_registration.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>

#include "base/error.h"

namespace hull {
namespace {

// A's object nearest to p and its distance (index -1 when A is empty).
std::pair<int, double> NearestObject(const std::vector<DetectedObject>& a, const Eigen::Vector3d& p) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = (a[i].centroid_m - p).norm();
    if (d < best.second) best = {static_cast<int>(i), d};
  }
  return best;
}

// An object's outward normal; objects without one (results written before
// normals were kept) take the mean normal of their map, else +z.
Eigen::Vector3d NormalOf(const DetectedObject& o, const Eigen::Vector3d& fallback) {
  const double n = o.normal_m.norm();
  return n > 1e-9 && std::isfinite(n) ? Eigen::Vector3d(o.normal_m / n) : fallback;
}

Eigen::Vector3d MeanNormal(const std::vector<DetectedObject>& objects) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const DetectedObject& o : objects) {
    if (o.normal_m.allFinite()) sum += o.normal_m;
  }
  return sum.norm() > 1e-9 ? Eigen::Vector3d(sum.normalized()) : Eigen::Vector3d::UnitZ();
}

// The rigid motion taking B's centroids (and the points 1 m out along their
// normals) onto A's, least squares (Umeyama, no scale).
Pose FitMotion(const std::vector<DetectedObject>& a, const std::vector<DetectedObject>& b,
               const std::vector<std::pair<int, int>>& pairs, const Eigen::Vector3d& normal_a,
               const Eigen::Vector3d& normal_b) {
  Eigen::Matrix3Xd src(3, 2 * pairs.size()), dst(3, 2 * pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const DetectedObject& oa = a[static_cast<std::size_t>(pairs[k].first)];
    const DetectedObject& ob = b[static_cast<std::size_t>(pairs[k].second)];
    src.col(static_cast<Eigen::Index>(2 * k)) = ob.centroid_m;
    src.col(static_cast<Eigen::Index>(2 * k + 1)) = ob.centroid_m + NormalOf(ob, normal_b);
    dst.col(static_cast<Eigen::Index>(2 * k)) = oa.centroid_m;
    dst.col(static_cast<Eigen::Index>(2 * k + 1)) = oa.centroid_m + NormalOf(oa, normal_a);
  }
  return Pose::FromMatrix(Eigen::umeyama(src, dst, false));
}

struct Score {
  int inliers = 0;
  double sum = 0;  // of the inliers' distances
  bool Better(const Score& o) const { return inliers != o.inliers ? inliers > o.inliers : sum < o.sum; }
};

Score Evaluate(const std::vector<DetectedObject>& a, const std::vector<DetectedObject>& b, const Pose& x_ab,
               double radius, std::vector<std::pair<int, int>>* inliers = nullptr) {
  Score s;
  for (std::size_t j = 0; j < b.size(); ++j) {
    const auto [i, d] = NearestObject(a, x_ab * b[j].centroid_m);
    if (i < 0 || d > radius) continue;
    ++s.inliers;
    s.sum += d;
    if (inliers) inliers->push_back({i, static_cast<int>(j)});
  }
  return s;
}

// One-to-one: where two B objects claim the same A object, the nearer keeps it.
std::vector<std::pair<int, int>> OneToOne(const std::vector<DetectedObject>& a, const std::vector<DetectedObject>& b,
                                          const Pose& x_ab, std::vector<std::pair<int, int>> pairs) {
  auto dist = [&](const std::pair<int, int>& p) {
    return (a[static_cast<std::size_t>(p.first)].centroid_m - x_ab * b[static_cast<std::size_t>(p.second)].centroid_m)
        .norm();
  };
  std::sort(pairs.begin(), pairs.end(), [&](const auto& x, const auto& y) {
    const double dx = dist(x), dy = dist(y);
    return dx != dy ? dx < dy : x < y;
  });
  std::vector<char> used(a.size(), 0);
  std::vector<std::pair<int, int>> out;
  for (const auto& p : pairs) {
    if (used[static_cast<std::size_t>(p.first)]) continue;
    used[static_cast<std::size_t>(p.first)] = 1;
    out.push_back(p);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

void SurveyRegistrationOptions::Check() const {
  if (!(std::isfinite(match_radius) && match_radius > 0)) throw OptionError("match_radius", "must be positive (m)");
  if (!(std::isfinite(max_offset) && max_offset > 0)) throw OptionError("max_offset", "must be positive (m)");
  if (!(std::isfinite(max_rotation) && max_rotation >= 0 && max_rotation <= M_PI)) {
    throw OptionError("max_rotation", "must lie in [0, pi] (rad)");
  }
  if (min_inliers < 2) throw OptionError("min_inliers", "must be >= 2");
  if (max_hypotheses < 1) throw OptionError("max_hypotheses", "must be >= 1");
}

SurveyRegistration RegisterSurveys(const std::vector<DetectedObject>& a, const std::vector<DetectedObject>& b,
                                   const SurveyRegistrationOptions& o) {
  o.Check();
  SurveyRegistration out;
  const Eigen::Vector3d normal_a = MeanNormal(a), normal_b = MeanNormal(b);
  const Score identity = Evaluate(a, b, Pose::Identity(), o.match_radius);
  out.identity_inliers = identity.inliers;
  out.inliers = identity.inliers;

  // Putative correspondences: every (A, B) pair within max_offset.
  std::vector<std::pair<int, int>> putative;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if ((a[i].centroid_m - b[j].centroid_m).norm() <= o.max_offset) {
        putative.push_back({static_cast<int>(i), static_cast<int>(j)});
      }
    }
  }
  // Hypotheses: two correspondences of distinct objects whose spacing agrees
  // in both maps, far enough apart to fix a rotation.
  const std::size_t n = putative.size();
  const std::uint64_t all = n < 2 ? 0 : static_cast<std::uint64_t>(n) * (n - 1) / 2;
  const bool sample = all > static_cast<std::uint64_t>(o.max_hypotheses);
  std::mt19937_64 rng(20261126);
  std::uniform_int_distribution<std::size_t> pick(0, n == 0 ? 0 : n - 1);
  Score best = identity;
  Pose best_motion = Pose::Identity();
  auto consider = [&](const std::pair<int, int>& p, const std::pair<int, int>& q) {
    if (p.first == q.first || p.second == q.second) return;
    const Eigen::Vector3d& a1 = a[static_cast<std::size_t>(p.first)].centroid_m;
    const Eigen::Vector3d& a2 = a[static_cast<std::size_t>(q.first)].centroid_m;
    const Eigen::Vector3d& b1 = b[static_cast<std::size_t>(p.second)].centroid_m;
    const Eigen::Vector3d& b2 = b[static_cast<std::size_t>(q.second)].centroid_m;
    const double da = (a1 - a2).norm();
    if (da < 2 * o.match_radius || std::abs(da - (b1 - b2).norm()) > o.match_radius) return;
    const Pose x_ab = FitMotion(a, b, {p, q}, normal_a, normal_b);
    if (Pose::AngleBetween(x_ab, Pose::Identity()) > o.max_rotation) return;
    const Score s = Evaluate(a, b, x_ab, o.match_radius);
    if (s.Better(best)) {
      best = s;
      best_motion = x_ab;
    }
  };
  if (sample) {
    for (int h = 0; h < o.max_hypotheses; ++h) consider(putative[pick(rng)], putative[pick(rng)]);
  } else {
    for (std::size_t u = 0; u < n; ++u) {
      for (std::size_t v = u + 1; v < n; ++v) consider(putative[u], putative[v]);
    }
  }
  if (best.inliers < o.min_inliers || !best.Better(identity)) return out;

  // Refine over the inliers (one to one), twice: the refit may gain some.
  Pose x_ab = best_motion;
  for (int round = 0; round < 2; ++round) {
    std::vector<std::pair<int, int>> inl;
    Evaluate(a, b, x_ab, o.match_radius, &inl);
    inl = OneToOne(a, b, x_ab, inl);
    if (static_cast<int>(inl.size()) < o.min_inliers) break;
    x_ab = FitMotion(a, b, inl, normal_a, normal_b);
  }
  std::vector<std::pair<int, int>> inl;
  Evaluate(a, b, x_ab, o.match_radius, &inl);
  inl = OneToOne(a, b, x_ab, inl);
  if (static_cast<int>(inl.size()) < o.min_inliers) return out;
  double ss = 0;
  for (const auto& [i, j] : inl) {
    ss += (a[static_cast<std::size_t>(i)].centroid_m - x_ab * b[static_cast<std::size_t>(j)].centroid_m).squaredNorm();
  }
  out.registered = true;
  out.a_from_b = x_ab;
  out.inliers = static_cast<int>(inl.size());
  out.rms = std::sqrt(ss / static_cast<double>(inl.size()));
  out.rotation = Pose::AngleBetween(x_ab, Pose::Identity());
  out.translation = x_ab.translation().norm();
  return out;
}

}  // namespace hull
