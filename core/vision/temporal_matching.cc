#include "vision/temporal_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <random>

#include "vision/camera_geometry.h"

namespace hull {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Points bucketed in square cells for window queries.
class PointGrid {
 public:
  PointGrid(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& ids, double cell, int width, int height)
      : cell_(cell),
        nx_(std::max(1, static_cast<int>(std::ceil(width / cell)) + 1)),
        ny_(std::max(1, static_cast<int>(std::ceil(height / cell)) + 1)),
        cells_(static_cast<std::size_t>(nx_ * ny_)) {
    for (int id : ids) {
      const Eigen::Vector2d& p = points[static_cast<std::size_t>(id)];
      cells_[static_cast<std::size_t>(CellY(p.y()) * nx_ + CellX(p.x()))].push_back(id);
    }
  }
  // Calls f(id) for every point in cells touching the box.
  template <typename F>
  void ForEachInBox(double x0, double y0, double x1, double y1, F&& f) const {
    for (int cy = CellY(y0); cy <= CellY(y1); ++cy) {
      for (int cx = CellX(x0); cx <= CellX(x1); ++cx) {
        for (int id : cells_[static_cast<std::size_t>(cy * nx_ + cx)]) f(id);
      }
    }
  }

 private:
  int CellX(double x) const { return std::clamp(static_cast<int>(std::floor((x + 0.5) / cell_)), 0, nx_ - 1); }
  int CellY(double y) const { return std::clamp(static_cast<int>(std::floor((y + 0.5) / cell_)), 0, ny_ - 1); }
  double cell_;
  int nx_, ny_;
  std::vector<std::vector<int>> cells_;
};

double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& s0, const Eigen::Vector2d& s1) {
  const Eigen::Vector2d d = s1 - s0;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - s0).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (s0 + t * d - p).norm();
}

// Best and second-best candidate of one descriptor; ratio test; returns the
// best id or -1.
struct Best {
  float d1 = std::numeric_limits<float>::infinity(), d2 = std::numeric_limits<float>::infinity();
  int id = -1;
  void Offer(float d, int candidate) {
    if (d < d1) {
      d2 = d1;
      d1 = d;
      id = candidate;
    } else if (d < d2) {
      d2 = d;
    }
  }
  bool Passes(double ratio) const { return id >= 0 && d1 <= ratio * d2; }
};

// b keeps, for each of its features, the match with the smallest distance.
std::vector<TemporalMatch> OneToOne(std::vector<TemporalMatch> m, std::size_t b_features) {
  std::vector<int> owner(b_features, -1);
  for (std::size_t k = 0; k < m.size(); ++k) {
    int& w = owner[static_cast<std::size_t>(m[k].b)];
    if (w < 0 || m[k].distance < m[static_cast<std::size_t>(w)].distance) w = static_cast<int>(k);
  }
  std::vector<TemporalMatch> out;
  for (std::size_t k = 0; k < m.size(); ++k) {
    if (owner[static_cast<std::size_t>(m[k].b)] == static_cast<int>(k)) out.push_back(m[k]);
  }
  return out;
}

bool Project(const Eigen::Matrix3d& K, const Eigen::Vector3d& p, Eigen::Vector2d& uv) {
  if (p.z() <= 1e-6) return false;
  const Eigen::Vector3d h = K * p;
  uv = h.head<2>() / h.z();
  return true;
}

