#include "registration/model_alignment.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "base/csv.h"
#include "base/error.h"
#include "geometry/point_index.h"
#include "registration/model_alignment_internal.h"
#include "survey/survey_origin.h"

namespace hull {
namespace alignment_internal {

HullFrame HullFrameOf(const SurveyManifest& m) {
  const ModelAxes axes = m.model_axes.value_or(ModelAxes{});
  HullFrame h;
  h.f = axes.forward.normalized();
  h.p = axes.up.cross(h.f).normalized();
  h.u = h.f.cross(h.p);
  return h;
}

// R_gM for a ship upright in g (up -> -z) whose forward axis points at
// heading psi (rad from north, x of g): f -> (cos psi, sin psi, 0),
// port -> its left, up -> -z.
Eigen::Matrix3d UprightRotation(const HullFrame& h, double psi) {
  Eigen::Matrix3d F, E;
  F << h.f, h.p, h.u;
  E.col(0) = Eigen::Vector3d::UnitX();
  E.col(1) = -Eigen::Vector3d::UnitY();
  E.col(2) = -Eigen::Vector3d::UnitZ();
  return Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()).toRotationMatrix() * E * F.transpose();
}

// Heading (rad) of the hull's forward axis under x_gM.
double HeadingOf(const HullFrame& h, const Pose& x_gM) {
  const Eigen::Vector3d f = x_gM.Rotate(h.f);
  return std::atan2(f.y(), f.x());
}

double AngleDiff(double a, double b) { return std::abs(WrapAngle(a - b)); }

void Deadline::ThrowIfSpent(const std::string& stage) const {
  if (!(seconds_ > 0)) return;
  const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (spent <= seconds_) return;
  throw std::runtime_error("the alignment's time budget of " + FormatDouble(seconds_) + " s (max_seconds) is spent (" +
                           FormatDouble(std::round(spent)) + " s) at: " + stage +
                           "; a mesh far larger than the survey, or too many DVL returns?");
}

Eigen::Vector3d Centroid(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pts) c += p;
  return pts.empty() ? c : Eigen::Vector3d(c / static_cast<double>(pts.size()));
}

namespace {

// The steps of a face's barycentric sampling grid: its longest edge over `spacing`.
int GridSteps(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double spacing) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return std::max(1, static_cast<int>(std::min(std::ceil(longest / spacing), 1e9)));
}

// Samples on a face's barycentric grid of n steps: (n + 1)(n + 2) / 2 points.
double GridSamples(int n) { return 0.5 * (n + 1.0) * (n + 2.0); }

// Calls f(q) for every point of the face's barycentric grid of n steps.
template <class F>
void ForEachGridSample(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int n, F f) {
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) f(a + (static_cast<double>(i) * (b - a) + static_cast<double>(j) * (c - a)) / n);
  }
}

// A face whose grid holds more samples than this is sampled only around the
// points near it (SampleLargeFaceNear): a face metres across has a few
// thousand, one a kilometre across 10^8, and a sliver reaching a vertex
// 10^6 m away (a stray vertex, a mesh in the wrong units) 10^14.
constexpr double kMaxFaceGridSamples = 1e6;

