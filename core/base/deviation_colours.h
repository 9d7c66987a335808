// The deviation colour map of the report's figures, shared with the glTF
// exporter plugin. Header-only and standard C++ only, so that a plugin
// (which links nothing of HullInspect) includes it too.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace hull {

// Diverging blue - near-white - red for t in [-1, 1] (ColorBrewer RdBu, 11
// classes, interpolated); red, green, blue in [0, 1]. A non-finite t is 0.
inline std::array<double, 3> DivergingRgb(double t) {
  static constexpr unsigned char kStops[][3] = {{0x05, 0x30, 0x61}, {0x21, 0x66, 0xac}, {0x43, 0x93, 0xc3},
                                                {0x92, 0xc5, 0xde}, {0xd1, 0xe5, 0xf0}, {0xf7, 0xf7, 0xf7},
                                                {0xfd, 0xdb, 0xc7}, {0xf4, 0xa5, 0x82}, {0xd6, 0x60, 0x4d},
                                                {0xb2, 0x18, 0x2b}, {0x67, 0x00, 0x1f}};
  constexpr int n = sizeof kStops / sizeof kStops[0];
  if (!std::isfinite(t)) t = 0;
  const double x = (std::clamp(t, -1.0, 1.0) + 1) / 2 * (n - 1);
  const int i = std::min(n - 2, static_cast<int>(std::floor(x)));
  const double f = x - i;
  std::array<double, 3> rgb;
  for (int k = 0; k < 3; ++k) rgb[k] = (kStops[i][k] + f * (kStops[i + 1][k] - kStops[i][k])) / 255.0;
  return rgb;
}

// The half-range of the colour map for these deviation magnitudes (m): their
// 99th percentile rounded up to 2.5 cm, at least 5 cm.
inline double DeviationColourRange(std::vector<double> magnitudes) {
  double p99 = 0;
  if (!magnitudes.empty()) {
    const auto k = static_cast<std::size_t>(0.99 * (magnitudes.size() - 1));
    std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(k), magnitudes.end());
    p99 = magnitudes[k];
  }
  return std::max(0.05, std::ceil(p99 / 0.025 - 1e-9) * 0.025);
}

}  // namespace hull
