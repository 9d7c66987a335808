#include "ui/models/cross_section.h"

#include <algorithm>
#include <cmath>

namespace hull::ui {

namespace {

void HullAxes(const std::optional<ModelAxes>& axes, Eigen::Vector3d* forward, Eigen::Vector3d* up) {
  *forward = Eigen::Vector3d::UnitX();
  *up = Eigen::Vector3d::UnitZ();
  if (axes && axes->forward.norm() > 0 && axes->up.norm() > 0) {
    *up = axes->up.normalized();
    // Forward made orthogonal to up (model axes are orthogonal in practice).
    Eigen::Vector3d f = axes->forward - axes->forward.dot(*up) * *up;
    if (f.norm() > 1e-9) *forward = f.normalized();
  }
}

}  // namespace

SlabFrame MakeSlabFrame(const std::optional<ModelAxes>& axes, const SlabSpec& spec) {
  Eigen::Vector3d forward, up;
  HullAxes(axes, &forward, &up);
  SlabFrame f;
  f.v = up;
  f.normal = spec.direction == SlabDirection::kTransverse ? forward : up.cross(forward).normalized();
  f.u = f.normal.cross(f.v).normalized();
  f.position = spec.position;
  f.half_width = 0.5 * spec.width;
  return f;
}

std::pair<double, double> SlabRange(const std::optional<ModelAxes>& axes, SlabDirection direction,
                                    const std::vector<Eigen::Vector3d>& points_M) {
  if (points_M.empty()) return {0.0, 0.0};
  SlabSpec spec;
  spec.direction = direction;
  const SlabFrame f = MakeSlabFrame(axes, spec);
  double lo = f.normal.dot(points_M.front()), hi = lo;
  for (const auto& p : points_M) {
    const double d = f.normal.dot(p);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return {lo, hi};
}

std::vector<ProfileSegment> MeshSection(const TriangleMesh& mesh_M, const SlabFrame& frame) {
  std::vector<ProfileSegment> out;
  std::vector<double> offset(mesh_M.vertices.size());
  for (std::size_t i = 0; i < offset.size(); ++i) offset[i] = frame.Offset(mesh_M.vertices[i]);
  for (const Face& f : mesh_M.faces) {
    const double d[3] = {offset[f[0]], offset[f[1]], offset[f[2]]};
    if ((d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0)) continue;
    // The points where the plane crosses the triangle's edges.
    Eigen::Vector3d hits[3];
    int n = 0;
    for (int e = 0; e < 3 && n < 2; ++e) {
      const int a = e, b = (e + 1) % 3;
      const double da = d[a], db = d[b];
      if ((da < 0 && db < 0) || (da > 0 && db > 0)) continue;
      if (da == db) continue;  // the edge lies in the plane: its neighbours give it
      const double t = da / (da - db);
      if (t < 0 || t > 1) continue;
      const Eigen::Vector3d p = mesh_M.vertices[f[a]] + t * (mesh_M.vertices[f[b]] - mesh_M.vertices[f[a]]);
      if (n == 1 && (p - hits[0]).squaredNorm() < 1e-18) continue;  // through a vertex
      hits[n++] = p;
    }
    if (n == 2) out.push_back({frame.Project(hits[0]), frame.Project(hits[1])});
  }
  return out;
}

ModelProfile ComputeModelProfile(const AdjustmentRun& run, const SlabFrame& frame) {
  ModelProfile out;
  out.model = run.model();
  const Pose x_Mg = run.x_gM().Inverse();
  for (const AdjustedLandmark& l : run.overlays->landmarks) {
    const Eigen::Vector3d p = x_Mg * l.position;
    if (!frame.Contains(p)) continue;
    ProfilePoint q;
    q.uv = frame.Project(p);
    q.label = l.label;
    q.deviation = l.deviation;
    q.id = l.id;
    out.features.push_back(q);
  }
  for (const DvlHit& h : run.overlays->dvl_hits) {
    const Eigen::Vector3d p = x_Mg * h.point;
    if (!frame.Contains(p)) continue;
    ProfilePoint q;
    q.uv = frame.Project(p);
    const auto k = static_cast<std::size_t>(h.nav_index);
    q.id = k < run.overlays->keyframes.size() ? run.overlays->keyframes[k] : 0;
    out.dvl.push_back(q);
  }
  return out;
}

SlabBox MakeSlabBox(const SlabFrame& frame, const Eigen::AlignedBox2d& extent, const Pose& x_gM) {
  SlabBox box;
  const Eigen::Vector2d c = extent.center();
  const Eigen::Vector3d centre_M = frame.position * frame.normal + c.x() * frame.u + c.y() * frame.v;
  box.centre = x_gM * centre_M;
  box.axes.col(0) = x_gM.Rotate(frame.normal);
  box.axes.col(1) = x_gM.Rotate(frame.u);
  box.axes.col(2) = x_gM.Rotate(frame.v);
  const Eigen::Vector2d half = 0.5 * extent.sizes();
  box.half_extents = Eigen::Vector3d(frame.half_width, half.x(), half.y());
  return box;
}

}  // namespace hull::ui
