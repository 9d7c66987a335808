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

// A hypothesis after point-to-plane ICP (stage 2) and GICP (stage 3).
struct Candidate {
  Pose start, x_gM;
  double score = 0;
  Eigen::Vector3d landing = Eigen::Vector3d::Zero();  // where the returns' centroid lands, in M
  double heading = 0;
  bool prior = false;
  Refined refined;
};

// The returns' footprint: centroid, normal (when planar) and horizontal
// principal axis, and the vehicle's mean heading.
struct Footprint {
  Eigen::Vector3d centroid, normal;
  bool planar = false;
  double axis_heading = 0;     // alpha: the principal axis (rad)
  double vehicle_heading = 0;  // beta: circular mean of nav yaw (rad)
};

Footprint FootprintOf(const SurveyBundle& bundle, const std::vector<DvlPoint>& returns,
                      const std::vector<Eigen::Vector3d>& pts_g) {
  Footprint fp;
  fp.centroid = Centroid(pts_g);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  Eigen::Vector3d mean_beam = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < pts_g.size(); ++i) {
    const Eigen::Vector3d d = pts_g[i] - fp.centroid;
    cov += d * d.transpose();
    mean_beam += returns[i].direction;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
  fp.planar = ev[0] < 0.01 * ev[1];  // thinner than a tenth of its narrower extent
  fp.normal = eig.eigenvectors().col(0);
  if (fp.normal.dot(mean_beam) > 0) fp.normal = -fp.normal;  // outward: toward the vehicle
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig2(cov.topLeftCorner<2, 2>());
  const Eigen::Vector2d axis = eig2.eigenvectors().col(1);
  fp.axis_heading = std::atan2(axis.y(), axis.x());
  Eigen::Vector2d hv = Eigen::Vector2d::Zero();
  for (const NavRecord& n : bundle.nav) hv += Eigen::Vector2d(std::cos(n.x_gv[5]), std::sin(n.x_gv[5]));
  fp.vehicle_heading = std::atan2(hv.y(), hv.x());
  return fp;
}

// The headings tried: the vehicle's and the footprint's axis (each both
// ways, the axis also across) and a sweep, none within 5 deg of another.
std::vector<double> CandidateHeadings(const Footprint& fp, const ModelAlignmentOptions& o) {
  std::vector<double> headings;
  auto add_heading = [&](double h) {
    h = WrapAngle(h);
    for (double g : headings) {
      if (AngleDiff(g, h) < 5 * kDeg) return;
    }
    headings.push_back(h);
  };
  const double alpha = fp.axis_heading, beta = fp.vehicle_heading;
  for (double h : {beta, beta + M_PI, alpha, alpha + M_PI, alpha + M_PI / 2, alpha - M_PI / 2}) add_heading(h);
  if (o.heading_step_deg > 0) {
    const int steps = static_cast<int>(std::floor(360.0 / o.heading_step_deg + 1e-9));
    for (int k = 0; k < steps; ++k) add_heading(beta + k * o.heading_step_deg * kDeg);
  }
  return headings;
}

// The search as stages, in the order CoarseSearch runs them: hypotheses
// (headings x anchors), stage 1 scores them all on a subsample, the
// tie-break reference, stage 2 gives the best distinct ones point-to-plane
// ICP, stage 3 refines the best of those by GICP, and the winner is picked.
class CoarseSearcher {
 public:
  CoarseSearcher(const SurveyBundle& bundle, const TriangleMesh& mesh, const MeshIndex& index,
                 const std::vector<DvlPoint>& returns, const std::vector<Eigen::Vector3d>& pts_g,
                 const ModelAlignmentOptions& o, Progress& progress)
      : bundle_(bundle),
        mesh_(mesh),
        index_(index),
        pts_g_(pts_g),
        o_(o),
        progress_(progress),
        hf_(HullFrameOf(bundle.manifest)),
        fp_(FootprintOf(bundle, returns, pts_g)) {}

  void MakeHypotheses(CoarseSearchReport* report);
  void ScoreHypotheses();
  void FindTieBreakReference();
  void RefineByIcp();
  void RefineByGicp(CoarseSearchReport* report);
  CoarseResult PickWinner(CoarseSearchReport* report) const;

 private:
  bool DistinctFrom(const std::vector<Candidate>& chosen, const Eigen::Vector3d& landing, double heading) const {
    for (const Candidate& c : chosen) {
      if ((c.landing - landing).norm() < 2.0 && AngleDiff(c.heading, heading) < 20 * kDeg) return false;
    }
    return true;
  }
  const Eigen::Vector3d& AnchorOf(const Hypothesis& h) const {
    return anchor_point_[static_cast<std::size_t>(h.anchor)];
  }
  bool NearestVehicleHeading(double heading) const {
    return AngleDiff(heading, fp_.vehicle_heading) <= best_dh_ + 1e-9;
  }

