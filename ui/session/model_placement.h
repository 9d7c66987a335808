// Where the CAD model is placed in g, and from what: the choices of the
// layers panel and the "model_placement" of project files. Plain values
// (no Qt, no survey types), so the project file reader checks the key alone.
#pragma once

#include <string>

namespace hull::ui {

// kAdjusted (the bundle adjustment's x_gM) exists only in a Session holding
// an adjustment.
enum class ModelPlacement { kIdentity, kGuess, kTruth, kAdjusted };
const char* ModelPlacementKey(ModelPlacement p);  // "identity", "guess", "truth", "adjusted"
const char* ModelPlacementLabel(ModelPlacement p);
bool ModelPlacementFromKey(const std::string& key, ModelPlacement* p);

}  // namespace hull::ui
