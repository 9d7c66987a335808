#include "ui/models/scale_bar.h"

#include <cmath>
#include <cstdio>

#include "base/axis_ticks.h"

namespace hull::ui {

ScaleBar ChooseScaleBar(double world_height, int height_px) {
  ScaleBar bar;
  if (!(world_height > 0) || !std::isfinite(world_height) || height_px <= 0) return bar;
  constexpr double kTargetPixels = 150.0;
  const double metres_per_pixel = world_height / height_px;
  const double target = kTargetPixels * metres_per_pixel;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  double best = decade, best_error = 1e300;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    const double error = std::abs(std::log(m * decade / target));
    if (error < best_error) best = m * decade, best_error = error;
  }
  bar.metres = best;
  bar.pixels = best / metres_per_pixel;
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f m", TickDecimals(best), best);
  bar.label = text;
  return bar;
}

}  // namespace hull::ui
