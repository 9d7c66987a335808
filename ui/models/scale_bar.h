// The length a scale bar shows: a round number of metres (1, 2 or 5 x 10^k)
// that takes about 150 pixels of a view, from what the view spans. Plain
// values: the 3-D scene draws it (ui/views/scene_guides_impl.h), tests
// check it.
#pragma once

#include <string>

namespace hull::ui {

struct ScaleBar {
  double metres = 0;  // 0: none (a view of no size or span)
  double pixels = 0;
  std::string label;  // "0.5 m", "2 m", "0.05 m"
};

// world_height: metres the view spans vertically where the bar holds (at
// its focal point); height_px: the view's height in pixels. The chosen
// length is the round one nearest 150 pixels on a log scale, so it takes
// 95 to 237 pixels.
ScaleBar ChooseScaleBar(double world_height, int height_px);

}  // namespace hull::ui
