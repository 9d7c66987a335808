#include "ui/models/deviation_histogram.h"

#include <algorithm>
#include <cmath>

namespace hull::ui {

int DeviationHistogram::max_count() const {
  return counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
}

DeviationHistogram ComputeDeviationHistogram(const std::vector<double>& values, double lo, double hi, int bins,
                                             double tolerance) {
  DeviationHistogram h;
  h.lo = lo;
  h.hi = hi;
  h.tolerance = tolerance > 0 ? tolerance : 0.0;
  if (bins < 1 || !(hi > lo)) return h;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  const double width = (hi - lo) / bins;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    ++h.total;
    if (h.tolerance > 0 && std::abs(v) <= h.tolerance) ++h.within;
    if (v < lo) {
      ++h.below;
    } else if (v > hi) {
      ++h.above;
    } else {
      const int bin = std::min(bins - 1, static_cast<int>((v - lo) / width));
      ++h.counts[static_cast<std::size_t>(bin)];
    }
  }
  return h;
}

}  // namespace hull::ui