// RANSAC over rigid alignments of matched 3-D points; returns the inlier mask.
std::vector<char> RansacRigid(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                              const std::vector<Eigen::Vector2d>& ua, const std::vector<Eigen::Vector2d>& ub,
                              const Eigen::Matrix3d& K, const TemporalOptions& o, Pose& x_cb_ca) {
  const std::size_t n = pa.size();
  auto inliers_of = [&](const Pose& T, std::vector<char>& mask) {
    const Pose Ti = T.Inverse();
    int count = 0;
    mask.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector2d u;
      if (!Project(K, T * pa[i], u) || (u - ub[i]).norm() > o.ransac_threshold) continue;
      if (!Project(K, Ti * pb[i], u) || (u - ua[i]).norm() > o.ransac_threshold) continue;
      mask[i] = 1;
      ++count;
    }
    return count;
  };
  std::vector<char> best_mask, mask;
  int best = -1;
  std::mt19937 rng(12345);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  int needed = o.ransac_max_iterations;
  for (int it = 0; it < needed && it < o.ransac_max_iterations; ++it) {
    std::size_t s[3] = {pick(rng), pick(rng), pick(rng)};
    if (s[0] == s[1] || s[0] == s[2] || s[1] == s[2]) continue;
    if ((pa[s[1]] - pa[s[0]]).cross(pa[s[2]] - pa[s[0]]).norm() < 1e-6) continue;  // collinear
    const Pose T = AlignRigid({pa[s[0]], pa[s[1]], pa[s[2]]}, {pb[s[0]], pb[s[1]], pb[s[2]]});
    const int c = inliers_of(T, mask);
    if (c > best) {
      best = c;
      best_mask = mask;
      x_cb_ca = T;
      needed = RansacDrawsNeeded(static_cast<double>(c) / static_cast<double>(n), 3, o.ransac_confidence,
                                 o.ransac_max_iterations);
      if (needed == 0) break;
    }
  }
  if (best < 3) return std::vector<char>(n, 0);
  // Refit on the inliers, twice.
  for (int round = 0; round < 2; ++round) {
    std::vector<Eigen::Vector3d> s, d;
    for (std::size_t i = 0; i < n; ++i) {
      if (best_mask[i]) {
        s.push_back(pa[i]);
        d.push_back(pb[i]);
      }
    }
    if (s.size() < 3) break;
    const Pose T = AlignRigid(s, d);
    const int c = inliers_of(T, mask);
    if (c < best) break;
    best = c;
    best_mask = mask;
    x_cb_ca = T;
  }
  return best_mask;
}

// Whether the point seen along unit rays ra (camera a) and rb (camera b)
// lies in front of both for the motion p_b = R p_a + t.
bool InFrontOfBoth(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Eigen::Vector3d& ra,
                   const Eigen::Vector3d& rb) {
  Eigen::Matrix<double, 3, 2> A;
  A.col(0) = R * ra;
  A.col(1) = -rb;
  const Eigen::Vector2d depth = A.colPivHouseholderQr().solve(-t);
  return depth(0) > 0 && depth(1) > 0;
}

