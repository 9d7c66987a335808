// The photomosaic's visibility stage (photomosaic_internal.h): which views
// see which faces. The rule is per (view, face) pair; what makes it fast is
// which pairs are looked at: only the faces whose centroid lies in a view's
// range ball (a k-d tree's radius search), and of those only the ones whose
// centroid the view's pinhole frustum holds get their corners projected
// and their rays cast. Both culls are conservative, so the result is the
// rule applied to every pair (tests/unit/mosaic: SeenFacesEqualsTheRuleOnEveryPair).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "geometry/point_index.h"
#include "mosaic/photomosaic_internal.h"

namespace hull {
namespace mosaic_internal {
std::array<Eigen::Vector3d, kSamples> FaceSamples(const TriangleMesh& m, int f) {
  const Face& F = m.faces[static_cast<std::size_t>(f)];
  const Eigen::Vector3d a = m.vertices[static_cast<std::size_t>(F[0])], b = m.vertices[static_cast<std::size_t>(F[1])],
                        c = m.vertices[static_cast<std::size_t>(F[2])];
  const Eigen::Vector3d g = (a + b + c) / 3.0;
  return {g, g + 0.85 * (a - g), g + 0.85 * (b - g), g + 0.85 * (c - g)};
}

Visibility SeenFaces(const TriangleMesh& model, const MeshIndex& index, const std::vector<MosaicCamera>& cameras,
                     int width, int height, const MosaicOptions& options, Progress& progress) {
  const std::size_t nf = model.num_faces();
  std::vector<Eigen::Vector3d> centroid(nf);
  for (std::size_t f = 0; f < nf; ++f) centroid[f] = model.FaceCentroid(static_cast<int>(f));
  // A k-d tree of the finite centroids (a degenerate face's is never within
  // range of anything); `face_of` maps the tree's points back to faces.
  std::vector<Eigen::Vector3d> finite;
  std::vector<int> face_of;
  finite.reserve(nf);
  face_of.reserve(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    if (!centroid[f].allFinite()) continue;
    finite.push_back(centroid[f]);
    face_of.push_back(static_cast<int>(f));
  }
  const PointIndex near_index(std::move(finite));
  const double cos_max = std::cos(options.max_incidence_deg * M_PI / 180.0);
  const double margin = options.image_margin;
  const int nviews = static_cast<int>(cameras.size());
  Visibility out;
  out.seen.resize(cameras.size());
  std::atomic<std::size_t> near{0}, projected{0}, rays{0};
  tbb::parallel_for(0, nviews, [&](int vi) {
    if (progress.Cancelled()) return;
    const MosaicCamera& cam = cameras[static_cast<std::size_t>(vi)];
    const Eigen::Vector3d o = cam.centre();
    const Eigen::Matrix3d Rt = cam.x_Mc().rotation().transpose();
    const PinholeIntrinsics& k = cam.intrinsics();
    // In the tree's order: `pass` is sorted by face below.
    const std::vector<std::pair<int, double>> faces = near_index.Within(o, options.max_range, false);
    std::vector<std::pair<int, float>> pass;
    std::vector<Eigen::Vector3d> points;
    std::size_t tested = 0;
    for (const auto& in_range : faces) {
      const int fi = face_of[static_cast<std::size_t>(in_range.first)];
      const auto f = static_cast<std::size_t>(fi);
      const Eigen::Vector3d& g = centroid[f];
      const Eigen::Vector3d to = o - g;
      const double d = to.norm();
      if (!(d > 1e-6 && d <= options.max_range)) continue;
      const double cosi = model.face_normals[f].dot(to) / d;
      if (cosi < cos_max) continue;
      // Frustum cull on the centroid: a pinhole maps the triangle (in front
      // of the camera) onto the triangle of its corners' pixels, so when
      // the corners are inside the margin, so is the centroid. One pixel of
      // slack for x_Mc against the adjustment's chain of rotations.
      const Eigen::Vector3d pc = Rt * (g - o);
      if (!(pc.z() > 0)) continue;
      const double u = k.fx * pc.x() / pc.z() + k.cx, v = k.fy * pc.y() / pc.z() + k.cy;
      constexpr double kSlack = 1.0;
      if (!(u >= margin - kSlack && v >= margin - kSlack && u <= width - 1 - margin + kSlack &&
            v <= height - 1 - margin + kSlack)) {
        continue;
      }
      ++tested;
      bool in_image = true;
      for (int i = 0; i < 3 && in_image; ++i) {
        Eigen::Vector2d uv;
        in_image = cam.Project(model.vertices[static_cast<std::size_t>(model.faces[f][i])], &uv) && uv.x() >= margin &&
                   uv.y() >= margin && uv.x() <= width - 1 - margin && uv.y() <= height - 1 - margin;
      }
      if (!in_image) continue;
      pass.emplace_back(fi, static_cast<float>(cosi / (d * d)));
    }
    std::sort(pass.begin(), pass.end());  // the list (and the rays) in face order
    for (const auto& fs : pass) {
      for (const Eigen::Vector3d& p : FaceSamples(model, fs.first)) points.push_back(p);
    }
    std::unique_ptr<bool[]> blocked(new bool[points.size() + 1]);
    index.OccludedToward(points.data(), static_cast<int>(points.size()), o, 1e-3, blocked.get());
    auto& seen = out.seen[static_cast<std::size_t>(vi)];
    for (std::size_t i = 0; i < pass.size(); ++i) {
      bool free = true;
      for (int s = 0; s < kSamples; ++s) free = free && !blocked[i * kSamples + static_cast<std::size_t>(s)];
      if (free) seen.push_back(pass[i]);
    }
    near += faces.size();
    projected += tested;
    rays += points.size();
  });
  out.near = near;
  out.projected = projected;
  out.rays = rays;
  return out;
}

}  // namespace mosaic_internal
}  // namespace hull
