#include "simulate/surface_albedo.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace hull {
namespace {

inline float Smoothstep(float a, float b, float x) {
  const float t = std::min(std::max((x - a) / (b - a), 0.0f), 1.0f);
  return t * t * (3 - 2 * t);
}
inline float Mix(float a, float b, float t) { return a + t * (b - a); }
inline float Fract(float x) { return x - static_cast<float>(GradientNoise::Floor(x)); }
// Distance from x to the nearest integer.
inline float DistanceToInteger(float x) {
  const float f = Fract(x);
  return std::min(f, 1 - f);
}

// The shared octaves: wavelengths 0.96 m halving down to 7.5 mm, four
// channels each, weighted per channel (rows) and octave (columns).
constexpr int kOctaves = 8;
constexpr float kCoarsest = 0.96f;
// HullRow: the coarse octaves (0.96, 0.48, 0.24, 0.12 m) and the zones
// (3.84 m) computed exactly every kRowStep points and interpolated between
// where the two anchors are at most kRowSpan apart and the point within
// kRowOffset of the line between them. Over 1.5 cm the 0.12 m octave's
// curvature errs by at most ~8 % of its amplitude, 0.5 mm off the line by
// ~3 % (at the survey's 1.5 m the span is 6 pixels, about 9 mm: ~3 %).
constexpr int kCoarseOctaves = 4;
constexpr int kRowStep = 6;
constexpr float kRowSpan = 0.015f;
constexpr float kRowOffset = 0.0005f;
enum Channel { kBlotch = 0, kWear = 1, kTone = 2, kGrain = 3 };
constexpr float kWeights[4][kOctaves] = {
    {0.0f, 0.5f, 0.6f, 0.45f, 0.3f, 0.18f, 0.0f, 0.0f},  // biofilm blotches: 48 cm .. 3 cm
    {0.0f, 0.0f, 0.0f, 0.0f, 0.5f, 0.6f, 0.4f, 0.2f},    // abraded paint: 6 cm .. 7.5 mm
    {1.0f, 0.5f, 0.25f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},   // paint tone: 96 cm .. 24 cm
    {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.5f, 0.7f, 1.0f}};   // grain: 3 cm .. 7.5 mm
// Each channel scaled to the same spread (its weights' root sum of squares).
struct ChannelNorms {
  float n[4];
  ChannelNorms() {
    for (int c = 0; c < 4; ++c) {
      float s = 0;
      for (int k = 0; k < kOctaves; ++k) s += kWeights[c][k] * kWeights[c][k];
      n[c] = 1.0f / std::sqrt(s);
    }
  }
};
const ChannelNorms kNorms;

// A unit vector perpendicular to n (an object's local x).
Eigen::Vector3f Perpendicular(const Eigen::Vector3f& n) {
  Eigen::Vector3f e = Eigen::Vector3f::UnitX() - n.x() * n;
  if (e.norm() < 0.1f) e = Eigen::Vector3f::UnitY() - n.y() * n;
  return e.normalized();
}

}  // namespace

SurfaceMaterial MaterialOf(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kPatch:
      return SurfaceMaterial::kFouling;
    case ObjectKind::kCylinder:
      return SurfaceMaterial::kPaintedSteel;
    case ObjectKind::kBox:
      return SurfaceMaterial::kBareMetal;
  }
  return SurfaceMaterial::kFouling;
}

SurfaceAlbedo::SurfaceAlbedo(std::uint64_t seed, const Eigen::Vector3d& forward, const Eigen::Vector3d& up)
    : seed_(seed),
      forward_(forward.normalized()),
      up_(up.normalized()),
      noise_(seed * 3 + 1),
      coarse_(seed * 3 + 2),
      streaks_(seed * 3 + 3) {
  f_ = forward_.cast<float>();
  u_ = (up_ - up_.dot(forward_) * forward_).normalized().cast<float>();
  q_ = u_.cross(f_);
}

HI_NOISE_INLINE void SurfaceAlbedo::Layers(const float* px, const float* py, const float* pz, const float* footprint,
                                           int m, float (&layer)[4][kLanes]) const {
  for (auto& row : layer) std::fill(row, row + kLanes, 0.0f);
  Octaves(px, py, pz, footprint, m, 0, kOctaves, layer);
}

