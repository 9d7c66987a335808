// The coarse search of the initial model alignment: headings and anchors
// scored against the mesh, the best refined (see CoarseSearchReport and
// ModelAlignmentOptions in model_alignment.h).
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "base/error.h"
#include "registration/model_alignment_internal.h"

namespace hull::alignment_internal {
namespace {

// A coarse-search hypothesis: heading and the anchor the returns' centroid lands on.
struct Hypothesis {
  double heading = 0;
  int anchor = 0;
  Pose x_gM;
  double score = 0;
};

}  // namespace

// The coarse search (see CoarseSearchReport and ModelAlignmentOptions).
CoarseResult CoarseSearch(const SurveyBundle& bundle, const TriangleMesh& mesh, const MeshIndex& index,
                          const std::vector<DvlPoint>& returns, const std::vector<Eigen::Vector3d>& pts_g,
                          const ModelAlignmentOptions& o, Progress& progress, CoarseSearchReport* report) {
  const HullFrame hf = HullFrameOf(bundle.manifest);
  const Eigen::Vector3d c_g = Centroid(pts_g);

  // The footprint: its normal (when planar) and horizontal principal axis.
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  Eigen::Vector3d mean_beam = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < pts_g.size(); ++i) {
    const Eigen::Vector3d d = pts_g[i] - c_g;
    cov += d * d.transpose();
    mean_beam += returns[i].direction;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
  const bool planar = ev[0] < 0.01 * ev[1];  // thinner than a tenth of its narrower extent
  Eigen::Vector3d n_g = eig.eigenvectors().col(0);
  if (n_g.dot(mean_beam) > 0) n_g = -n_g;  // outward: toward the vehicle
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig2(cov.topLeftCorner<2, 2>());
  const Eigen::Vector2d axis = eig2.eigenvectors().col(1);
  const double alpha = std::atan2(axis.y(), axis.x());
  // The vehicle's mean heading (circular mean of nav yaw).
  Eigen::Vector2d hv = Eigen::Vector2d::Zero();
  for (const NavRecord& n : bundle.nav) hv += Eigen::Vector2d(std::cos(n.x_gv[5]), std::sin(n.x_gv[5]));
  const double beta = std::atan2(hv.y(), hv.x());

  std::vector<double> headings;
  auto add_heading = [&](double h) {
    h = WrapAngle(h);
    for (double g : headings) {
      if (AngleDiff(g, h) < 5 * kDeg) return;
    }
    headings.push_back(h);
  };
  for (double h : {beta, beta + M_PI, alpha, alpha + M_PI, alpha + M_PI / 2, alpha - M_PI / 2}) add_heading(h);
  if (o.heading_step_deg > 0) {
    const int steps = static_cast<int>(std::floor(360.0 / o.heading_step_deg + 1e-9));
    for (int k = 0; k < steps; ++k) add_heading(beta + k * o.heading_step_deg * kDeg);
  }

  // Anchors: the surface thinned to about one point per anchor_spacing voxel.
  const std::vector<Eigen::Vector3d> anchors =
      VoxelDownsample(SampleMeshSurface(mesh, o.anchor_spacing), o.anchor_spacing);
  std::vector<Eigen::Vector3d> anchor_point(anchors.size()), anchor_normal(anchors.size());
  tbb::parallel_for(std::size_t{0}, anchors.size(), [&](std::size_t i) {
    const ClosestPoint cp = index.Closest(anchors[i]);
    anchor_point[i] = cp.point;
    anchor_normal[i] = mesh.face_normals[static_cast<std::size_t>(cp.face)];
  });

  std::vector<Hypothesis> hyps;
  const double cos_max = std::cos(o.max_normal_angle_deg * kDeg);
  for (double h : headings) {
    const Eigen::Matrix3d R = UprightRotation(hf, h);
    const Eigen::Vector3d n_M = R.transpose() * n_g;
    for (std::size_t a = 0; a < anchors.size(); ++a) {
      if (planar && anchor_normal[a].dot(n_M) < cos_max) continue;
      Hypothesis hy;
      hy.heading = h;
      hy.anchor = static_cast<int>(a);
      hy.x_gM = Pose(R, c_g - R * anchor_point[a]);
      hyps.push_back(hy);
    }
  }
  report->ran = true;
  report->hypotheses = hyps.size();
  if (hyps.empty()) throw InputError({bundle.directory, 0, 0, "dvl.csv"}, "no hull placement fits the DVL returns");

  // Stage 1: score every hypothesis on an even subsample of the returns.
  std::vector<Eigen::Vector3d> sub;
  const std::size_t stride = std::max<std::size_t>(1, pts_g.size() / static_cast<std::size_t>(o.score_points));
  for (std::size_t i = 0; i < pts_g.size(); i += stride) sub.push_back(pts_g[i]);
  progress.Update(0.05, "coarse search: scoring " + std::to_string(hyps.size()) + " placements");
  tbb::parallel_for(std::size_t{0}, hyps.size(), [&](std::size_t i) {
    if (progress.Cancelled()) return;
    hyps[i].score = TruncatedSurfaceRms(index, sub, hyps[i].x_gM, o.score_truncation);
  });
  progress.ThrowIfCancelled();
  std::sort(hyps.begin(), hyps.end(), [](const Hypothesis& a, const Hypothesis& b) { return a.score < b.score; });

  // The tie-break reference: among the placements the scores cannot tell
  // apart (a flat or prismatic stretch fits anywhere along it), those whose
  // heading is nearest the vehicle's, and their mean anchor: the place that
  // minimises the largest possible error along the ambiguous stretch.
  const double tie = hyps.front().score + o.tie_tolerance;
  double best_dh = M_PI;
  for (const Hypothesis& h : hyps) {
    if (h.score > tie) break;
    best_dh = std::min(best_dh, AngleDiff(h.heading, beta));
  }
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();
  int nref = 0;
  for (const Hypothesis& h : hyps) {
    if (h.score > tie) break;
    if (AngleDiff(h.heading, beta) <= best_dh + 1e-9) {
      ref += anchor_point[static_cast<std::size_t>(h.anchor)];
      ++nref;
    }
  }
  ref /= std::max(1, nref);
  int prior_pick = -1;
  double best_ref = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hyps.size() && hyps[i].score <= tie; ++i) {
    const double d = (anchor_point[static_cast<std::size_t>(hyps[i].anchor)] - ref).norm();
    if (AngleDiff(hyps[i].heading, beta) <= best_dh + 1e-9 && d < best_ref) {
      best_ref = d;
      prior_pick = static_cast<int>(i);
    }
  }