  const SurveyBundle& bundle_;
  const TriangleMesh& mesh_;
  const MeshIndex& index_;
  const std::vector<Eigen::Vector3d>& pts_g_;
  const ModelAlignmentOptions& o_;
  Progress& progress_;
  const HullFrame hf_;
  const Footprint fp_;
  std::vector<Eigen::Vector3d> anchor_point_, anchor_normal_;
  std::vector<Hypothesis> hyps_;      // sorted by score after stage 1
  std::vector<Eigen::Vector3d> sub_;  // the returns' subsample of stages 1 and 2
  // The tie-break: the heading difference to the vehicle's nearest among the
  // tied hypotheses, their mean anchor, and the hypothesis nearest it (-1: none).
  double best_dh_ = M_PI;
  Eigen::Vector3d ref_ = Eigen::Vector3d::Zero();
  int prior_pick_ = -1;
  std::vector<Candidate> stage2_, cands_;
};

// Anchors: the surface thinned to about one point per anchor_spacing voxel;
// a hypothesis per heading and anchor whose normal agrees with a planar
// footprint's.
void CoarseSearcher::MakeHypotheses(CoarseSearchReport* report) {
  const std::vector<Eigen::Vector3d> anchors =
      VoxelDownsample(SampleMeshSurface(mesh_, o_.anchor_spacing), o_.anchor_spacing);
  anchor_point_.resize(anchors.size());
  anchor_normal_.resize(anchors.size());
  tbb::parallel_for(std::size_t{0}, anchors.size(), [&](std::size_t i) {
    const ClosestPoint cp = index_.Closest(anchors[i]);
    anchor_point_[i] = cp.point;
    anchor_normal_[i] = mesh_.face_normals[static_cast<std::size_t>(cp.face)];
  });
  const double cos_max = std::cos(o_.max_normal_angle_deg * kDeg);
  for (double h : CandidateHeadings(fp_, o_)) {
    const Eigen::Matrix3d R = UprightRotation(hf_, h);
    const Eigen::Vector3d n_M = R.transpose() * fp_.normal;
    for (std::size_t a = 0; a < anchors.size(); ++a) {
      if (fp_.planar && anchor_normal_[a].dot(n_M) < cos_max) continue;
      Hypothesis hy;
      hy.heading = h;
      hy.anchor = static_cast<int>(a);
      hy.x_gM = Pose(R, fp_.centroid - R * anchor_point_[a]);
      hyps_.push_back(hy);
    }
  }
  report->ran = true;
  report->hypotheses = hyps_.size();
  if (hyps_.empty()) throw InputError({bundle_.directory, 0, 0, "dvl.csv"}, "no hull placement fits the DVL returns");
}

// Stage 1: every hypothesis scored on an even subsample of the returns, best first.
void CoarseSearcher::ScoreHypotheses() {
  const std::size_t stride = std::max<std::size_t>(1, pts_g_.size() / static_cast<std::size_t>(o_.score_points));
  for (std::size_t i = 0; i < pts_g_.size(); i += stride) sub_.push_back(pts_g_[i]);
  progress_.Update(0.05, "coarse search: scoring " + std::to_string(hyps_.size()) + " placements");
  tbb::parallel_for(std::size_t{0}, hyps_.size(), [&](std::size_t i) {
    if (progress_.Cancelled()) return;
    hyps_[i].score = TruncatedSurfaceRms(index_, sub_, hyps_[i].x_gM, o_.score_truncation);
  });
  progress_.ThrowIfCancelled();
  std::sort(hyps_.begin(), hyps_.end(), [](const Hypothesis& a, const Hypothesis& b) { return a.score < b.score; });
}

// The tie-break reference: among the placements the scores cannot tell
// apart (a flat or prismatic stretch fits anywhere along it), those whose
// heading is nearest the vehicle's, and their mean anchor: the place that
// minimises the largest possible error along the ambiguous stretch.
void CoarseSearcher::FindTieBreakReference() {
  const double tie = hyps_.front().score + o_.tie_tolerance;
  for (const Hypothesis& h : hyps_) {
    if (h.score > tie) break;
    best_dh_ = std::min(best_dh_, AngleDiff(h.heading, fp_.vehicle_heading));
  }
  int nref = 0;
  for (const Hypothesis& h : hyps_) {
    if (h.score > tie) break;
    if (NearestVehicleHeading(h.heading)) {
      ref_ += AnchorOf(h);
      ++nref;
    }
  }
  ref_ /= std::max(1, nref);
  double best_ref = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hyps_.size() && hyps_[i].score <= tie; ++i) {
    const double d = (AnchorOf(hyps_[i]) - ref_).norm();
    if (NearestVehicleHeading(hyps_[i].heading) && d < best_ref) {
      best_ref = d;
      prior_pick_ = static_cast<int>(i);
    }
  }
}

