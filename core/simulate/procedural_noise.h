// Gradient noise for procedural textures (Perlin's improved noise, 2002), in
// single precision and header-only, evaluated for a batch of points at once
// in plain loops the compiler vectorises (the renderer shades a row of
// pixels per call). One lattice lookup yields up to four independent
// channels (each its own gradient hash), so texture layers that share
// octaves cost little more than one. The lattice is hashed as a whole (no
// permutation table that wraps every 256 cells): the texture never repeats.
// Deterministic from the seed on every machine: integer hashing and IEEE
// single-precision adds and multiplies only, the same in every batch size.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

// The batch loops must be inlined into their callers, which may be compiled
// for a wider vector unit (target_clones in surface_albedo.cc).
#if defined(__GNUC__)
#define HI_NOISE_INLINE __attribute__((always_inline)) inline
#else
#define HI_NOISE_INLINE inline
#endif

namespace hull {

// Where up to kLanes points fall in the noise lattice: fractional
// coordinates, fade weights and the hashes of the eight cell corners.
struct NoiseLattice {
  static constexpr int kLanes = 16;
  float x[kLanes], y[kLanes], z[kLanes];  // position within the cell, [0, 1)
  float u[kLanes], v[kLanes], w[kLanes];  // quintic fade of x, y, z
  std::uint32_t h[8][kLanes];             // corner k = (k & 1, k >> 1 & 1, k >> 2)

  // out[i] += weight[i] * channel c's noise (about N(0, 0.2), within
  // [-1.3, 1.3]) for i < n; channels 0..9 use their own 3 bits of each hash.
  HI_NOISE_INLINE void Accumulate(int c, const float* weight, float* out, int n) const {
    const int s = 3 * c;
    for (int i = 0; i < n; ++i) {
      const float x0 = x[i], y0 = y[i], z0 = z[i], x1 = x0 - 1, y1 = y0 - 1, z1 = z0 - 1;
      auto g = [&](int k, float dx, float dy, float dz) {
        // One of the eight diagonal gradients (+-1, +-1, +-1): three hash
        // bits flip the signs of dx, dy, dz.
        const std::uint32_t b = h[k][i] >> s;
        return FlipSign(dx, b << 31) + FlipSign(dy, (b << 30) & kSignBit) + FlipSign(dz, (b << 29) & kSignBit);
      };
      const float a = Lerp(u[i], g(0, x0, y0, z0), g(1, x1, y0, z0));
      const float b = Lerp(u[i], g(2, x0, y1, z0), g(3, x1, y1, z0));
      const float c0 = Lerp(u[i], g(4, x0, y0, z1), g(5, x1, y0, z1));
      const float d = Lerp(u[i], g(6, x0, y1, z1), g(7, x1, y1, z1));
      out[i] += weight[i] * kScale * Lerp(w[i], Lerp(v[i], a, b), Lerp(v[i], c0, d));
    }
  }

  static float Lerp(float t, float a, float b) { return a + t * (b - a); }
  static constexpr std::uint32_t kSignBit = 0x80000000u;
  // v with its sign bit xor-ed with `sign` (0 or kSignBit): exactly +-v.
  static float FlipSign(float v, std::uint32_t sign) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    bits ^= sign;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  static constexpr float kScale = 0.7f;  // brings the diagonal gradients' spread near that of Perlin's edge set
};

class GradientNoise {
 public:
  explicit GradientNoise(std::uint64_t seed) : seed_(static_cast<std::uint32_t>(seed ^ (seed >> 32)) ^ 0x5EEDCAFEu) {}

  // Places n <= NoiseLattice::kLanes points (x, y, z in lattice units).
  HI_NOISE_INLINE void Locate(const float* xs, const float* ys, const float* zs, int n, NoiseLattice& L) const {
    for (int i = 0; i < n; ++i) {
      const std::int32_t X = Floor(xs[i]), Y = Floor(ys[i]), Z = Floor(zs[i]);
      const float fx = xs[i] - static_cast<float>(X), fy = ys[i] - static_cast<float>(Y),
                  fz = zs[i] - static_cast<float>(Z);
      L.x[i] = fx;
      L.y[i] = fy;
      L.z[i] = fz;
      L.u[i] = Fade(fx);
      L.v[i] = Fade(fy);
      L.w[i] = Fade(fz);
      // Hash's linear part for the cell's two x, y and z planes ((X + 1) A = X A + A, mod 2^32).
      const std::uint32_t ax = static_cast<std::uint32_t>(X) * kA, ay = static_cast<std::uint32_t>(Y) * kB,
                          az = static_cast<std::uint32_t>(Z) * kC;
      for (int k = 0; k < 8; ++k) {
        L.h[k][i] = Mix(seed_ ^ ((k & 1) ? ax + kA : ax) ^ (((k >> 1) & 1) ? ay + kB : ay) ^ ((k >> 2) ? az + kC : az));
      }
    }
  }

  // One point, one channel (the same value a batch gives).
  float Sample1(float x, float y, float z, int channel = 0) const {
    NoiseLattice L;
    Locate(&x, &y, &z, 1, L);
    const float one = 1.0f;
    float out = 0.0f;
    L.Accumulate(channel, &one, &out, 1);
    return out;
  }

  // A well-mixed 32-bit hash of a lattice point (also used for cell jitter).
  std::uint32_t Hash(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    return Mix(seed_ ^ (x * kA) ^ (y * kB) ^ (z * kC));
  }

  // floor() for |x| < 2^31, in integer arithmetic (vectorises without SSE4.1).
  static std::int32_t Floor(float x) {
    const auto i = static_cast<std::int32_t>(x);
    return i - static_cast<std::int32_t>(x < static_cast<float>(i));
  }

 private:
  static float Fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  static constexpr std::uint32_t kA = 0x8DA6B343u, kB = 0xD8163841u, kC = 0xCB1AB31Fu;
  // A 32-bit finaliser (two multiply-xorshift rounds).
  static std::uint32_t Mix(std::uint32_t h) {
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
  }

  std::uint32_t seed_;
};

// Weight of a noise octave of wavelength `wavelength` seen with a pixel
// footprint `footprint` (both in metres): 1 while the octave spans at least
// four footprints, fading to 0 at two (finer octaves would only alias).
// OctaveWeightOfRatio takes r = wavelength / footprint.
inline float OctaveWeightOfRatio(float r) { return std::min(std::max(0.5f * (r - 2.0f), 0.0f), 1.0f); }
inline float OctaveWeight(float wavelength, float footprint) {
  return OctaveWeightOfRatio(wavelength / footprint);  // r = +inf for footprint 0
}

}  // namespace hull