// The samples of a large face (a, b, c) within `margin` of the points near
// it (`candidates`, indices into `points`): an in-plane square grid of
// `spacing` from a (axes along a->b and across it) over each point's
// margin window, each grid point once, in grid order, kept when inside the
// face and within the margin of a point.
void SampleLargeFaceNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         const PointIndex& points, const std::vector<std::pair<int, double>>& candidates,
                         double spacing, double margin, std::vector<Eigen::Vector3d>* out) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d normal = e1.cross(e2);
  if (!(normal.norm() > 0) || !(e1.norm() > 0)) return;  // a degenerate face has no area to sample
  const Eigen::Vector3d n = normal.normalized(), t1 = e1.normalized(), t2 = n.cross(t1);
  // The face in its plane's coordinates: a = (0, 0), b = (bx, 0), c = (cx, cy).
  const double bx = e1.norm(), cx = t1.dot(e2), cy = t2.dot(e2);
  const auto w = static_cast<std::int64_t>(std::ceil(margin / spacing));
  std::vector<std::pair<std::int64_t, std::int64_t>> cells;
  for (const auto& [i, d] : candidates) {
    const Eigen::Vector3d q = points.point(static_cast<std::size_t>(i)) - a;
    if (std::abs(n.dot(q)) > margin) continue;
    const auto x0 = static_cast<std::int64_t>(std::floor(t1.dot(q) / spacing));
    const auto y0 = static_cast<std::int64_t>(std::floor(t2.dot(q) / spacing));
    for (std::int64_t x = x0 - w; x <= x0 + w + 1; ++x) {
      for (std::int64_t y = y0 - w; y <= y0 + w + 1; ++y) cells.emplace_back(x, y);
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  const double m2 = margin * margin, eps = 1e-9 * bx;
  for (const auto& [xi, yi] : cells) {
    const double x = static_cast<double>(xi) * spacing, y = static_cast<double>(yi) * spacing;
    // Barycentric coordinates of (x, y) in the face: v along c, u along b.
    const double v = y / cy, u = (x - v * cx) / bx;
    if (u < -eps || v < -eps || u + v > 1 + eps) continue;
    const Eigen::Vector3d p = a + x * t1 + y * t2;
    const auto near = points.NearestOne(p);
    if (near.first >= 0 && near.second <= m2) out->push_back(p);
  }
}

}  // namespace

