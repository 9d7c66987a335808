#include "ui/report/figure_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mapping/mapping_options.h"
#include "registration/dvl_points.h"

namespace hull::report {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

Eigen::Vector3d FaceNormal(const TriangleMesh& mesh, int f) {
  if (mesh.face_normals.size() == mesh.faces.size()) return mesh.face_normals[f];
  const Face& t = mesh.faces[f];
  const Eigen::Vector3d n =
      (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

}  // namespace

HullFrame ReportHullFrame(const ReportInputs& in) {
  if (in.mapping) return in.mapping->hull;
  const MappingOptions defaults;
  return MakeHullFrame(*in.cad, in.bundle->manifest.model_axes, Pose::FromVector(in.pipeline->adjustment.x_gM),
                       defaults.stations, defaults.bottom_angle_deg);
}

const char* HullViewName(HullView v) {
  switch (v) {
    case HullView::kBottom:
      return "bottom";
    case HullView::kPort:
      return "port";
    case HullView::kStarboard:
      return "starboard";
  }
  return "?";
}

ViewBasis MakeViewBasis(const HullFrame& hull, HullView view) {
  // Right-handed screens: right x up = toward the viewer.
  switch (view) {
    case HullView::kBottom:
      return {hull.forward(), -hull.port(), -hull.up()};
    case HullView::kPort:
      return {-hull.forward(), hull.up(), hull.port()};
    case HullView::kStarboard:
      return {hull.forward(), hull.up(), -hull.port()};
  }
  return {hull.forward(), hull.up(), -hull.port()};
}

std::vector<ProjectedTriangle> ProjectMesh(const TriangleMesh& mesh, const ViewBasis& view,
                                           const std::vector<double>* values, const std::vector<double>* valued_mask,
                                           const std::optional<Eigen::AlignedBox2d>& window) {
  const std::size_t nv = mesh.vertices.size();
  if (values && values->size() != nv) values = nullptr;
  if (valued_mask && valued_mask->size() != nv) valued_mask = nullptr;
  std::vector<Eigen::Vector2d> projected(nv);
  std::vector<double> depth(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    projected[i] = view.Project(mesh.vertices[i]);
    depth[i] = view.Depth(mesh.vertices[i]);
  }
  std::vector<ProjectedTriangle> out;
  out.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    ProjectedTriangle p;
    p.face = static_cast<int>(f);
    Eigen::AlignedBox2d box;
    for (int k = 0; k < 3; ++k) {
      p.corner[k] = projected[t[k]];
      box.extend(p.corner[k]);
    }
    if (window && !window->intersects(box)) continue;
    p.depth = (depth[t[0]] + depth[t[1]] + depth[t[2]]) / 3;
    p.facing = FaceNormal(mesh, static_cast<int>(f)).dot(view.toward_viewer);
    if (values) {
      p.valued = !valued_mask || ((*valued_mask)[t[0]] > 0 && (*valued_mask)[t[1]] > 0 && (*valued_mask)[t[2]] > 0);
      p.value = ((*values)[t[0]] + (*values)[t[1]] + (*values)[t[2]]) / 3;
    }
    out.push_back(p);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ProjectedTriangle& a, const ProjectedTriangle& b) { return a.depth < b.depth; });
  return out;
}

std::vector<Eigen::AlignedBox2d> PlaceLabels(const Eigen::AlignedBox2d& bounds,
                                             const std::vector<Eigen::Vector2d>& anchors,
                                             const std::vector<Eigen::Vector2d>& sizes) {
  constexpr double kGap = 10, kAbove = 22, kBelow = 8, kStep = 3, kAnchorMargin = 3, kAnchorCost = 50, kSpacing = 2;
  constexpr int kRings = 8;
  std::vector<Eigen::AlignedBox2d> placed;
  placed.reserve(anchors.size());
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const Eigen::Vector2d& at = anchors[i];
    const double w = sizes[i].x(), h = sizes[i].y();
    Eigen::AlignedBox2d best;
    double least = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring < kRings && least > 0; ++ring) {
      const double up = -kAbove - ring * (h + kStep), down = kBelow + ring * (h + kStep);
      for (const Eigen::Vector2d& off : {Eigen::Vector2d(kGap, up), Eigen::Vector2d(kGap, down),
                                         Eigen::Vector2d(-kGap - w, up), Eigen::Vector2d(-kGap - w, down)}) {
        const Eigen::AlignedBox2d box(at + off, at + off + Eigen::Vector2d(w, h));
        double overlap = bounds.contains(box) ? 0.0 : 1e9;
        for (const Eigen::AlignedBox2d& o : placed) {
          // Labels keep kSpacing apart: touching boxes read as one.
          const Eigen::AlignedBox2d both = Eigen::AlignedBox2d(o.min() - Eigen::Vector2d::Constant(kSpacing),
                                                               o.max() + Eigen::Vector2d::Constant(kSpacing))
                                               .intersection(box);
          if (!both.isEmpty()) overlap += std::max(both.volume(), 1.0);
        }
        const Eigen::AlignedBox2d widened(box.min() - Eigen::Vector2d::Constant(kAnchorMargin),
                                          box.max() + Eigen::Vector2d::Constant(kAnchorMargin));
        for (const Eigen::Vector2d& a : anchors) {
          if (widened.contains(a)) overlap += kAnchorCost;
        }
        if (overlap < least) {
          least = overlap;
          best = box;
          if (least == 0) break;
        }
      }
    }
    placed.push_back(best);
  }
  return placed;
}