// Stage 2: the prior pick and the best distinct hypotheses get a few
// point-to-plane ICP steps on the subsample and are scored again (a grid
// of anchors and headings rarely lands on a curved stretch's best fit).
void CoarseSearcher::RefineByIcp() {
  auto add = [&](int i, bool prior) {
    const Hypothesis& h = hyps_[static_cast<std::size_t>(i)];
    Candidate c;
    c.start = h.x_gM;
    c.landing = AnchorOf(h);
    c.heading = h.heading;
    c.prior = prior;
    stage2_.push_back(c);
  };
  if (prior_pick_ >= 0) add(prior_pick_, true);
  for (std::size_t i = 0; i < hyps_.size() && static_cast<int>(stage2_.size()) < o_.icp_hypotheses; ++i) {
    if (DistinctFrom(stage2_, AnchorOf(hyps_[i]), hyps_[i].heading)) add(static_cast<int>(i), false);
  }
  progress_.Update(0.1, "coarse search: point-to-plane ICP of " + std::to_string(stage2_.size()) + " placements");
  tbb::parallel_for(std::size_t{0}, stage2_.size(), [&](std::size_t i) {
    if (progress_.Cancelled()) return;
    Candidate& c = stage2_[i];
    c.x_gM = PointToPlaneIcp(index_, sub_, c.start, 10, o_.score_truncation);
    c.score = TruncatedSurfaceRms(index_, sub_, c.x_gM, o_.score_truncation);
    c.landing = c.x_gM.Inverse() * fp_.centroid;
    c.heading = HeadingOf(hf_, c.x_gM);
  });
  progress_.ThrowIfCancelled();
  std::stable_sort(stage2_.begin(), stage2_.end(), [](const Candidate& a, const Candidate& b) {
    if (a.prior != b.prior) return a.prior;  // the prior pick stays first
    return a.score < b.score;
  });
}

// Stage 3: the best distinct ones are refined by GICP (against a lighter
// target) and scored on every return.
void CoarseSearcher::RefineByGicp(CoarseSearchReport* report) {
  for (const Candidate& c : stage2_) {
    if (static_cast<int>(cands_.size()) >= o_.refine_hypotheses) break;
    if (DistinctFrom(cands_, c.landing, c.heading)) cands_.push_back(c);
  }
  ModelAlignmentOptions light = o_;
  light.sample_spacing = std::max(o_.sample_spacing, o_.candidate_sample_spacing);
  for (std::size_t k = 0; k < cands_.size(); ++k) {
    progress_.ThrowIfCancelled();
    progress_.Update(
        0.15 + 0.5 * static_cast<double>(k) / static_cast<double>(cands_.size()),
        "coarse search: GICP of placement " + std::to_string(k + 1) + " of " + std::to_string(cands_.size()));
    Candidate& c = cands_[k];
    c.refined = Refine(index_, pts_g_, c.x_gM, light);
    c.score = TruncatedSurfaceRmsParallel(index_, pts_g_, c.refined.x_gM, o_.score_truncation);
    c.landing = c.refined.x_gM.Inverse() * fp_.centroid;
    c.heading = HeadingOf(hf_, c.refined.x_gM);
  }
  report->refined = cands_.size();
}

// Winner: among the refined placements tied with the best score, the one
// whose heading is nearest the vehicle's (10 deg buckets), then nearest the
// reference place.
CoarseResult CoarseSearcher::PickWinner(CoarseSearchReport* report) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Candidate& c : cands_) best = std::min(best, c.score);
  std::vector<const Candidate*> tied;
  for (const Candidate& c : cands_) {
    if (c.score <= best + o_.tie_tolerance) tied.push_back(&c);
  }
  auto key = [&](const Candidate* c) {
    return std::make_pair(std::floor(AngleDiff(c->heading, fp_.vehicle_heading) / (10 * kDeg)),
                          (c->landing - ref_).norm());
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

}  // namespace

// The coarse search (see CoarseSearchReport and ModelAlignmentOptions).
CoarseResult CoarseSearch(const SurveyBundle& bundle, const TriangleMesh& mesh, const MeshIndex& index,
                          const std::vector<DvlPoint>& returns, const std::vector<Eigen::Vector3d>& pts_g,
                          const ModelAlignmentOptions& o, Progress& progress, CoarseSearchReport* report) {
  CoarseSearcher search(bundle, mesh, index, returns, pts_g, o, progress);
  search.MakeHypotheses(report);
  search.ScoreHypotheses();
  search.FindTieBreakReference();
  search.RefineByIcp();
  search.RefineByGicp(report);
  return search.PickWinner(report);
}

}  // namespace hull::alignment_internal