// Mesh samples within `margin` of any of `near_M` (points in M): faces whose
// bounding sphere comes within the margin are sampled, then each sample is
// kept if a point is within the margin. A large face is sampled only around
// the points near it (SampleLargeFaceNear), so the work grows with the area
// near the points, never with a face's size.
std::vector<Eigen::Vector3d> SampleNear(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& near_M,
                                        double spacing, double margin, const Deadline& deadline) {
  std::vector<Eigen::Vector3d> out;
  if (near_M.empty()) return out;
  const PointIndex index(near_M);
  const double m2 = margin * margin;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (f % 4096 == 0) deadline.ThrowIfSpent("sampling the mesh near the DVL returns");
    const Face& face = mesh.faces[f];
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(face[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(face[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(face[2])];
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    const double r = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
    const auto nn = index.Nearest(centre, 1);
    if (nn.empty() || nn[0].second > (r + margin) * (r + margin)) continue;
    const int n = GridSteps(a, b, c, spacing);
    if (GridSamples(n) > kMaxFaceGridSamples) {
      SampleLargeFaceNear(a, b, c, index, index.Within(centre, r + margin, false), spacing, margin, &out);
      continue;
    }
    ForEachGridSample(a, b, c, n, [&](const Eigen::Vector3d& q) {
      const auto near = index.Nearest(q, 1);
      if (!near.empty() && near[0].second <= m2) out.push_back(q);
    });
  }
  return out;
}

std::vector<Eigen::Vector3d> ToModel(const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM) {
  const Pose x_Mg = x_gM.Inverse();
  std::vector<Eigen::Vector3d> out;
  out.reserve(pts_g.size());
  for (const auto& p : pts_g) out.push_back(x_Mg * p);
  return out;
}

// RMS over the points of min(distance to the mesh, truncation).
double TruncatedSurfaceRms(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM,
                           double truncation) {
  if (pts_g.empty()) return 0.0;
  const Pose x_Mg = x_gM.Inverse();
  double sum = 0;
  for (const auto& p : pts_g) {
    const double d = std::min(index.Closest(x_Mg * p).distance, truncation);
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(pts_g.size()));
}

double TruncatedSurfaceRmsParallel(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM,
                                   double truncation) {
  if (pts_g.empty()) return 0.0;
  const Pose x_Mg = x_gM.Inverse();
  std::vector<double> d2(pts_g.size());
  tbb::parallel_for(std::size_t{0}, pts_g.size(), [&](std::size_t i) {
    const double d = std::min(index.Closest(x_Mg * pts_g[i]).distance, truncation);
    d2[i] = d * d;
  });
  return std::sqrt(std::accumulate(d2.begin(), d2.end(), 0.0) / static_cast<double>(pts_g.size()));
}

// Degeneracy guard (the "solution remapping" of Zhang, Kaess and Singh,
// ICRA 2016): GICP's update is kept only along the directions the returns
// constrain. At the aligned pose, with the returns q_i in M, their centroid c,
// RMS radius L and the closest faces' normals n_i, the point-to-plane
// information of a motion s = (L * rotation about c, translation) is
//   H = 1/N sum J_i^T J_i,  J_i = [((q_i - c) x n_i)^T / L, n_i^T],
// in m^2 of distance per m^2 of motion. Eigen-directions with eigenvalue
// below min_observability (e.g. in-plane motion and yaw over a flat bottom,
// motion along a prismatic stretch) are returned to the start: the data say
// nothing there, and GICP drifts freely along them (several degrees of yaw
// on the demo's flat bottom).
void ConstrainUpdate(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM0,
                     double min_observability, double truncation, Refined* r) {
  const Pose x_Mg1 = r->x_gM.Inverse();
  std::vector<Eigen::Vector3d> q(pts_g.size()), n(pts_g.size());
  std::vector<char> inlier(pts_g.size(), 0);
  tbb::parallel_for(std::size_t{0}, pts_g.size(), [&](std::size_t i) {
    q[i] = x_Mg1 * pts_g[i];
    const ClosestPoint cp = index.Closest(q[i]);
    n[i] = index.mesh().face_normals[static_cast<std::size_t>(cp.face)];
    inlier[i] = cp.distance < truncation;
  });
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  int m = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (inlier[i]) {
      c += q[i];
      ++m;
    }
  }
  if (m < 6) return;
  c /= m;
  double L2 = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (inlier[i]) L2 += (q[i] - c).squaredNorm();
  }
  const double L = std::max(1e-3, std::sqrt(L2 / m));
  Matrix6d H = Matrix6d::Zero();
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (!inlier[i]) continue;
    Vector6d J;
    J << (q[i] - c).cross(n[i]) / L, n[i];
    H += J * J.transpose();
  }
  H /= m;
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(H);
  r->observability = eig.eigenvalues();
  r->constrained_directions = 0;
  // The way back to the start, G = x_Mg0 (-)x_Mg1, as a motion about c:
  // G(q) = R_G (q - c) + c + w.
  const Pose G = x_gM0.Inverse() * r->x_gM;
  const Eigen::AngleAxisd aa(G.quaternion());
  Vector6d s;
  s << L * aa.angle() * aa.axis(), G * c - c;
  Vector6d back = Vector6d::Zero();
  for (int k = 0; k < 6; ++k) {
    if (eig.eigenvalues()[k] >= min_observability) {
      ++r->constrained_directions;
    } else {
      const Vector6d v = eig.eigenvectors().col(k);
      back += v.dot(s) * v;
    }
  }
  const Eigen::Vector3d rot = back.head<3>() / L;
  const Eigen::Quaterniond qb(
      Eigen::AngleAxisd(rot.norm(), rot.norm() > 0 ? Eigen::Vector3d(rot.normalized()) : Eigen::Vector3d::UnitX()));
  const Pose partial(qb, c + back.tail<3>() - (qb * c));
  r->x_gM = (partial * x_Mg1).Inverse();
}

// GICP of the returns (source, g) to the mesh samples near them (target, M)
// from x_gM0 (the GICP transform is x_Mg), then the degeneracy guard.
Refined Refine(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM0,
               const ModelAlignmentOptions& o, const Deadline& deadline) {
  const std::vector<Eigen::Vector3d> target =
      SampleNear(index.mesh(), ToModel(pts_g, x_gM0), o.sample_spacing, o.sample_margin, deadline);
  Refined r;
  r.target_points = target.size();
  deadline.ThrowIfSpent("starting GICP");
  r.gicp = AlignGicp(pts_g, target, x_gM0.Inverse(), o.gicp);
  deadline.ThrowIfSpent("GICP");
  const bool usable = r.gicp.status == GicpStatus::kConverged || r.gicp.status == GicpStatus::kMaxIterations;
  r.x_gM = usable ? r.gicp.transform.Inverse() : x_gM0;
  if (usable && o.min_observability > 0) {
    ConstrainUpdate(index, pts_g, x_gM0, o.min_observability, o.score_truncation, &r);
  }
  return r;
}