Eigen::AlignedBox2d ProjectedBounds(const TriangleMesh& mesh, const ViewBasis& view) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(view.Project(v));
  return box;
}

std::vector<PlacedLandmark> LandmarksInModel(const AdjustmentResult& result) {
  const Pose x_Mg = Pose::FromVector(result.x_gM).Inverse();
  std::vector<PlacedLandmark> out;
  out.reserve(result.landmarks.size());
  for (const LandmarkEstimate& l : result.landmarks) out.push_back({x_Mg * l.p, l.deviation, l.label});
  return out;
}

std::vector<Eigen::Vector3d> DvlReturnsInModel(const SurveyBundle& bundle, const AdjustmentResult& result) {
  std::vector<Pose> x_gv(bundle.nav.size());
  std::vector<double> servo(bundle.nav.size());
  for (std::size_t i = 0; i < bundle.nav.size(); ++i) {
    x_gv[i] = Pose::FromVector(bundle.nav[i].x_gv);
    servo[i] = bundle.nav[i].servo;
  }
  const auto index = bundle.KeyframeIndex();
  for (std::size_t k = 0; k < result.keyframes.size() && k < result.poses.size(); ++k) {
    const auto it = index.find(result.keyframes[k]);
    if (it == index.end()) continue;
    x_gv[it->second] = Pose::FromVector(result.poses[k]);
    if (k < result.servo.size()) servo[it->second] = result.servo[k];
  }
  const Pose x_Mg = Pose::FromVector(result.x_gM).Inverse();
  std::vector<Eigen::Vector3d> out;
  for (const DvlPoint& d : DvlPointsInG(bundle, x_gv, servo)) out.push_back(x_Mg * d.point);
  return out;
}

Eigen::Vector2d SectionCoordinates(const HullFrame& hull, const Eigen::Vector3d& p_m) {
  return {p_m.dot(hull.port()), p_m.dot(hull.up())};
}

std::vector<Segment2> SliceMesh(const TriangleMesh& mesh, const HullFrame& hull, double from_bow) {
  std::vector<Segment2> out;
  std::vector<double> d(mesh.vertices.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    d[i] = hull.DistanceFromBow(mesh.vertices[i]) - from_bow;
    if (d[i] == 0) d[i] = 1e-12;  // a vertex on the plane counts as aft of it: no doubled segments
  }
  for (const Face& t : mesh.faces) {
    Eigen::Vector2d cut[2];
    int n = 0;
    for (int k = 0; k < 3 && n < 2; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if ((d[a] < 0) == (d[b] < 0)) continue;
      const double s = d[a] / (d[a] - d[b]);
      cut[n++] = SectionCoordinates(hull, mesh.vertices[a] + s * (mesh.vertices[b] - mesh.vertices[a]));
    }
    if (n == 2) out.push_back({cut[0], cut[1]});
  }
  return out;
}