HI_NOISE_INLINE void SurfaceAlbedo::Octaves(const float* px, const float* py, const float* pz, const float* footprint,
                                            int m, int k0, int k1, float (&layer)[4][kLanes]) const {
  NoiseLattice L;
  float xs[kLanes], ys[kLanes], zs[kLanes], w[kLanes], cw[kLanes], inv[kLanes];
  // Octave weights from the reciprocal footprints (one division per point,
  // not per octave); the finest footprint decides where the octaves end.
  float finest = footprint[0];
  for (int i = 0; i < m; ++i) {
    inv[i] = 1.0f / footprint[i];  // +inf for footprint 0: every octave
    finest = std::min(finest, footprint[i]);
  }
  const float inv_finest = 1.0f / finest;
  float wavelength = kCoarsest;
  for (int k = 0; k < k0; ++k) wavelength *= 0.5f;
  for (int k = k0; k < k1; ++k, wavelength *= 0.5f) {
    if (OctaveWeightOfRatio(wavelength * inv_finest) == 0) break;  // finer octaves fade earlier still
    for (int i = 0; i < m; ++i) w[i] = OctaveWeightOfRatio(wavelength * inv[i]);
    const float s = 1.0f / wavelength, off = 17.31f * static_cast<float>(k);
    for (int i = 0; i < m; ++i) {
      xs[i] = px[i] * s + off;
      ys[i] = py[i] * s - off;
      zs[i] = pz[i] * s + 0.5f * off;
    }
    noise_.Locate(xs, ys, zs, m, L);
    for (int c = 0; c < 4; ++c) {
      if (kWeights[c][k] == 0) continue;
      const float cn = kWeights[c][k] * kNorms.n[c];
      for (int i = 0; i < m; ++i) cw[i] = w[i] * cn;
      L.Accumulate(c, cw, layer[c], m);
    }
  }
}

void SurfaceAlbedo::Layers(const Eigen::Vector3f& p, float footprint, float (&layer)[4]) const {
  float batch[4][kLanes];
  Layers(&p.x(), &p.y(), &p.z(), &footprint, 1, batch);
  for (int c = 0; c < 4; ++c) layer[c] = batch[c][0];
}

HI_NOISE_INLINE void SurfaceAlbedo::Coarse(const float* px, const float* py, const float* pz, const float* footprint,
                                           int m, float (&layer)[4][kLanes], float* zone) const {
  for (auto& row : layer) std::fill(row, row + kLanes, 0.0f);
  Octaves(px, py, pz, footprint, m, 0, kCoarseOctaves, layer);
  // Clean zones (about a fifth of the hull): fresh paint, little texture.
  NoiseLattice L;
  float xs[kLanes], ys[kLanes], zs[kLanes], ones[kLanes];
  std::fill(ones, ones + kLanes, 1.0f);
  std::fill(zone, zone + kLanes, 0.0f);
  for (int i = 0; i < m; ++i) {
    xs[i] = px[i] / 3.84f;
    ys[i] = py[i] / 3.84f;
    zs[i] = pz[i] / 3.84f;
  }
  coarse_.Locate(xs, ys, zs, m, L);
  L.Accumulate(0, ones, zone, m);
}