  // Stage 2: the prior pick and the best distinct hypotheses get a few
  // point-to-plane ICP steps on the subsample and are scored again (a grid
  // of anchors and headings rarely lands on a curved stretch's best fit).
  struct Candidate {
    Pose start, x_gM;
    double score = 0;
    Eigen::Vector3d landing = Eigen::Vector3d::Zero();  // where the returns' centroid lands, in M
    double heading = 0;
    bool prior = false;
    Refined refined;
  };
  auto distinct_from = [&](const std::vector<Candidate>& chosen, const Eigen::Vector3d& landing, double heading) {
    for (const Candidate& c : chosen) {
      if ((c.landing - landing).norm() < 2.0 && AngleDiff(c.heading, heading) < 20 * kDeg) return false;
    }
    return true;
  };
  std::vector<Candidate> stage2;
  auto add2 = [&](int i, bool prior) {
    const Hypothesis& h = hyps[static_cast<std::size_t>(i)];
    Candidate c;
    c.start = h.x_gM;
    c.landing = anchor_point[static_cast<std::size_t>(h.anchor)];
    c.heading = h.heading;
    c.prior = prior;
    stage2.push_back(c);
  };
  if (prior_pick >= 0) add2(prior_pick, true);
  for (std::size_t i = 0; i < hyps.size() && static_cast<int>(stage2.size()) < o.icp_hypotheses; ++i) {
    if (distinct_from(stage2, anchor_point[static_cast<std::size_t>(hyps[i].anchor)], hyps[i].heading)) {
      add2(static_cast<int>(i), false);
    }
  }
  progress.Update(0.1, "coarse search: point-to-plane ICP of " + std::to_string(stage2.size()) + " placements");
  tbb::parallel_for(std::size_t{0}, stage2.size(), [&](std::size_t i) {
    if (progress.Cancelled()) return;
    Candidate& c = stage2[i];
    c.x_gM = PointToPlaneIcp(index, sub, c.start, 10, o.score_truncation);
    c.score = TruncatedSurfaceRms(index, sub, c.x_gM, o.score_truncation);
    c.landing = c.x_gM.Inverse() * c_g;
    c.heading = HeadingOf(hf, c.x_gM);
  });
  progress.ThrowIfCancelled();
  std::stable_sort(stage2.begin(), stage2.end(), [](const Candidate& a, const Candidate& b) {
    if (a.prior != b.prior) return a.prior;  // the prior pick stays first
    return a.score < b.score;
  });

