#include "mapping/inspection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "geometry/point_index.h"
#include "mapping/point_cone_tree.h"
#include "mapping/surface_clip.h"

namespace hull {
namespace {

// A sample counts as unoccluded when the CAD's first hit along the camera's
// ray lies no nearer than this before it.
constexpr double kOcclusionTolerance = 0.02;

}  // namespace

std::vector<double> ZoneAreas(const TriangleMesh& cad, const HullFrame& hull) {
  std::vector<double> area(static_cast<std::size_t>(hull.num_zones()), 0.0);
  const double step = hull.station_length();
  for (std::size_t f = 0; f < cad.num_faces(); ++f) {
    const HullSide side = hull.Side(cad.face_normals[f]);
    if (side == HullSide::kNone) continue;
    const Face& F = cad.faces[f];
    double lo = 1e300, hi = -1e300;
    for (const int v : F) {
      const double s = hull.DistanceFromBow(cad.vertices[static_cast<std::size_t>(v)]);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
    const int k0 = std::clamp(static_cast<int>(std::floor(lo / step)), 0, hull.stations() - 1);
    const int k1 = std::clamp(static_cast<int>(std::floor(hi / step)), 0, hull.stations() - 1);
    for (int k = k0; k <= k1; ++k) {
      ClipPolygon poly;
      for (const int v : F) poly.push_back({cad.vertices[static_cast<std::size_t>(v)], 0.0});
      // Station k holds distances in [k step, (k + 1) step); the first and the
      // last also what lies beyond the ends.
      if (k > 0) ClipKeep(poly, [&](const ClipVertex& c) { return hull.DistanceFromBow(c.p) - k * step; });
      if (k < hull.stations() - 1) {
        ClipKeep(poly, [&](const ClipVertex& c) { return (k + 1) * step - hull.DistanceFromBow(c.p); });
      }
      area[static_cast<std::size_t>(HullFrame::ZoneIndex(k, side))] += Moments(poly).area;
    }
  }
  return area;
}

InspectionCoverage MeasureInspection(const TriangleMesh& cad, const MeshIndex& cad_index, const HullFrame& hull,
                                     const std::vector<Pose>& x_M_cT, const CameraRig& camera, double spacing,
                                     double range, Progress& progress) {
  InspectionCoverage out;
  out.hull_area = ZoneAreas(cad, hull);
  out.inspected_area.assign(out.hull_area.size(), 0.0);
  for (const double a : out.hull_area) out.total_hull_area += a;
  if (x_M_cT.empty()) return out;

  // Samples on the faces within reach of some camera: sub-triangle centroids
  // of an m x m barycentric subdivision, each standing for area / m^2.
  std::vector<Eigen::Vector3d> centres;
  centres.reserve(x_M_cT.size());
  for (const auto& c : x_M_cT) centres.push_back(c.translation());
  const PointIndex cameras(std::move(centres));
  std::vector<Eigen::Vector3d> pos;
  std::vector<float> weight;
  std::vector<int> face_of, zone_of;
  for (std::size_t f = 0; f < cad.num_faces(); ++f) {
    const HullSide side = hull.Side(cad.face_normals[f]);
    if (side == HullSide::kNone) continue;
    const Face& F = cad.faces[f];
    const Eigen::Vector3d &a = cad.vertices[static_cast<std::size_t>(F[0])],
                          &b = cad.vertices[static_cast<std::size_t>(F[1])],
                          &c = cad.vertices[static_cast<std::size_t>(F[2])];
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    const double reach = std::max({(a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm()});
    if (cameras.NearestOne(centroid).second > (range + reach) * (range + reach)) continue;
    const double area = cad.FaceArea(static_cast<int>(f));
    const int m = std::max(1, static_cast<int>(std::ceil(std::sqrt(area) / spacing)));
    const double w = area / (static_cast<double>(m) * m);
    const Eigen::Vector3d u = (b - a) / m, v = (c - a) / m;
    auto add = [&](const Eigen::Vector3d& p) {
      pos.push_back(p);
      weight.push_back(static_cast<float>(w));
      face_of.push_back(static_cast<int>(f));
      zone_of.push_back(HullFrame::ZoneIndex(hull.Station(p), side));
    };
    for (int i = 0; i < m; ++i) {
      for (int j = 0; i + j < m; ++j) {
        const Eigen::Vector3d o = a + static_cast<double>(i) * u + static_cast<double>(j) * v;
        add(o + (u + v) / 3.0);                             // "upright" sub-triangle
        if (i + j < m - 1) add(o + u + v - (u + v) / 3.0);  // "inverted" sub-triangle
      }
    }
  }
  out.samples = pos.size();
  progress.ThrowIfCancelled();
  const PointConeTree tree(pos);

  // The image's bounding cone (from the corners of the outermost pixels).
  const PinholeIntrinsics& k = camera.top;
  const double hx = std::max(k.cx + 0.5, camera.width - 0.5 - k.cx) / k.fx;
  const double hy = std::max(k.cy + 0.5, camera.height - 0.5 - k.cy) / k.fy;
  const double half = std::atan(std::hypot(hx, hy)) + 1e-6;
  const bool narrow = half < 80.0 * M_PI / 180.0;
  std::unique_ptr<std::atomic<unsigned char>[]> seen(new std::atomic<unsigned char>[pos.size()]);
  for (std::size_t i = 0; i < pos.size(); ++i) seen[i].store(0, std::memory_order_relaxed);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, x_M_cT.size(), 32), [&](const tbb::blocked_range<std::size_t>& r) {
        if (progress.Cancelled()) return;
        for (std::size_t kf = r.begin(); kf != r.end(); ++kf) {
          const Pose& cam = x_M_cT[kf];
          const Pose inv = cam.Inverse();
          const Eigen::Vector3d& c = cam.translation();
          tree.Query(
              c, range, cam.Rotate(Eigen::Vector3d::UnitZ()), std::cos(half), std::sin(half), narrow, [&](int i) {
                if (seen[static_cast<std::size_t>(i)].load(std::memory_order_relaxed)) return;
                const Eigen::Vector3d& p = pos[static_cast<std::size_t>(i)];
                const Eigen::Vector3d d = p - c;
                const double dist = d.norm();
                if (!(dist <= range) || !(dist > 0)) return;
                if (!(cad.face_normals[static_cast<std::size_t>(face_of[static_cast<std::size_t>(i)])].dot(d) < 0))
                  return;
                const Eigen::Vector3d p_c = inv * p;
                if (!(p_c.z() > 0) || !camera.InImage(k.Project(p_c))) return;
                const RayHit h = cad_index.Raycast(c, d / dist, dist + kOcclusionTolerance);
                if (h.hit && h.range < dist - kOcclusionTolerance) return;
                seen[static_cast<std::size_t>(i)].store(1, std::memory_order_relaxed);
              });
        }
      });
  progress.ThrowIfCancelled();
  for (std::size_t i = 0; i < pos.size(); ++i) {
    if (!seen[i].load(std::memory_order_relaxed)) continue;
    ++out.samples_seen;
    out.inspected_area[static_cast<std::size_t>(zone_of[i])] += weight[i];
  }
  for (std::size_t z = 0; z < out.inspected_area.size(); ++z) {
    out.inspected_area[z] = std::min(out.inspected_area[z], out.hull_area[z]);
    out.total_inspected_area += out.inspected_area[z];
  }
  return out;
}

}  // namespace hull