// A few Levenberg-damped Gauss-Newton steps of point-to-plane ICP against
// the exact mesh (closest faces looked up afresh each step), with returns
// farther than `truncation` left out; cheap enough for dozens of hypotheses.
// The motion is parametrised about the returns' centroid in M.
Pose PointToPlaneIcp(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM,
                     int iterations, double truncation) {
  Pose x_Mg = x_gM.Inverse();
  for (int it = 0; it < iterations; ++it) {
    std::vector<Eigen::Vector3d> q;
    q.reserve(pts_g.size());
    for (const auto& p : pts_g) q.push_back(x_Mg * p);
    const Eigen::Vector3d c = Centroid(q);
    Matrix6d H = Matrix6d::Zero();
    Vector6d b = Vector6d::Zero();
    int n = 0;
    for (const auto& qi : q) {
      const ClosestPoint cp = index.Closest(qi);
      if (cp.distance > truncation) continue;
      const Eigen::Vector3d& nrm = index.mesh().face_normals[static_cast<std::size_t>(cp.face)];
      Vector6d J;
      J << (qi - c).cross(nrm), nrm;
      const double r = nrm.dot(qi - cp.point);
      H += J * J.transpose();
      b += J * r;
      ++n;
    }
    if (n < 6) break;
    H += 1e-3 * n * Matrix6d::Identity();
    const Vector6d xi = -H.ldlt().solve(b);
    const Eigen::Vector3d w = xi.head<3>();
    const Eigen::Quaterniond dq(
        Eigen::AngleAxisd(w.norm(), w.norm() > 0 ? Eigen::Vector3d(w.normalized()) : Eigen::Vector3d::UnitX()));
    x_Mg = Pose(dq, c + xi.tail<3>() - dq * c) * x_Mg;
    if (xi.tail<3>().norm() < 1e-4 && w.norm() < 1e-5) break;
  }
  return x_Mg.Inverse();
}

}  // namespace alignment_internal

using namespace alignment_internal;

GicpOptions DvlGicpOptions() {
  GicpOptions g;
  g.voxel_size = 0.0;
  g.max_correspondence_distance = 0.5;
  g.coarse_voxel_size = 0.3;
  g.coarse_max_correspondence_distance = 1.5;
  g.correspondence_randomness = 10;
  // 0.1 mm and ~0.006 deg per iteration: far below what the drifting
  // navigation lets the returns resolve, and it stops the slow drift along
  // unconstrained directions (the degeneracy guard undoes that drift anyway).
  g.transformation_epsilon = 1e-4;
  g.rotation_epsilon = 1e-4;
  return g;
}

void ModelAlignmentOptions::Check() const {
  gicp.Check();
  if (!(sample_spacing > 0 && std::isfinite(sample_spacing)))
    throw OptionError("sample_spacing", "must be positive (m)");
  if (!(sample_margin > 0 && std::isfinite(sample_margin))) throw OptionError("sample_margin", "must be positive (m)");
  if (!(min_observability >= 0 && std::isfinite(min_observability))) {
    throw OptionError("min_observability", "must be >= 0 (0: keep every direction of the GICP update)");
  }
  if (!(depth_window >= 0 && std::isfinite(depth_window))) {
    throw OptionError("depth_window", "must be >= 0 (s; 0: no depth correction)");
  }
  if (!(max_beam_range > 0)) throw OptionError("max_beam_range", "must be positive (m)");
  if (!(max_seconds >= 0 && std::isfinite(max_seconds))) throw OptionError("max_seconds", "must be >= 0 (s; 0: none)");
  if (!(anchor_spacing > 0 && std::isfinite(anchor_spacing)))
    throw OptionError("anchor_spacing", "must be positive (m)");
  if (!(heading_step_deg >= 0 && heading_step_deg < 360)) {
    throw OptionError("heading_step_deg", "must be in [0, 360) (0: no sweep)");
  }
  if (!(max_normal_angle_deg > 0 && max_normal_angle_deg <= 180)) {
    throw OptionError("max_normal_angle_deg", "must be in (0, 180]");
  }
  if (score_points < 8) throw OptionError("score_points", "must be >= 8");
  if (icp_hypotheses < 1) throw OptionError("icp_hypotheses", "must be >= 1");
  if (refine_hypotheses < 1) throw OptionError("refine_hypotheses", "must be >= 1");
  if (!(candidate_sample_spacing > 0 && std::isfinite(candidate_sample_spacing))) {
    throw OptionError("candidate_sample_spacing", "must be positive (m)");
  }
  if (!(tie_tolerance >= 0 && std::isfinite(tie_tolerance))) throw OptionError("tie_tolerance", "must be >= 0 (m)");
  if (!(score_truncation > 0 && std::isfinite(score_truncation))) {
    throw OptionError("score_truncation", "must be positive (m)");
  }
}

