// Survey geometry -> vtkPolyData for the scene's actors (VTK side only).
#pragma once

#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "ui/survey_overlays.h"

class vtkMatrix4x4;
class vtkPolyData;

namespace hull::ui {

// Triangles, in the mesh's own frame (no normals: flat shading).
vtkSmartPointer<vtkPolyData> MeshPolyData(const TriangleMesh& mesh);
// One polyline through the points, in order.
vtkSmartPointer<vtkPolyData> PolylinePolyData(const std::vector<Eigen::Vector3d>& points);
// One vertex cell per point.
vtkSmartPointer<vtkPolyData> PointCloudPolyData(const std::vector<Eigen::Vector3d>& points);
// Landmarks as vertices with the point arrays "label_rgb" (green on the
// hull, red on a foreign object, grey when unknown) and "deviation".
vtkSmartPointer<vtkPolyData> LandmarksPolyData(const std::vector<LandmarkMarker>& landmarks);
// Closed loops and segments of every outline, with the point array
// "object_index" (position in `outlines`) for picking.
vtkSmartPointer<vtkPolyData> OutlinesPolyData(const std::vector<ObjectOutline>& outlines);
// Four edges from the apex and the image rectangle of each frustum.
vtkSmartPointer<vtkPolyData> FrustaPolyData(const std::vector<Frustum>& frusta);

vtkSmartPointer<vtkMatrix4x4> PoseMatrix(const Pose& pose);

}  // namespace hull::ui