  // Stage 3: the best distinct ones are refined by GICP (against a lighter
  // target) and scored on every return.
  std::vector<Candidate> cands;
  for (const Candidate& c : stage2) {
    if (static_cast<int>(cands.size()) >= o.refine_hypotheses) break;
    if (distinct_from(cands, c.landing, c.heading)) cands.push_back(c);
  }
  ModelAlignmentOptions light = o;
  light.sample_spacing = std::max(o.sample_spacing, o.candidate_sample_spacing);
  for (std::size_t k = 0; k < cands.size(); ++k) {
    progress.ThrowIfCancelled();
    progress.Update(
        0.15 + 0.5 * static_cast<double>(k) / static_cast<double>(cands.size()),
        "coarse search: GICP of placement " + std::to_string(k + 1) + " of " + std::to_string(cands.size()));
    Candidate& c = cands[k];
    c.refined = Refine(index, pts_g, c.x_gM, light);
    c.score = TruncatedSurfaceRmsParallel(index, pts_g, c.refined.x_gM, o.score_truncation);
    c.landing = c.refined.x_gM.Inverse() * c_g;
    c.heading = HeadingOf(hf, c.refined.x_gM);
  }
  report->refined = cands.size();

  // Winner: among the refined placements tied with the best score, the one
  // whose heading is nearest the vehicle's (10 deg buckets), then nearest the
  // reference place.
  double best = std::numeric_limits<double>::infinity();
  for (const Candidate& c : cands) best = std::min(best, c.score);
  std::vector<const Candidate*> tied;
  for (const Candidate& c : cands) {
    if (c.score <= best + o.tie_tolerance) tied.push_back(&c);
  }
  auto key = [&](const Candidate* c) {
    return std::make_pair(std::floor(AngleDiff(c->heading, beta) / (10 * kDeg)), (c->landing - ref).norm());
  };
  const Candidate* win = *std::min_element(tied.begin(), tied.end(),
                                           [&](const Candidate* a, const Candidate* b) { return key(a) < key(b); });
  report->tied = tied.size();
  for (const Candidate* a : tied) {
    for (const Candidate* b : tied) {
      report->tied_position_spread = std::max(report->tied_position_spread, (a->landing - b->landing).norm());
      report->tied_heading_spread_deg =
          std::max(report->tied_heading_spread_deg, AngleDiff(a->heading, b->heading) / kDeg);
    }
  }
  report->best_score = win->score;
  report->start = win->start;
  return {win->start, win->refined.x_gM};
}

}  // namespace hull::alignment_internal