// A near-planar scene (a stretch of hull seen by one camera) fits more than
// one essential matrix, and the 5-point RANSAC may return one whose motion is
// not the vehicle's (recoverPose then reports a rotation far from the prior).
// The plane's homography decomposes into up to four motions (Faugeras and
// Lustman; cv::decomposeHomographyMat): the one nearest the navigation prior
// is taken if it agrees with it, and every putative match is then judged by
// its Sampson distance to that motion's epipolar geometry and by cheirality,
// so points off the plane (fouling, objects) stay inliers.
bool PlanarMotionNearThePrior(const std::vector<cv::Point2d>& pa, const std::vector<cv::Point2d>& pb,
                              const Eigen::Matrix3d& K, const Pose& prior_cb_ca, const TemporalOptions& o,
                              Pose& x_cb_ca, std::vector<char>& mask) {
  cv::Mat hmask;
  const cv::Mat H = cv::findHomography(pa, pb, cv::RANSAC, o.ransac_threshold, hmask, 2000, o.ransac_confidence);
  if (H.empty()) return false;
  cv::Mat Kcv;
  cv::eigen2cv(K, Kcv);
  std::vector<cv::Mat> Rs, ts, ns;
  const int n = cv::decomposeHomographyMat(H, Kcv, Rs, ts, ns);
  const Eigen::Vector3d tp = prior_cb_ca.translation();
  double best = o.max_rotation_error_deg * kDeg;
  bool found = false;
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix3d Ri;
    Eigen::Vector3d ti;
    cv::cv2eigen(Rs[static_cast<std::size_t>(i)], Ri);
    cv::cv2eigen(ts[static_cast<std::size_t>(i)], ti);
    if (!(ti.norm() > 1e-12)) continue;
    ti.normalize();
    const Pose cand(Ri, ti);
    const double rot = Pose::AngleBetween(cand, prior_cb_ca);
    if (rot > best) continue;
    if (tp.norm() > 0.01 && AngleBetweenDirections(ti, tp) > o.max_direction_error_deg * kDeg) continue;
    best = rot;
    x_cb_ca = cand;
    found = true;
  }
  if (!found) return false;
  const Eigen::Matrix3d R = x_cb_ca.rotation();
  const Eigen::Vector3d t = x_cb_ca.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Matrix3d F = Kinv.transpose() * tx * R * Kinv;
  mask.assign(pa.size(), 0);
  for (std::size_t k = 0; k < pa.size(); ++k) {
    const Eigen::Vector3d x1(pa[k].x, pa[k].y, 1.0), x2(pb[k].x, pb[k].y, 1.0);
    const Eigen::Vector3d Fx1 = F * x1, Ftx2 = F.transpose() * x2;
    const double e = x2.dot(Fx1);
    const double den = Fx1.x() * Fx1.x() + Fx1.y() * Fx1.y() + Ftx2.x() * Ftx2.x() + Ftx2.y() * Ftx2.y();
    if (!(den > 0) || e * e / den > o.ransac_threshold * o.ransac_threshold) continue;
    mask[k] = InFrontOfBoth(R, t, (Kinv * x1).normalized(), (Kinv * x2).normalized()) ? 1 : 0;
  }
  return true;
}

}  // namespace

int RansacDrawsNeeded(double inlier_ratio, int sample_size, double confidence, int max_draws) {
  // A hypothesis with no inliers says nothing about the inlier ratio: log(1)
  // = 0 would make the bound -inf and end the search at its first bad draw
  // (which dropped 8 % of the demo's keyframe pairs with "0 inliers").
  if (inlier_ratio <= 0) return max_draws;
  const double fail = 1.0 - std::pow(std::min(inlier_ratio, 1.0), sample_size);
  if (fail <= 0) return 0;
  const double draws = std::ceil(std::log(1.0 - confidence) / std::log(fail));
  return static_cast<int>(std::min(draws, static_cast<double>(max_draws)));
}

