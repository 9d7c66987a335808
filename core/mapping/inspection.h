// The inspected area: the part of the CAD surface the survey's top camera
// actually saw. The surface is sampled (one sample per about
// inspection_spacing^2 of area, each standing for its share of its face);
// a sample is inspected when at least one keyframe's top camera sees it:
// in front of the camera and inside the image, within inspection_range,
// on a face turned toward the camera, and with nothing of the CAD in
// between. Summed per hull zone with the zone's whole CAD area (exact: each
// face is clipped at the station boundaries).
#pragma once

#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "mapping/hull_zones.h"
#include "survey/survey.h"

namespace hull {

struct InspectionCoverage {
  std::vector<double> hull_area;       // per zone (HullFrame::ZoneIndex): CAD area (m^2)
  std::vector<double> inspected_area;  // per zone: the part a top camera saw (m^2)
  double total_hull_area = 0;          // all zones (decks excluded)
  double total_inspected_area = 0;
  std::size_t samples = 0;  // surface samples near the survey
  std::size_t samples_seen = 0;
};

// x_M_cT: the top camera in M per keyframe. spacing and range as in
// MappingOptions (inspection_spacing, inspection_range).
InspectionCoverage MeasureInspection(const TriangleMesh& cad, const MeshIndex& cad_index, const HullFrame& hull,
                                     const std::vector<Pose>& x_M_cT, const CameraRig& camera, double spacing,
                                     double range, Progress& progress);

// The CAD area of each zone (faces clipped at the station boundaries).
std::vector<double> ZoneAreas(const TriangleMesh& cad, const HullFrame& hull);

}  // namespace hull
