// The histogram beside the deviation colour bar (issue 25.2, CloudCompare's
// scalar-field histogram): how many vertices of the remeshed model fall in
// each band of the legend's range, how many lie beyond either end, and --
// against a tolerance -- the share within it. Plain values: the 3-D scene
// draws it (ui/views/legend_histogram_impl.h), tests and the status text
// read it.
#pragma once

#include <vector>

namespace hull::ui {

struct DeviationHistogram {
  double lo = 0, hi = 0;     // the legend's range (m); bins split it evenly, bin 0 at lo
  std::vector<int> counts;   // per bin
  int below = 0, above = 0;  // values < lo and > hi (a manual range)
  int total = 0;             // finite values
  double tolerance = 0;      // m; 0: none
  int within = 0;            // |value| <= tolerance (0 without one)

  int max_count() const;
  double WithinFraction() const { return total > 0 ? static_cast<double>(within) / total : 0.0; }
};

// NaN and infinite values are left out; a value exactly at hi falls in the
// last bin. Empty counts when bins < 1 or the range is empty.
DeviationHistogram ComputeDeviationHistogram(const std::vector<double>& values, double lo, double hi, int bins,
                                             double tolerance);

}  // namespace hull::ui
