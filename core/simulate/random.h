// Deterministic random numbers for the simulators: one seed gives the same
// bundle on every machine (std::mt19937_64 is specified bit-exactly; the
// distributions below are written out rather than taken from <random>, whose
// results differ between standard libraries).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace hull {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  // A child stream for item `index` (e.g. a keyframe), independent of the
  // order in which items are processed: safe for parallel loops.
  static Rng ForItem(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
    std::uint64_t s = seed * 0x9E3779B97F4A7C15ULL ^ (stream + 0x632BE59BD9B4E019ULL) * 0xBF58476D1CE4E5B9ULL ^
                      (index + 1) * 0x94D049BB133111EBULL;
    s ^= s >> 31;
    return Rng(s);
  }

  // Uniform in [0, 1).
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [0, n).
  std::uint64_t Index(std::uint64_t n) {
    return n ? static_cast<std::uint64_t>(Uniform() * static_cast<double>(n)) % n : 0;
  }
  bool Bernoulli(double p) { return Uniform() < p; }
  // Standard normal (Box-Muller).
  double Gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = Uniform();
    while (u1 <= 1e-300) u1 = Uniform();
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2);
  }
  double Gaussian(double sigma) { return sigma * Gaussian(); }
  // Normal truncated at +-limit standard deviations (resampled).
  double TruncatedGaussian(double sigma, double limit) {
    double g = Gaussian();
    while (std::abs(g) > limit) g = Gaussian();
    return sigma * g;
  }
  // Random sign.
  double Sign() { return Uniform() < 0.5 ? -1.0 : 1.0; }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

}  // namespace hull