HI_NOISE_INLINE void SurfaceAlbedo::HullChunk(const float* px, const float* py, const float* pz, const float* nx,
                                              const float* ny, const float* nz, const float* footprint, int m,
                                              const float* const* coarse, float* out) const {
  float layer[4][kLanes], zone[kLanes];
  if (coarse) {  // the coarse octaves and zones given (coarse[4]: the zones)
    for (int c = 0; c < 4; ++c) std::copy(coarse[c], coarse[c] + m, layer[c]);
    std::copy(coarse[4], coarse[4] + m, zone);
  } else {
    Coarse(px, py, pz, footprint, m, layer, zone);
  }
  Octaves(px, py, pz, footprint, m, kCoarseOctaves, kOctaves, layer);
  NoiseLattice L;
  float xs[kLanes], ys[kLanes], zs[kLanes], ones[kLanes];
  std::fill(ones, ones + kLanes, 1.0f);

  // Hull coordinates: along the hull, and around its girth (across the
  // bottom, up the sides).
  float along[kLanes], girth[kLanes];
  const float fx = f_.x(), fy = f_.y(), fz = f_.z(), ux = u_.x(), uy = u_.y(), uz = u_.z(), qx = q_.x(), qy = q_.y(),
              qz = q_.z();
  for (int i = 0; i < m; ++i) {
    along[i] = px[i] * fx + py[i] * fy + pz[i] * fz;
    const float up_dot_n = std::abs(nx[i] * ux + ny[i] * uy + nz[i] * uz);
    const float port = px[i] * qx + py[i] * qy + pz[i] * qz;
    const float height = px[i] * ux + py[i] * uy + pz[i] * uz;
    const float bottom = static_cast<float>(up_dot_n > 0.6f);  // 1 on the bottom (and deck), 0 on the sides
    girth[i] = height + bottom * (port - height);
  }
  // Rust streaks along the flow (anisotropic: long along, thin across).
  float streak[kLanes] = {};
  for (int i = 0; i < m; ++i) {
    xs[i] = along[i] / 0.5f;
    ys[i] = girth[i] / 0.015f;
    zs[i] = 0.5f;
  }
  streaks_.Locate(xs, ys, zs, m, L);
  L.Accumulate(0, ones, streak, m);

  for (int i = 0; i < m; ++i) {
    const float z = zone[i];
    const float clean = Smoothstep(0.14f, 0.26f, z);
    const float dirty = 1 - clean;
    // Plates: longitudinal seams every 2 m of girth, butts every 3 m along,
    // staggered from strake to strake; each plate its own paint tone.
    const float g = girth[i] / 2.0f + 0.37f;
    const std::int32_t strake = GradientNoise::Floor(g);
    const float a = (along[i] + 1.1f * static_cast<float>(strake)) / 3.0f + 0.21f;
    const std::uint32_t plate =
        noise_.Hash(static_cast<std::uint32_t>(strake), static_cast<std::uint32_t>(GradientNoise::Floor(a)), 7u);
    const float plate_tone = static_cast<float>(static_cast<std::int32_t>(plate & 1023u)) / 1023.0f - 0.5f;
    float rho = 0.34f + 0.16f * layer[kTone][i] + 0.04f * plate_tone;
    // Biofilm blotches, darker.
    const float blotch = Smoothstep(0.02f, 0.10f, layer[kBlotch][i]) * dirty;
    rho = Mix(rho, 0.17f + 0.2f * layer[kTone][i], blotch);
    // Abraded anti-fouling: spots of the lighter primer.
    const float wear = Smoothstep(0.30f, 0.38f, layer[kWear][i] + 0.1f * z) * (1 - 0.7f * clean);
    rho = Mix(rho, 0.6f, wear);
    // Rust streaks.
    rho *= 1 - 0.25f * Smoothstep(0.3f, 0.55f, streak[i]) * OctaveWeight(0.015f, footprint[i]) * dirty;
    // Weld seams: a light bead in a darker heat-affected band, with ripple.
    const float weld = OctaveWeight(0.012f, footprint[i]);
    const float d = std::min(DistanceToInteger(g) * 2.0f, DistanceToInteger(a) * 3.0f) + 0.0075f * layer[kGrain][i];
    const float bead = 1 - Smoothstep(0.004f, 0.007f, d);
    const float heat = 1 - Smoothstep(0.007f, 0.02f, d);
    rho = Mix(rho, 0.75f * rho, heat * (1 - bead) * weld);
    rho = Mix(rho, 0.5f, 0.8f * bead * weld);
    // Fine grain of the paint and growth.
    rho *= 1 + (0.15f + 0.25f * dirty) * layer[kGrain][i];
    out[i] = std::min(std::max(rho, 0.03f), 0.9f);
  }
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
// Also compiled for AVX2 (8 lanes), chosen at run time where the CPU has it.
// Without FMA contraction (ISO C++ mode) both give bit-identical results.
__attribute__((target_clones("avx2", "default")))
#endif
void SurfaceAlbedo::HullBatch(const float* px, const float* py, const float* pz, const float* nx, const float* ny,
                              const float* nz, const float* footprint, int n, float* out) const {
  for (int base = 0; base < n; base += kLanes) {
    const int m = std::min(kLanes, n - base);
    HullChunk(px + base, py + base, pz + base, nx + base, ny + base, nz + base, footprint + base, m, nullptr,
              out + base);
  }
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void SurfaceAlbedo::HullRow(const float* px, const float* py, const float* pz, const float* nx, const float* ny,
                            const float* nz, const float* footprint, int n, float* out) const {
  if (n <= 0) return;
  const std::size_t N = static_cast<std::size_t>(n);
  // The coarse part of every point: 4 layer channels and the zones.
  std::vector<float> coarse(5 * N);
  float* cp[5];
  for (int c = 0; c < 5; ++c) cp[c] = coarse.data() + static_cast<std::size_t>(c) * N;
  // Exact at the anchors (every kRowStep-th point and the last) and at the
  // points where interpolating is not safe; gathered kLanes at a time.
  std::vector<int> exact;
  exact.reserve(N);
  for (int i = 0; i < n; i += kRowStep) exact.push_back(i);
  if ((n - 1) % kRowStep != 0) exact.push_back(n - 1);
  auto anchor_of = [&](int i) { return std::min(i - i % kRowStep + kRowStep, n - 1); };
  // Between anchors a and b: interpolated where the segment a-b is short, the
  // point lies on it (within kRowOffset) and the coarse octaves are fully
  // resolved at all three (footprint at most a quarter of their finest
  // wavelength, so their weights are 1 and do not vary).
  std::vector<float> seg(N, -1.0f);  // position along a-b in [0, 1]; -1: exact
  const float max_fp = kCoarsest / static_cast<float>(1 << (kCoarseOctaves - 1)) / 4;
  for (int a = 0; a + 1 < n; a += kRowStep) {
    const int b = anchor_of(a);
    const float ex = px[b] - px[a], ey = py[b] - py[a], ez = pz[b] - pz[a];
    const float len2 = ex * ex + ey * ey + ez * ez;
    const bool span_ok = len2 <= kRowSpan * kRowSpan && len2 > 0 && footprint[a] <= max_fp && footprint[b] <= max_fp;
    for (int i = a + 1; i < b; ++i) {
      bool ok = span_ok && footprint[i] <= max_fp;
      if (ok) {
        const float rx = px[i] - px[a], ry = py[i] - py[a], rz = pz[i] - pz[a];
        const float t = (rx * ex + ry * ey + rz * ez) / len2;
        const float ox = rx - t * ex, oy = ry - t * ey, oz = rz - t * ez;
        ok = t >= 0 && t <= 1 && ox * ox + oy * oy + oz * oz <= kRowOffset * kRowOffset;
        if (ok) seg[static_cast<std::size_t>(i)] = t;
      }
      if (!ok) exact.push_back(i);
    }
  }
  float gx[kLanes], gy[kLanes], gz[kLanes], gf[kLanes], layer[4][kLanes], zone[kLanes];
  for (std::size_t base = 0; base < exact.size(); base += kLanes) {
    const int m = static_cast<int>(std::min<std::size_t>(kLanes, exact.size() - base));
    for (int k = 0; k < m; ++k) {
      const std::size_t i = static_cast<std::size_t>(exact[base + static_cast<std::size_t>(k)]);
      gx[k] = px[i];
      gy[k] = py[i];
      gz[k] = pz[i];
      gf[k] = footprint[i];
    }
    Coarse(gx, gy, gz, gf, m, layer, zone);
    for (int k = 0; k < m; ++k) {
      const std::size_t i = static_cast<std::size_t>(exact[base + static_cast<std::size_t>(k)]);
      for (int c = 0; c < 4; ++c) cp[c][i] = layer[c][k];
      cp[4][i] = zone[k];
    }
  }
  for (int i = 0; i < n; ++i) {
    const float t = seg[static_cast<std::size_t>(i)];
    if (t < 0) continue;
    const std::size_t a = static_cast<std::size_t>(i - i % kRowStep), b = static_cast<std::size_t>(anchor_of(i));
    for (int c = 0; c < 5; ++c) cp[c][i] = cp[c][a] + t * (cp[c][b] - cp[c][a]);
  }
  for (int base = 0; base < n; base += kLanes) {
    const int m = std::min(kLanes, n - base);
    const float* chunk[5];
    for (int c = 0; c < 5; ++c) chunk[c] = cp[c] + base;
    HullChunk(px + base, py + base, pz + base, nx + base, ny + base, nz + base, footprint + base, m, chunk, out + base);
  }
}

float SurfaceAlbedo::OnHull(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float footprint) const {
  float out;
  HullBatch(&p.x(), &p.y(), &p.z(), &n.x(), &n.y(), &n.z(), &footprint, 1, &out);
  return out;
}

float SurfaceAlbedo::Fouling(const Eigen::Vector3f& p, float footprint, const float (&layer)[4]) const {
  // Barnacle-like shells on a dark weed film: a cellular pattern, one shell
  // per 16 mm cell at a random spot, radius 4.5-8 mm, a dark opening.
  constexpr float kCell = 0.016f;
  const float film = 0.11f + 0.25f * layer[kTone] + 0.15f * layer[kGrain];
  const float detail = OctaveWeight(kCell, footprint);
  if (detail == 0) return std::clamp(film + 0.1f, 0.03f, 0.9f);
  const Eigen::Vector3f x = p / kCell;
  const std::int32_t bx = GradientNoise::Floor(x.x()), by = GradientNoise::Floor(x.y()),
                     bz = GradientNoise::Floor(x.z());
  float best = 1e9f, radius = 0, tint = 0;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const std::uint32_t h = coarse_.Hash(static_cast<std::uint32_t>(bx + dx), static_cast<std::uint32_t>(by + dy),
                                             static_cast<std::uint32_t>(bz + dz));
        const Eigen::Vector3f spot =
            Eigen::Vector3f(float(bx + dx), float(by + dy), float(bz + dz)) +
            Eigen::Vector3f(float(h & 1023u), float((h >> 10) & 1023u), float((h >> 20) & 1023u)) / 1023.0f;
        const float d = (x - spot).norm();
        if (d < best) {
          best = d;
          radius = 0.28f + 0.22f * float((h >> 30) & 3u) / 3.0f;
          tint = float((h >> 27) & 7u) / 7.0f;
        }
      }
    }
  }
  float rho = film;
  if (best < radius) {
    const float r = best / radius;
    rho = r < 0.35f ? 0.08f : 0.42f + 0.2f * tint + 0.15f * (1 - r);
  }
  return std::clamp(Mix(film + 0.1f, rho, detail), 0.03f, 0.9f);
}

