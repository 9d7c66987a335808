// What the 3-D scene shows and how, as plain values (no VTK): shared by the
// scene view, the layers panel and the project file.
#pragma once

#include <QString>
#include <array>
#include <map>
#include <optional>
#include <vector>

namespace hull::ui {

// One actor (or group of actors) of the 3-D scene each.
enum class SceneLayer {
  kHull,            // the CAD mesh, placed by x_gM
  kTrajectory,      // vehicle positions of the initial navigation (nav.csv)
  kTrueTrajectory,  // the true trajectory (truth/poses.csv)
  kDvlHits,         // DVL returns from the initial poses
  kLandmarks,       // landmarks (truth or landmarks.csv)
  kTruthObjects,    // outlines of the true foreign objects (truth/objects.json)
  kFrusta,          // camera frusta of every Nth keyframe
  // The bundle adjustment's results (present once it ran):
  kAdjustedTrajectory,  // vehicle positions after adjustment
  kAdjustedDvlHits,     // DVL returns from the adjusted poses
  kAdjustedLandmarks,   // adjusted landmarks: label (max-mixture lambda) or deviation
  kSlab,                // the cross-section slab, a translucent box
  // Mapping's results (present once it ran):
  kHeatmap,          // the fused, remeshed model coloured by its deviation
  kAlphaShapes,      // Algorithm 1's alpha shapes of every keyframe
  kDetectedObjects,  // the detected objects' footprint outlines
  kSigmaHeatmap,     // the fused model coloured by its per-vertex sigma (mm)
  kSignificance,     // the fused model's deviation where |h| > k sigma, grey elsewhere
  // A comparison of two surveys (present once one ran):
  kHeightChange,  // survey B's model coloured by the change in height since survey A
  // A photomosaic opened from a results folder (present once one is open):
  kPhotomosaic,  // the remeshed model textured with the mosaic's atlas
};

const std::vector<SceneLayer>& AllSceneLayers();
QString LayerKey(SceneLayer layer);    // stable name for files: "hull", "dvl_hits", ...
QString LayerLabel(SceneLayer layer);  // for menus and panels
std::optional<SceneLayer> LayerFromKey(const QString& key);

enum class LandmarkColouring {
  kLabel,      // on the hull green, on a foreign object red
  kDeviation,  // signed distance to the CAD surface, with a colour legend
};
QString ColouringKey(LandmarkColouring c);
std::optional<LandmarkColouring> ColouringFromKey(const QString& key);

// The deviation colours (RGB in [0, 1]) of a tolerance band and of values
// beyond a manual legend range.
constexpr double kWithinTolerance[3] = {0.20, 0.66, 0.32};
constexpr double kAboveRange[3] = {0.95, 0.85, 0.10};
constexpr double kBelowRange[3] = {0.10, 0.85, 0.90};

struct SceneOptions {
  std::map<SceneLayer, bool> visible = DefaultVisibility();
  bool hull_edges = false;
  LandmarkColouring colouring = LandmarkColouring::kLabel;
  // Colour-legend range (m); auto_range uses the data's own range.
  bool auto_range = true;
  double range_min = -0.05, range_max = 0.15;
  // Tolerance band (m; 0: none): deviations within +-tolerance drawn in one
  // colour (green), those beyond it in the deviation colours; zero stays
  // white whatever the range, and with a manual range the values beyond
  // its ends are marked (above yellow, below cyan) rather than clamped.
  double tolerance = 0;
  int frustum_stride = 10;  // a frustum at every Nth keyframe

  bool IsVisible(SceneLayer layer) const;
  static std::map<SceneLayer, bool> DefaultVisibility();  // all on except the frusta and alpha shapes
  bool operator==(const SceneOptions& o) const;
  bool operator!=(const SceneOptions& o) const { return !(*this == o); }
};

// A VTK camera as values: position, focal point and view-up in g (metres),
// vertical view angle in degrees.
struct CameraState {
  std::array<double, 3> position{{0, 0, 0}};
  std::array<double, 3> focal_point{{0, 0, 0}};
  std::array<double, 3> view_up{{0, 0, -1}};
  double view_angle = 30.0;
  bool operator==(const CameraState& o) const;
};

}  // namespace hull::ui
