// Results made from the synthetic survey's truth without running the
// solver (adjustment runs of each surface model with a made-up iteration
// log and DVL residuals) and its mapping by the core Mapper from the truth:
// deterministic data for the screenshot baselines of the result views.
#pragma once

#include <memory>

#include "ui/session/inspection_results.h"
#include "ui/session/session.h"
#include "ui/views/scene_view.h"

namespace hull::ui::testing {

// The naive run's features sit 15 mm off the hull (misregistered with the
// DVL, Fig. 14 a-c), all-on-surface squashes them to 30 % of their height.
std::shared_ptr<const AdjustmentRun> SyntheticRun(SurfaceModel model);
const Session::ModelRuns& SyntheticRuns();
// Mapped from the truth with made-up landmark sigmas (2 to 5 mm): the fused
// model has per-vertex "sigma" and "significant", the objects a height sigma.
std::shared_ptr<const MappingRun> SyntheticMapping();

// Points `scene`'s camera close at the synthetic survey's cylinder ((2.0,
// 0.75) in M), from below: the view the result-view baselines share.
void LookAtTheCylinder(SceneView& scene);

}  // namespace hull::ui::testing
