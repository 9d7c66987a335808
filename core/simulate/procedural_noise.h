// Gradient noise for procedural textures (Perlin's improved noise, 2002), in
// single precision and header-only so the renderer's per-pixel loop inlines
// it. One lattice lookup yields up to four independent channels (each its
// own gradient hash), so several texture layers that share octaves cost
// little more than one. Deterministic from the seed on every machine.
#pragma once

#include <cmath>
#include <cstdint>

namespace hull {

class GradientNoise {
 public:
  static constexpr int kChannels = 4;

  explicit GradientNoise(std::uint64_t seed) : seed_(static_cast<std::uint32_t>(seed ^ (seed >> 32)) ^ 0x5EEDCAFEu) {}

  // Noise in about [-1, 1] at (x, y, z) (lattice spacing 1), `channels`
  // (1..4) independent values written to out[0..channels). The lattice is
  // hashed as a whole (no permutation table that wraps every 256 cells), so
  // the texture never repeats.
  void Sample(float x, float y, float z, int channels, float* out) const {
    const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const auto X = static_cast<std::uint32_t>(static_cast<std::int64_t>(fx));
    const auto Y = static_cast<std::uint32_t>(static_cast<std::int64_t>(fy));
    const auto Z = static_cast<std::uint32_t>(static_cast<std::int64_t>(fz));
    x -= fx;
    y -= fy;
    z -= fz;
    const float u = Fade(x), v = Fade(y), w = Fade(z);
    std::uint32_t h[8];
    for (int k = 0; k < 8; ++k) h[k] = Hash(X + (k & 1), Y + ((k >> 1) & 1), Z + (k >> 2));
    const float x1 = x - 1, y1 = y - 1, z1 = z - 1;
    for (int c = 0; c < channels; ++c) {
      const int s = 4 * c;  // channel c takes its own 4 bits of each corner's hash
      auto g = [&](int k, float dx, float dy, float dz) { return Grad(static_cast<int>(h[k] >> s), dx, dy, dz); };
      out[c] = Lerp(w,
                    Lerp(v, Lerp(u, g(0, x, y, z), g(1, x1, y, z)), Lerp(u, g(2, x, y1, z), g(3, x1, y1, z))),
                    Lerp(v, Lerp(u, g(4, x, y, z1), g(5, x1, y, z1)), Lerp(u, g(6, x, y1, z1), g(7, x1, y1, z1))));
    }
  }

  float Sample1(float x, float y, float z) const {
    float v;
    Sample(x, y, z, 1, &v);
    return v;
  }

  // A well-mixed 32-bit hash of a lattice point (also used for cell jitter).
  std::uint32_t Hash(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    std::uint32_t h = seed_ ^ (x * 0x8DA6B343u) ^ (y * 0xD8163841u) ^ (z * 0xCB1AB31Fu);
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
  }

 private:
  static float Fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  static float Lerp(float t, float a, float b) { return a + t * (b - a); }
  // One of the 12 cube-edge directions (and 4 repeats), Perlin 2002.
  static float Grad(int hash, float x, float y, float z) {
    const int h = hash & 15;
    const float a = h < 8 ? x : y;
    const float b = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -a : a) + ((h & 2) ? -b : b);
  }

  std::uint32_t seed_;
};

// Weight of a noise octave of wavelength `wavelength` seen with a pixel
// footprint `footprint` (both in metres): 1 while the octave spans at least
// four footprints, fading to 0 at two (finer octaves would only alias).
inline float OctaveWeight(float wavelength, float footprint) {
  if (!(footprint > 0)) return 1.0f;
  const float r = wavelength / footprint;
  return r >= 4.0f ? 1.0f : (r <= 2.0f ? 0.0f : 0.5f * (r - 2.0f));
}

}  // namespace hull