PairMatches MatchKeyframes(const KeyframeView& a, const KeyframeView& b, const CameraRig& rig,
                           const TemporalOptions& o) {
  o.Check();
  PairMatches r;
  r.stereo = rig.stereo() && !a.stereo.empty() && !b.stereo.empty();
  const Eigen::Matrix3d K = CameraMatrix(rig.top);
  const Eigen::Matrix3d Kinv = K.inverse();
  const Pose prior_cb_ca = b.x_g_cT.Inverse() * a.x_g_cT;  // moves a-frame points into b's frame
  const double margin = o.window;

  // Candidates in b: its stereo features (stereo) or all its features (mono).
  std::vector<int> b_ids;
  std::vector<int> b_stereo(b.top.size(), -1);  // top index -> stereo match index
  if (r.stereo) {
    for (std::size_t k = 0; k < b.stereo.size(); ++k) {
      b_ids.push_back(b.stereo[k].top);
      b_stereo[static_cast<std::size_t>(b.stereo[k].top)] = static_cast<int>(k);
    }
  } else {
    for (std::size_t k = 0; k < b.top.size(); ++k) b_ids.push_back(static_cast<int>(k));
  }
  const PointGrid grid(b.top.points, b_ids, std::max(16.0, o.window), rig.width, rig.height);

  std::vector<TemporalMatch> putative;
  std::vector<int> a_stereo_of;  // stereo: a's stereo match index per putative match
  if (r.stereo) {
    std::vector<std::pair<TemporalMatch, int>> found;
    for (std::size_t k = 0; k < a.stereo.size(); ++k) {
      const StereoMatch& s = a.stereo[k];
      Eigen::Vector2d pred;
      if (!Project(K, prior_cb_ca * s.p_top, pred)) continue;
      if (pred.x() < -margin || pred.y() < -margin || pred.x() > rig.width + margin || pred.y() > rig.height + margin)
        continue;
      Best best;
      const float* da = a.top.Descriptor(static_cast<std::size_t>(s.top));
      grid.ForEachInBox(
          pred.x() - o.window, pred.y() - o.window, pred.x() + o.window, pred.y() + o.window, [&](int id) {
            if ((b.top.points[static_cast<std::size_t>(id)] - pred).norm() > o.window) return;
            best.Offer(std::sqrt(DescriptorDistance2(da, b.top.Descriptor(static_cast<std::size_t>(id)))), id);
          });
      if (best.Passes(o.ratio)) found.push_back({{s.top, best.id, best.d1}, static_cast<int>(k)});
    }
    std::vector<TemporalMatch> m;
    for (const auto& f : found) m.push_back(f.first);
    putative = OneToOne(m, b.top.size());
    std::vector<int> a_stereo(a.top.size(), -1);
    for (const auto& f : found) a_stereo[static_cast<std::size_t>(f.first.a)] = f.second;
    for (const auto& m1 : putative) a_stereo_of.push_back(a_stereo[static_cast<std::size_t>(m1.a)]);
  } else {
    std::vector<TemporalMatch> m;
    for (std::size_t i = 0; i < a.top.size(); ++i) {
      const Eigen::Vector3d ray = Kinv * a.top.points[i].homogeneous();
      Eigen::Vector2d s0, s1;
      if (!Project(K, prior_cb_ca * (ray * o.mono_min_depth), s0) ||
          !Project(K, prior_cb_ca * (ray * o.mono_max_depth), s1))
        continue;
      Best best;
      const float* da = a.top.Descriptor(i);
      grid.ForEachInBox(std::min(s0.x(), s1.x()) - o.window, std::min(s0.y(), s1.y()) - o.window,
                        std::max(s0.x(), s1.x()) + o.window, std::max(s0.y(), s1.y()) + o.window, [&](int id) {
                          if (PointSegmentDistance(b.top.points[static_cast<std::size_t>(id)], s0, s1) > o.window)
                            return;
                          best.Offer(std::sqrt(DescriptorDistance2(da, b.top.Descriptor(static_cast<std::size_t>(id)))),
                                     id);
                        });
      if (best.Passes(o.ratio)) m.push_back({static_cast<int>(i), best.id, best.d1});
    }
    putative = OneToOne(m, b.top.size());
  }
  r.putative = static_cast<int>(putative.size());
  r.putative_matches = putative;
  r.putative_inlier.assign(putative.size(), 0);
  if (r.putative < o.min_inliers) {
    r.note = "too few putative matches";
    return r;
  }

  std::vector<char> mask;
  if (r.stereo) {
    std::vector<Eigen::Vector3d> pa, pb;
    std::vector<Eigen::Vector2d> ua, ub;
    for (std::size_t k = 0; k < putative.size(); ++k) {
      pa.push_back(a.stereo[static_cast<std::size_t>(a_stereo_of[k])].p_top);
      pb.push_back(b.stereo[static_cast<std::size_t>(b_stereo[static_cast<std::size_t>(putative[k].b)])].p_top);
      ua.push_back(a.top.points[static_cast<std::size_t>(putative[k].a)]);
      ub.push_back(b.top.points[static_cast<std::size_t>(putative[k].b)]);
    }
    Pose x_cb_ca;
    mask = RansacRigid(pa, pb, ua, ub, K, o, x_cb_ca);
    r.x_ca_cb = x_cb_ca.Inverse();
    r.inliers = static_cast<int>(std::count(mask.begin(), mask.end(), 1));
    if (r.inliers >= o.min_inliers) {
      const double rot = Pose::AngleBetween(x_cb_ca, prior_cb_ca);
      const double dt = (x_cb_ca.translation() - prior_cb_ca.translation()).norm();
      if (rot > o.max_rotation_error_deg * kDeg) {
        r.note = "rotation disagrees with the navigation prior";
      } else if (dt > o.max_translation_error) {
        r.note = "translation disagrees with the navigation prior";
      }
    }
  } else {
    std::vector<cv::Point2d> pa, pb;
    for (const auto& m : putative) {
      const Eigen::Vector2d& u = a.top.points[static_cast<std::size_t>(m.a)];
      const Eigen::Vector2d& v = b.top.points[static_cast<std::size_t>(m.b)];
      pa.emplace_back(u.x(), u.y());
      pb.emplace_back(v.x(), v.y());
    }
    cv::Mat Kcv;
    cv::eigen2cv(K, Kcv);
    cv::Mat inl;
    cv::Mat E = cv::findEssentialMat(pa, pb, Kcv, cv::RANSAC, o.ransac_confidence, o.ransac_threshold, inl);
    if (E.rows < 3 || E.cols != 3) {
      r.note = "no essential matrix";
      return r;
    }
    E = E.rowRange(0, 3).clone();
    cv::Mat R, t;
    cv::recoverPose(E, pa, pb, Kcv, R, t, inl);  // keeps the inliers in front of both cameras
    Eigen::Matrix3d Re;
    Eigen::Vector3d te;
    cv::cv2eigen(R, Re);
    cv::cv2eigen(t, te);
    Pose x_cb_ca(Re, te);
    r.x_ca_cb = x_cb_ca.Inverse();
    mask.assign(putative.size(), 0);
    for (std::size_t k = 0; k < putative.size(); ++k) mask[k] = inl.at<unsigned char>(static_cast<int>(k)) ? 1 : 0;
    r.inliers = static_cast<int>(std::count(mask.begin(), mask.end(), 1));
    Pose planar;
    std::vector<char> planar_mask;
    if (r.inliers >= o.min_inliers && Pose::AngleBetween(x_cb_ca, prior_cb_ca) > o.max_rotation_error_deg * kDeg &&
        PlanarMotionNearThePrior(pa, pb, K, prior_cb_ca, o, planar, planar_mask)) {
      // The essential matrix took the other motion of a near-planar scene.
      x_cb_ca = planar;
      mask = planar_mask;
      r.x_ca_cb = x_cb_ca.Inverse();
      r.inliers = static_cast<int>(std::count(mask.begin(), mask.end(), 1));
      te = x_cb_ca.translation();
    }
    if (r.inliers >= o.min_inliers) {
      const double rot = Pose::AngleBetween(x_cb_ca, prior_cb_ca);
      const Eigen::Vector3d tp = prior_cb_ca.translation();
      if (rot > o.max_rotation_error_deg * kDeg) {
        r.note = "rotation disagrees with the navigation prior";
      } else if (tp.norm() > 0.01 && AngleBetweenDirections(te, tp) > o.max_direction_error_deg * kDeg) {
        r.note = "translation direction disagrees with the navigation prior";
      }
    }
  }
  r.putative_inlier = mask;
  if (r.inliers < o.min_inliers) {
    r.note = "too few RANSAC inliers";
    return r;
  }
  if (!r.note.empty()) return r;
  r.accepted = true;
  for (std::size_t k = 0; k < putative.size(); ++k) {
    if (mask[k]) r.matches.push_back(putative[k]);
  }
  return r;
}

}  // namespace hull
