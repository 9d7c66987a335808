// What the Details panel shows for a point picked on a surface layer
// (issue 25, "measure anywhere"): the remeshed model in any of its colourings
// (deviation, sigma, significance), the change map between two surveys, or
// the CAD. The values are those of the picked triangle's corner nearest the
// click, so a pick reads exactly the vertex's value in model.ply (mapping)
// or in the comparison's model.ply; where on the hull it is comes from the
// mapping's hull frame (from the bow, station, side). No VTK, no widgets.
#pragma once

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "results/compare_files.h"
#include "ui/models/pick_details.h"
#include "ui/session/inspection_results.h"

namespace hull::ui {

// The corner of `face` nearest p (p in the mesh's frame); -1 for a face
// index out of range.
int NearestCorner(const TriangleMesh& mesh, int face, const Eigen::Vector3d& p);

// A vertex of the mapping's remeshed model: its deviation, sigma and whether
// |deviation| > k sigma (k: the significance factor on screen), fusions,
// where it is on the hull, and the object it belongs to or the nearest one.
PickInfo DescribeModelPoint(const MappingRun& mapping, int vertex, double significance_k);
// A vertex of the comparison's model (survey B's): the change in height
// since survey A, its sigma and significance, and B's deviation there;
// x_gM places it in g.
PickInfo DescribeChangePoint(const SurveyComparisonRun& comparison, int vertex, const Pose& x_gM);
// A vertex of the CAD mesh (a corner of `face`) placed by x_gM: on the CAD
// by definition (deviation 0); where on the hull when a mapping is given
// (its hull frame; the side from the face's normal).
PickInfo DescribeCadPoint(const TriangleMesh& cad, int face, int vertex, const Pose& x_gM, const MappingRun* mapping);

}  // namespace hull::ui
