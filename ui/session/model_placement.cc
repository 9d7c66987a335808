#include "ui/session/model_placement.h"

namespace hull::ui {

const char* ModelPlacementKey(ModelPlacement p) {
  switch (p) {
    case ModelPlacement::kIdentity:
      return "identity";
    case ModelPlacement::kGuess:
      return "guess";
    case ModelPlacement::kTruth:
      return "truth";
    case ModelPlacement::kAdjusted:
      return "adjusted";
  }
  return "";
}

const char* ModelPlacementLabel(ModelPlacement p) {
  switch (p) {
    case ModelPlacement::kIdentity:
      return "identity (no placement known)";
    case ModelPlacement::kGuess:
      return "model_pose_guess (survey.json)";
    case ModelPlacement::kTruth:
      return "ground truth (truth/model_pose.json)";
    case ModelPlacement::kAdjusted:
      return "bundle adjustment (x_gM estimated)";
  }
  return "";
}

bool ModelPlacementFromKey(const std::string& key, ModelPlacement* p) {
  for (ModelPlacement c :
       {ModelPlacement::kIdentity, ModelPlacement::kGuess, ModelPlacement::kTruth, ModelPlacement::kAdjusted}) {
    if (key == ModelPlacementKey(c)) {
      *p = c;
      return true;
    }
  }
  return false;
}

}  // namespace hull::ui
