#include "adjust/adjust_result.h"

namespace hull {

double AdjustmentResult::FractionOnSurface() const {
  if (landmarks.empty()) return 0;
  int on = 0;
  for (const auto& l : landmarks) on += l.label;
  return static_cast<double>(on) / static_cast<double>(landmarks.size());
}

}  // namespace hull
