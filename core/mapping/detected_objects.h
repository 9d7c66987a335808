// Detected objects: the connected regions of the fused model whose deviation
// from the CAD surface exceeds h_min over at least a minimum footprint (or,
// smaller, that enough shaped features above h_min from enough keyframes
// hold up: MappingOptions::object_min_features, object_min_views), each
// merging every view that saw it; and the area they cover per hull zone
// (for the fouling assessment).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/point_index.h"
#include "geometry/triangle_mesh.h"
#include "mapping/hull_zones.h"
#include "mapping/mapping_input.h"
#include "mapping/mapping_options.h"
#include "mapping/shape_detection.h"

namespace hull {

struct DetectedObject {
  std::string id;  // "obj-1", "obj-2", ... from the bow aft
  // Centroid of the footprint (on the CAD surface, in M) and the CAD's
  // outward normal there.
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_m = Eigen::Vector3d::Zero();
  // Hull-relative: metres from the bow, station (0 at the bow) and side.
  double distance_from_bow = 0;
  int station = 0;
  HullSide side = HullSide::kBottom;
  // The footprint: the CAD-surface area where the fused deviation exceeds
  // h_min (linear interpolation over each face), and the heights over it.
  double area = 0;         // m^2
  double mean_height = 0;  // m, area-weighted over the footprint
  double max_height = 0;   // m, the highest fused vertex
  double p95_height = 0;   // m, 95th percentile of the footprint's vertex heights (nearest rank)
  // m, the standard deviation of max_height: the sigma_h of the object's
  // supporting feature (landmark over the footprint) nearest to its highest
  // vertex; NaN when none of them has a sigma_h (docs/mapping.md, "Objects").
  double max_height_sigma = std::nan("");
  int num_features = 0;                 // landmarks of this run's shapes lying over the footprint
  int num_views = 0;                    // keyframes whose shapes hold at least one of them
  std::vector<std::int64_t> keyframes;  // their ids, ascending
  std::vector<int> vertices;            // model vertices above h_min (indices into the fused model)
};

struct ObjectDetection {
  std::vector<DetectedObject> objects;
  // Per zone (HullFrame::ZoneIndex): area covered by objects (m^2), the
  // integral of their height over it (m^3), their highest point (m) and how
  // many objects have their centroid there.
  std::vector<double> zone_covered_area, zone_height_integral, zone_max_height;
  std::vector<int> zone_objects;
};

// prior: the refined mesh before fusion (in M; its vertices lie on the CAD
// surface) with face normals; deviation: the fused deviation per vertex;
// prior_index: a PointIndex over prior.vertices; cad_index: the CAD mesh.
ObjectDetection DetectObjects(const TriangleMesh& prior, const std::vector<double>& deviation,
                              const PointIndex& prior_index, const MeshIndex& cad_index, const HullFrame& hull,
                              const MappingInput& input, const std::vector<KeyframeShapes>& shapes,
                              const MappingOptions& options);

}  // namespace hull