namespace {

// The slab's centre and the close-up's subject when the options leave them open.
void ChooseSlab(const ReportInputs& in, const HullFrame& hull, const ReportOptions& options, CrossSection& cs) {
  const bool given = std::isfinite(options.slab_from_bow);
  if (in.mapping && !in.mapping->objects.empty()) {
    const DetectedObject* best = nullptr;
    for (const DetectedObject& o : in.mapping->objects) {
      if (given) {
        if (!best || std::abs(o.distance_from_bow - options.slab_from_bow) <
                         std::abs(best->distance_from_bow - options.slab_from_bow)) {
          best = &o;
        }
      } else if (!best || o.num_features > best->num_features ||
                 (o.num_features == best->num_features && o.area > best->area)) {
        best = &o;
      }
    }
    cs.from_bow = given ? options.slab_from_bow : best->distance_from_bow;
    if (std::abs(best->distance_from_bow - cs.from_bow) <= std::max(cs.width, 0.5)) {
      cs.focus = best->id;
      cs.focus_point = SectionCoordinates(hull, best->centroid_m);
      return;
    }
  }
  // Without detected objects: the landmarks the adjustment put off the hull
  // (or all of them), their median station and section position.
  const std::vector<PlacedLandmark> marks = LandmarksInModel(in.pipeline->adjustment);
  std::vector<double> along, along_off;
  for (const PlacedLandmark& l : marks) {
    const double s = hull.DistanceFromBow(l.p_m);
    along.push_back(s);
    if (l.label == 0) along_off.push_back(s);
  }
  if (!given) cs.from_bow = Median(along_off.size() >= 3 ? along_off : along);
  std::vector<double> x, y, x_off, y_off;
  for (const PlacedLandmark& l : marks) {
    if (std::abs(hull.DistanceFromBow(l.p_m) - cs.from_bow) > cs.width / 2) continue;
    const Eigen::Vector2d p = SectionCoordinates(hull, l.p_m);
    x.push_back(p.x());
    y.push_back(p.y());
    if (l.label == 0) {
      x_off.push_back(p.x());
      y_off.push_back(p.y());
    }
  }
  if (!x_off.empty()) {
    cs.focus_point = {Median(x_off), Median(y_off)};
  } else if (!x.empty()) {
    cs.focus_point = {Median(x), Median(y)};
  }
}

}  // namespace

CrossSection BuildCrossSection(const ReportInputs& in, const HullFrame& hull, const ReportOptions& options) {
  CrossSection cs;
  cs.width = options.slab_width > 0 ? options.slab_width : 0.3;
  cs.decision_boundary = in.pipeline->adjustment.options.DecisionBoundary();
  ChooseSlab(in, hull, options, cs);
  cs.cad = SliceMesh(*in.cad, hull, cs.from_bow);
  for (const Segment2& s : cs.cad) {
    cs.hull_box.extend(s.a);
    cs.hull_box.extend(s.b);
  }
  const auto in_slab = [&](const Eigen::Vector3d& p) {
    return std::abs(hull.DistanceFromBow(p) - cs.from_bow) <= cs.width / 2;
  };
  for (const AdjustmentResult* r : ModelsInOrder(*in.pipeline)) {
    SectionModel m;
    m.model = r->options.model;
    for (const PlacedLandmark& l : LandmarksInModel(*r)) {
      if (!in_slab(l.p_m)) continue;
      // The max-mixture's own label (with the cavity E-step a feature just
      // inside the boundary may be off); the baselines have none: their
      // features are coloured by the boundary, where the max-mixture would
      // put them.
      const bool off =
          r->options.model == SurfaceModel::kMaxMixture ? l.label == 0 : std::abs(l.deviation) > cs.decision_boundary;
      m.features.push_back({SectionCoordinates(hull, l.p_m), l.deviation, off});
      cs.data_box.extend(m.features.back().p);
    }
    for (const Eigen::Vector3d& p : DvlReturnsInModel(*in.bundle, *r)) {
      if (!in_slab(p)) continue;
      m.dvl.push_back(SectionCoordinates(hull, p));
      cs.data_box.extend(m.dvl.back());
    }
    if (in.mapping && r == &in.pipeline->adjustment) m.fused = SliceMesh(in.mapping->model, hull, cs.from_bow);
    cs.models.push_back(std::move(m));
  }
  return cs;
}

int Histogram::Max() const {
  int m = 0;
  for (int c : counts) m = std::max(m, c);
  return m;
}

Histogram MakeHistogram(const std::vector<double>& values, double lo, double hi, int bins) {
  Histogram h;
  h.lo = lo;
  h.hi = hi;
  h.counts.assign(static_cast<std::size_t>(std::max(1, bins)), 0);
  const double w = (hi - lo) / h.counts.size();
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++h.total;
    if (v < lo) {
      ++h.below;
    } else if (v >= hi) {
      ++h.above;
    } else {
      const auto b = std::min(h.counts.size() - 1, static_cast<std::size_t>((v - lo) / w));
      ++h.counts[b];
    }
  }
  return h;
}

std::vector<const AdjustmentResult*> ModelsInOrder(const PipelineResult& result) {
  std::vector<const AdjustmentResult*> out{&result.adjustment};
  for (const AdjustmentResult& b : result.baselines) out.push_back(&b);
  std::stable_sort(out.begin(), out.end(), [](const AdjustmentResult* a, const AdjustmentResult* b) {
    return static_cast<int>(a->options.model) < static_cast<int>(b->options.model);
  });
  return out;
}

}  // namespace hull::report