float SurfaceAlbedo::OnObject(const TrueObject& object, const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                              float footprint) const {
  float layer[4];
  Layers(p, footprint, layer);
  return ObjectFromLayers(object, p, n, footprint, layer);
}

void SurfaceAlbedo::ObjectBatch(const TrueObject* const* objects, const float* px, const float* py, const float* pz,
                                const float* nx, const float* ny, const float* nz, const float* footprint, int n,
                                float* out) const {
  float batch[4][kLanes];
  for (int base = 0; base < n; base += kLanes) {
    const int m = std::min(kLanes, n - base);
    Layers(px + base, py + base, pz + base, footprint + base, m, batch);
    for (int k = 0; k < m; ++k) {
      const int i = base + k;
      const float layer[4] = {batch[0][k], batch[1][k], batch[2][k], batch[3][k]};
      out[i] = ObjectFromLayers(*objects[i], Eigen::Vector3f(px[i], py[i], pz[i]), Eigen::Vector3f(nx[i], ny[i], nz[i]),
                                footprint[i], layer);
    }
  }
}

float SurfaceAlbedo::ObjectFromLayers(const TrueObject& object, const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                                      float footprint, const float (&layer)[4]) const {
  const SurfaceMaterial material = MaterialOf(object.kind);
  if (material == SurfaceMaterial::kFouling) return Fouling(p, footprint, layer);
  const Eigen::Vector3f axis = object.normal.cast<float>().normalized();
  const Eigen::Vector3f e1 = Perpendicular(axis), e2 = axis.cross(e1);
  const Eigen::Vector3f r = p - object.center.cast<float>();
  const float h = r.dot(axis), lx = r.dot(e1), ly = r.dot(e2);
  const bool top = n.dot(axis) > 0.5f;
  const float line = OctaveWeight(0.01f, footprint);  // markings fade when unresolved
  float rho;
  if (material == SurfaceMaterial::kPaintedSteel) {
    rho = 0.62f + 0.1f * layer[kTone];
    if (top) {
      if (std::min(std::abs(lx), std::abs(ly)) < 0.01f) rho = Mix(rho, 0.08f, line);  // a cross on the cap
    } else {
      if (std::abs(h - 0.55f * static_cast<float>(object.Height())) < 0.012f) rho = Mix(rho, 0.08f, line);
      if (Fract(std::atan2(ly, lx) / (2 * static_cast<float>(M_PI)) * 8) < 0.06f) rho = Mix(rho, 0.12f, line);
    }
    rho = Mix(rho, 0.22f, Smoothstep(0.3f, 0.36f, layer[kWear]));  // rust specks
  } else {
    rho = 0.42f + 0.1f * layer[kTone];
    if (top) {
      rho = Mix(rho, Fract((lx + ly) / 0.05f) < 0.5f ? 0.15f : 0.7f, line);  // hazard stripes
    } else if (std::abs(h - 0.5f * static_cast<float>(object.Height())) < 0.006f) {
      rho = Mix(rho, 0.12f, line);
    }
  }
  rho *= 1 + 0.5f * layer[kGrain];
  return std::clamp(rho, 0.03f, 0.9f);
}

}  // namespace hull
