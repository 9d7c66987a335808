#include "simulate/hull_forms.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace hull {

void HullFormOptions::Check() const {
  if (!(length > 0)) throw OptionError("length", "must be positive");
  if (!(beam > 0)) throw OptionError("beam", "must be positive");
  if (!(draft > 0 && draft < depth)) throw OptionError("draft", "must be positive and less than depth");
  if (!(bilge_radius > 0 && bilge_radius < beam / 2 && bilge_radius < draft)) {
    throw OptionError("bilge_radius", "must be positive and less than the half-beam and the draft");
  }
  if (!(midbody_start > 0 && midbody_start < midbody_end && midbody_end < 1)) {
    throw OptionError("midbody_start/midbody_end", "must satisfy 0 < start < end < 1");
  }
  if (!(end_half_breadth > 0 && end_half_breadth <= 1)) throw OptionError("end_half_breadth", "must be in (0, 1]");
  if (!(stern_rise >= 0 && bow_rise >= 0 && stern_rise < draft && bow_rise < draft)) {
    throw OptionError("stern_rise/bow_rise", "must be in [0, draft)");
  }
  if (!(station_spacing > 0 && station_spacing <= length / 4)) {
    throw OptionError("station_spacing", "must be positive and at most a quarter of the length");
  }
  if (bottom_points < 2 || bilge_points < 2 || side_points < 2 || deck_points < 1) {
    throw OptionError("points", "each section segment needs at least 2 samples (deck 1)");
  }
}

namespace {

// Half-breadth scale s(x) in [end, 1] and keel height at station x.
struct Station {
  double scale;
  double keel;
};

Station StationAt(const HullFormOptions& o, double x) {
  const double L = o.length;
  const double xs = o.midbody_start * L, xb = o.midbody_end * L;
  Station st{1.0, 0.0};
  if (x < xs) {
    const double f = (xs - x) / xs;  // 0 at midbody, 1 at the aft end
    st.scale = 1.0 - (1.0 - o.end_half_breadth) * std::pow(f, 2.0);
    st.keel = o.stern_rise * std::pow(f, 3.0);
  } else if (x > xb) {
    const double f = (x - xb) / (L - xb);  // 0 at midbody, 1 at the stem
    st.scale = 1.0 - (1.0 - o.end_half_breadth) * std::pow(f, 1.7);
    st.keel = o.bow_rise * std::pow(f, 4.0);
  }
  return st;
}

// Starboard half-section from the keel centreline up to the deck centreline,
// as (y, z) with y <= 0 (starboard is -y in M).
std::vector<Eigen::Vector2d> HalfSection(const HullFormOptions& o, const Station& st) {
  std::vector<Eigen::Vector2d> pts;
  const double half = 0.5 * o.beam * st.scale;
  const double r = std::min(o.bilge_radius * st.scale, 0.9 * (o.depth - st.keel));
  const double flat = std::max(half - r, 0.0);
  // Flat bottom (flat keel at y = 0).
  for (int i = 0; i < o.bottom_points; ++i) {
    pts.emplace_back(-flat * i / o.bottom_points, st.keel);
  }
  // Bilge arc, centre (-flat, keel + r), from straight down to horizontal.
  for (int i = 0; i < o.bilge_points; ++i) {
    const double a = -M_PI / 2 - (M_PI / 2) * i / o.bilge_points;  // -90 .. -180 deg
    pts.emplace_back(-flat + r * std::cos(a), st.keel + r + r * std::sin(a));
  }
  // Side, from the top of the bilge to the deck.
  const double z0 = st.keel + r;
  for (int i = 0; i < o.side_points; ++i) {
    pts.emplace_back(-half, z0 + (o.depth - z0) * i / o.side_points);
  }
  // Deck towards the centreline (the centreline point itself belongs to the port half).
  for (int i = 0; i < o.deck_points; ++i) {
    pts.emplace_back(-half + half * i / o.deck_points, o.depth);
  }
  return pts;
}

}  // namespace

TriangleMesh MakeParametricHull(const HullFormOptions& o) {
  o.Check();
  const int nst = std::max(2, static_cast<int>(std::ceil(o.length / o.station_spacing)) + 1);
  TriangleMesh mesh;
  int ring = -1;
  for (int s = 0; s < nst; ++s) {
    const double x = o.length * s / (nst - 1);
    const Station st = StationAt(o, x);
    const auto half = HalfSection(o, st);
    // Full loop: starboard half (keel -> deck), then port half mirrored (deck -> keel).
    std::vector<Eigen::Vector2d> loop = half;
    loop.emplace_back(0.0, o.depth);
    for (int i = static_cast<int>(half.size()) - 1; i >= 1; --i) loop.emplace_back(-half[i].x(), half[i].y());
    ring = static_cast<int>(loop.size());
    for (const auto& p : loop) mesh.vertices.emplace_back(x, p.x(), p.y());
  }
  // Quad strips between consecutive sections.
  for (int s = 0; s + 1 < nst; ++s) {
    const int a = s * ring, b = (s + 1) * ring;
    for (int i = 0; i < ring; ++i) {
      const int j = (i + 1) % ring;
      mesh.faces.push_back({a + i, b + i, b + j});
      mesh.faces.push_back({a + i, b + j, a + j});
    }
  }
  // End caps: fans from the section centroid (sections are convex).
  for (int end = 0; end < 2; ++end) {
    const int base = end == 0 ? 0 : (nst - 1) * ring;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = 0; i < ring; ++i) c += mesh.vertices[base + i];
    c /= ring;
    const int ci = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(c);
    for (int i = 0; i < ring; ++i) {
      const int j = (i + 1) % ring;
      if (end == 0)
        mesh.faces.push_back({ci, base + j, base + i});
      else
        mesh.faces.push_back({ci, base + i, base + j});
    }
  }
  mesh.OrientOutward();
  return mesh;
}

}  // namespace hull
