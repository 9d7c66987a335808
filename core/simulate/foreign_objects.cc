#include "simulate/foreign_objects.h"

#include <algorithm>
#include <cmath>

#include "simulate/random.h"

namespace hull {
namespace {

// Orthonormal frame (e1, e2, n) with e1 as close as possible to `forward`.
void TangentFrame(const Eigen::Vector3d& n, const Eigen::Vector3d& forward, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
  e1 = forward - forward.dot(n) * n;
  if (e1.norm() < 1e-6) e1 = n.unitOrthogonal();
  e1.normalize();
  e2 = n.cross(e1);
}

// Adds a closed "extruded heightfield" over a star-shaped footprint: the top
// surface z = top(rho, phi) over rings, a vertical skirt at the rim down to
// -sink, and a flat bottom cap. rim(phi) is the footprint radius.
template <typename Top, typename Rim>
void AddHeightfield(TriangleMesh& m, const Eigen::Vector3d& c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                    const Eigen::Vector3d& n, int rings, int sectors, double sink, Top top, Rim rim) {
  auto at = [&](double rho, double phi, double h) {
    const double r = rho * rim(phi);
    return Eigen::Vector3d(c + r * std::cos(phi) * e1 + r * std::sin(phi) * e2 + h * n);
  };
  const int centre = static_cast<int>(m.vertices.size());
  m.vertices.push_back(c + top(0.0, 0.0) * n);
  // Ring k = 1..rings of the top surface.
  for (int k = 1; k <= rings; ++k) {
    const double rho = static_cast<double>(k) / rings;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2 * M_PI * s / sectors;
      m.vertices.push_back(at(rho, phi, top(rho, phi)));
    }
  }
  auto ringv = [&](int k, int s) { return centre + 1 + (k - 1) * sectors + (s % sectors); };
  for (int s = 0; s < sectors; ++s) m.faces.push_back({centre, ringv(1, s), ringv(1, s + 1)});
  for (int k = 1; k < rings; ++k) {
    for (int s = 0; s < sectors; ++s) {
      m.faces.push_back({ringv(k, s), ringv(k + 1, s), ringv(k + 1, s + 1)});
      m.faces.push_back({ringv(k, s), ringv(k + 1, s + 1), ringv(k, s + 1)});
    }
  }
  // Skirt: rim at the top surface down to -sink.
  const int low = static_cast<int>(m.vertices.size());
  for (int s = 0; s < sectors; ++s) m.vertices.push_back(at(1.0, 2 * M_PI * s / sectors, -sink));
  for (int s = 0; s < sectors; ++s) {
    const int t0 = ringv(rings, s), t1 = ringv(rings, s + 1);
    const int b0 = low + s, b1 = low + (s + 1) % sectors;
    m.faces.push_back({t0, b0, b1});
    m.faces.push_back({t0, b1, t1});
  }
  // Bottom cap.
  const int bc = static_cast<int>(m.vertices.size());
  m.vertices.push_back(c - sink * n);
  for (int s = 0; s < sectors; ++s) m.faces.push_back({bc, low + (s + 1) % sectors, low + s});
}

}  // namespace

TriangleMesh MakeObjectMesh(const TrueObject& o, std::uint64_t seed, double sink) {
  TriangleMesh m;
  const Eigen::Vector3d n = o.normal.normalized();
  Eigen::Vector3d e1, e2;
  TangentFrame(n, Eigen::Vector3d::UnitX(), e1, e2);
  switch (o.kind) {
    case ObjectKind::kCylinder: {
      const double h = o.height, r = o.radius;
      AddHeightfield(
          m, o.center, e1, e2, n, 2, 48, sink, [h](double, double) { return h; }, [r](double) { return r; });
      break;
    }
    case ObjectKind::kBox: {
      const double a = 0.5 * o.size.x(), b = 0.5 * o.size.y(), h = o.size.z();
      const double zs[2] = {-sink, h};
      for (int k = 0; k < 2; ++k) {
        for (int s = 0; s < 4; ++s) {
          const double u = (s == 0 || s == 3) ? -a : a;
          const double v = (s < 2) ? -b : b;
          m.vertices.push_back(o.center + u * e1 + v * e2 + zs[k] * n);
        }
      }
      const Face faces[12] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                              {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
      m.faces.assign(std::begin(faces), std::end(faces));
      break;
    }
    case ObjectKind::kPatch: {
      Rng rng(seed);
      const double h = o.height, r = o.radius;
      double amp[3], ph[3];
      for (int i = 0; i < 3; ++i) {
        amp[i] = rng.Uniform(0.05, 0.15);
        ph[i] = rng.Uniform(0, 2 * M_PI);
      }
      const double rim_ph = rng.Uniform(0, 2 * M_PI);
      // Every other clump (drawn last, so the others keep their shapes) has
      // a narrow peak: a cone-like top (1 - rho^2)^3, the top centimetre of
      // it a few centimetres across (a tube-worm tuft), which a fusion that
      // averages its hits flattens.
      const bool narrow = rng.Uniform() < 0.5;
      // A lumpy clump (barnacles, tube worms): a broad top falling off
      // steeply toward the rim, with lobes; rho^2 keeps the centre exactly
      // at height h, which is the highest point.
      auto top = [=](double rho, double phi) {
        double lobes = 1.0;
        for (int i = 0; i < 3; ++i) lobes += amp[i] * std::sin((i + 2) * phi + ph[i]);
        const double r2 = rho * rho;
        const double shape = narrow ? std::pow(1.0 - r2, 3.0) : std::pow(std::max(0.0, 1.0 - r2 * r2), 1.5);
        return h * shape * (1.0 + 0.5 * (lobes - 1.0) * r2 * r2);
      };
      auto rim = [=](double phi) { return r * (0.85 + 0.15 * std::sin(2 * phi + rim_ph)); };
      // Narrow peaks get finer rings near the centre.
      AddHeightfield(m, o.center, e1, e2, n, narrow ? 16 : 8, 32, sink, top, rim);
      break;
    }
  }
  m.OrientOutward();
  return m;
}

TrueObject PlaceObject(const MeshIndex& cad, std::string id, ObjectKind kind, const Eigen::Vector3d& near,
                       double radius, double height, const Eigen::Vector3d& box_size) {
  TrueObject o;
  o.id = std::move(id);
  o.kind = kind;
  const ClosestPoint cp = cad.Closest(near);
  o.center = cp.point;
  o.normal = cad.mesh().face_normals[static_cast<std::size_t>(cp.face)];
  if (kind == ObjectKind::kBox) {
    o.size = box_size;
    o.height = box_size.z();
    o.radius = 0.5 * std::hypot(box_size.x(), box_size.y());
  } else {
    o.radius = radius;
    o.height = height;
  }
  return o;
}

std::vector<TrueObject> PlacePatchStrip(const MeshIndex& cad, const std::string& prefix, const Eigen::Vector3d& from,
                                        const Eigen::Vector3d& to, double r_min, double r_max, double h_min,
                                        double h_max, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<TrueObject> out;
  const double length = (to - from).norm();
  double s = 0;
  int k = 1;
  while (s <= length) {
    const double r = rng.Uniform(r_min, r_max);
    const double h = rng.Uniform(h_min, h_max);
    const Eigen::Vector3d p = from + (length > 0 ? s / length : 0.0) * (to - from);
    out.push_back(PlaceObject(cad, prefix + "-" + std::to_string(k++), ObjectKind::kPatch, p, r, h));
    s += rng.Uniform(1.1, 1.5) * r;  // overlapping neighbours: a continuous strip
  }
  return out;
}

}  // namespace hull
