// What model-assisted mapping produces. Its files (mapping.json, the
// remeshed model as PLY/OBJ/STL, objects and zones as CSV and JSON,
// shapes.csv) are written and read by results/mapping_files.h.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "mapping/detected_objects.h"
#include "mapping/fouling.h"
#include "mapping/hull_zones.h"
#include "mapping/mapping_options.h"
#include "mapping/peak_fit.h"
#include "mapping/shape_detection.h"

namespace hull {

struct MappingTimings {  // wall seconds of each step of a run
  double shapes = 0, region = 0, refinement = 0, fusion = 0, deviation = 0, inspection = 0, objects = 0, total = 0;
};

struct MappingSummary {
  std::string source;  // MappingInput::source
  std::size_t keyframes = 0, keyframes_with_shapes = 0;
  std::size_t points = 0, points_clustered = 0;  // features observed (in front of the camera) and with |d| > tau
  std::size_t shapes = 0, shape_triangles = 0;
  std::size_t model_vertices = 0, model_faces = 0;
  std::size_t vertices_fused = 0, fusion_hits = 0;
  std::size_t peaks_fitted = 0, peaks_placed = 0;  // apexes accepted by the peak fit, and put into the model
  // Peak features (shape_fusion.h: lump tops no keyframe meshed), and those whose vertex rose to them.
  std::size_t peak_features = 0, peak_features_raised = 0;
  std::size_t region_cells = 0;                                // cells of the region the cached mesh was refined for
  double refined_area = 0;                                     // m^2 remeshed to refine_edge
  bool refinement_reused = false;                              // the cached refined mesh served this run
  double hull_area = 0, inspected_area = 0, covered_area = 0;  // m^2 (zones only: decks excluded)
  MappingTimings seconds;
};

struct MappingResult {
  static constexpr int kFormatVersion = 1;

  MappingOptions options;
  // Provenance written to mapping.json "inputs" (e.g. {"adjustment", dir}).
  std::vector<std::pair<std::string, std::string>> inputs;
  HullFrame hull;
  // Algorithm 1 per keyframe (indexed like MappingInput::keyframes).
  std::vector<KeyframeShapes> keyframes;
  // Algorithm 2's M_new in M: vertex scalars "deviation" (signed distance to
  // the CAD surface, m) and "fusions" (hits of eq. 15).
  TriangleMesh model;
  // The peak fit's candidates (MappingOptions::peak_fit; peak_fit.h),
  // accepted or not, with what the fusion made of the accepted ones.
  std::vector<FittedPeak> peaks;
  std::vector<DetectedObject> objects;
  std::vector<ZoneAssessment> zones;
  MappingSummary summary;
};

}  // namespace hull