std::optional<Pose> ModelPoseGuess(const SurveyBundle& bundle) {
  if (!bundle.manifest.model_pose_guess) return std::nullopt;
  return Pose::FromVector(*bundle.manifest.model_pose_guess);
}

std::vector<Eigen::Vector3d> SampleMeshSurface(const TriangleMesh& mesh, double spacing, double max_samples) {
  std::vector<Eigen::Vector3d> out;
  if (!(spacing > 0)) throw std::invalid_argument("SampleMeshSurface: spacing must be positive");
  double total = 0, largest = 0;
  std::size_t largest_face = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    const int n =
        GridSteps(mesh.vertices[static_cast<std::size_t>(face[0])], mesh.vertices[static_cast<std::size_t>(face[1])],
                  mesh.vertices[static_cast<std::size_t>(face[2])], spacing);
    total += GridSamples(n);
    if (n * spacing > largest) largest = n * spacing, largest_face = f;
  }
  if (total > max_samples) {
    throw InputError({"mesh", 0, 0, "face " + std::to_string(largest_face)},
                     "sampling the surface every " + FormatDouble(spacing) + " m would take " + FormatDouble(total) +
                         " points (this face is " + FormatDouble(largest) +
                         " m across): a vertex far from the rest of the mesh, or a mesh in the wrong units? Check "
                         "the mesh, or give the survey a model_pose_guess so that no search over the whole hull "
                         "is needed");
  }
  out.reserve(static_cast<std::size_t>(total));
  for (const Face& face : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(face[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(face[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(face[2])];
    ForEachGridSample(a, b, c, GridSteps(a, b, c, spacing), [&](const Eigen::Vector3d& q) { out.push_back(q); });
  }
  return out;
}

std::vector<double> DvlRangeResiduals(const std::vector<DvlPoint>& returns, const MeshIndex& mesh_in_M,
                                      const Pose& x_gM, double max_beam_range) {
  const Pose x_Mg = x_gM.Inverse();
  std::vector<double> out(returns.size(), kNaN);
  tbb::parallel_for(std::size_t{0}, returns.size(), [&](std::size_t i) {
    const DvlPoint& r = returns[i];
    const RayHit hit = mesh_in_M.Raycast(x_Mg * r.origin, x_Mg.Rotate(r.direction), max_beam_range);
    if (hit.hit) out[i] = hit.range - r.range;
  });
  return out;
}

namespace {

// The per-beam range residuals before and after, their RMS, and the
// returns' truncated surface RMS, into `out`.
void RecordResiduals(const std::vector<DvlPoint>& returns, const std::vector<Eigen::Vector3d>& pts_g,
                     const MeshIndex& index, const ModelAlignmentOptions& o, ModelAlignment* out) {
  const std::vector<double> before = DvlRangeResiduals(returns, index, out->initial_x_gM, o.max_beam_range);
  const std::vector<double> after = DvlRangeResiduals(returns, index, out->x_gM, o.max_beam_range);
  double sb = 0, sa = 0;
  out->residuals.reserve(returns.size());
  for (std::size_t i = 0; i < returns.size(); ++i) {
    out->residuals.push_back({returns[i].keyframe, returns[i].beam, returns[i].range, before[i], after[i]});
    if (std::isfinite(before[i]) && std::isfinite(after[i])) {
      sb += before[i] * before[i];
      sa += after[i] * after[i];
      ++out->residual_beams;
    }
  }
  if (out->residual_beams > 0) {
    out->residual_rms_before = std::sqrt(sb / static_cast<double>(out->residual_beams));
    out->residual_rms_after = std::sqrt(sa / static_cast<double>(out->residual_beams));
  }
  out->surface_rms_before = TruncatedSurfaceRmsParallel(index, pts_g, out->initial_x_gM, o.score_truncation);
  out->surface_rms_after = TruncatedSurfaceRmsParallel(index, pts_g, out->x_gM, o.score_truncation);
}

// The alignment of a survey in its local frame (LocalOrigin(bundle) is zero).
ModelAlignment AlignLocalSurvey(const SurveyBundle& bundle, const TriangleMesh& mesh_in_M,
                                std::optional<Pose> initial_x_gM, const ModelAlignmentOptions& o, Progress& progress) {
  const Deadline deadline(o.max_seconds);
  TriangleMesh mesh = mesh_in_M;
  if (mesh.face_normals.size() != mesh.faces.size()) mesh.ComputeNormals();
  const MeshIndex index(mesh);
  std::vector<double> servo;
  servo.reserve(bundle.nav.size());
  for (const NavRecord& n : bundle.nav) servo.push_back(n.servo);
  const std::vector<DvlPoint> returns =
      DvlPointsInG(bundle, InitialPosesWithZpr(bundle, o.depth_window, o.measured_roll_pitch), servo);
  const std::vector<Eigen::Vector3d> pts_g = PointsOf(returns);
  const auto k = static_cast<std::size_t>(o.gicp.correspondence_randomness);
  if (pts_g.size() < std::max<std::size_t>(k, 8)) {
    throw InputError({bundle.directory, 0, 0, "dvl.csv"}, "only " + std::to_string(pts_g.size()) +
                                                              " DVL returns: too few to align the model (need " +
                                                              std::to_string(std::max<std::size_t>(k, 8)) + ")");
  }

  progress.ThrowIfCancelled();
  ModelAlignment out;
  out.dvl_points = pts_g.size();
  Refined r;
  if (initial_x_gM) {
    out.initial_x_gM = *initial_x_gM;
    progress.Update(0.1, "aligning the DVL returns to the model (GICP)");
    r = Refine(index, pts_g, out.initial_x_gM, o, deadline);
  } else {
    // The winner's placement before any refinement is the "before" of the
    // residuals; the final GICP (full target) starts from its refined pose.
    const CoarseResult c = CoarseSearch(bundle, mesh, index, returns, pts_g, o, progress, deadline, &out.coarse);
    out.initial_x_gM = c.start;
    progress.Update(0.7, "aligning the DVL returns to the model (GICP)");
    r = Refine(index, pts_g, c.candidate, o, deadline);
  }
  out.x_gM = r.x_gM;
  out.gicp = r.gicp;
  out.observability = r.observability;
  out.constrained_directions = r.constrained_directions;
  out.target_points = r.target_points;
  progress.ThrowIfCancelled();

  progress.Update(0.9, "DVL range residuals");
  RecordResiduals(returns, pts_g, index, o, &out);
  progress.Update(1.0, "aligned");
  return out;
}

}  // namespace

ModelAlignment AlignDvlToModel(const SurveyBundle& bundle, const TriangleMesh& mesh_in_M,
                               std::optional<Pose> initial_x_gM, const ModelAlignmentOptions& o, Progress& progress) {
  o.Check();
  if (mesh_in_M.empty()) throw std::invalid_argument("AlignDvlToModel: the mesh has no faces");
  const Eigen::Vector3d origin = LocalOrigin(bundle);
  if (origin.isZero()) return AlignLocalSurvey(bundle, mesh_in_M, initial_x_gM, o, progress);
  // Large coordinates (survey_origin.h): aligned in g - origin, answered in g.
  SurveyBundle local = bundle;
  ShiftSurvey(local, -origin);
  if (initial_x_gM) initial_x_gM = ShiftedFrame(*initial_x_gM, -origin);
  ModelAlignment out = AlignLocalSurvey(local, mesh_in_M, initial_x_gM, o, progress);
  out.x_gM = ShiftedFrame(out.x_gM, origin);
  out.initial_x_gM = ShiftedFrame(out.initial_x_gM, origin);
  if (out.coarse.ran) out.coarse.start = ShiftedFrame(out.coarse.start, origin);
  out.gicp.transform = out.gicp.transform * Pose(Eigen::Quaterniond::Identity(), -origin);  // x_Mg
  return out;
}

}  // namespace hull
