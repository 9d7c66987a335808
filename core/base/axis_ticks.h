// Round tick values for a plot axis, the one definition the screen's plots
// (ui/views) and the report's figures (ui/report) share, so an axis reads
// the same on screen and on paper. Standard C++ only.
#pragma once

#include <vector>

namespace hull {

// About `target` round tick values covering [lo, hi]: steps of 1, 2, 2.5 or
// 5 x 10^k, the first tick at or above lo, the last at or below hi. A tick
// within a billionth of a step of zero is exactly 0 (no "-1e-17" label).
// Empty when the interval is empty or not finite; target < 1 counts as 1.
std::vector<double> NiceTicks(double lo, double hi, int target);

// The decimals a label needs for ticks `step` apart to read exactly (0.25:
// 2, 2.5: 1, 5: 0, 0.001: 3), at most 6.
int TickDecimals(double step);

// The powers of ten within [lo, hi] (lo > 0), for a logarithmic axis.
std::vector<double> LogTicks(double lo, double hi);

}  // namespace hull
