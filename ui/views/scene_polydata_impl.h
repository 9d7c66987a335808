// Survey geometry -> vtkPolyData for the scene's actors (VTK side only).
#pragma once

#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "ui/models/cross_section.h"
#include "ui/session/inspection_results.h"
#include "ui/session/survey_overlays.h"

class vtkMatrix4x4;
class vtkPolyData;
class vtkTexture;

namespace hull::ui {

// Triangles, in the mesh's own frame (no normals: flat shading).
vtkSmartPointer<vtkPolyData> MeshPolyData(const TriangleMesh& mesh);
// A textured OBJ (the photomosaic's mosaic.obj) with its texture
// coordinates (vtkOBJReader) and smooth point normals; empty when the file
// cannot be read or has no texture coordinates.
vtkSmartPointer<vtkPolyData> TexturedObjPolyData(const std::string& obj_path);
// A PNG as a texture, interpolated (the photomosaic's atlas).
vtkSmartPointer<vtkTexture> AtlasTexture(const std::string& png_path);
// One polyline through the points, in order.
vtkSmartPointer<vtkPolyData> PolylinePolyData(const std::vector<Eigen::Vector3d>& points);
// One vertex cell per point.
vtkSmartPointer<vtkPolyData> PointCloudPolyData(const std::vector<Eigen::Vector3d>& points);
// Landmarks as vertices with the point arrays "label_rgb" (green on the
// hull, red on a foreign object, grey when unknown) and "deviation".
vtkSmartPointer<vtkPolyData> LandmarksPolyData(const std::vector<LandmarkMarker>& landmarks);
// Adjusted landmarks as vertices with "label_rgb" (green for lambda = 1, on
// the hull; red for lambda = 0, foreign structure) and "deviation" (estimated).
vtkSmartPointer<vtkPolyData> AdjustedLandmarksPolyData(const std::vector<AdjustedLandmark>& landmarks);
// The slab's six faces (quads).
vtkSmartPointer<vtkPolyData> SlabPolyData(const SlabBox& slab);
// The fused model (in M) with its vertex normals and the point array
// "deviation" (zero where the mesh has none).
vtkSmartPointer<vtkPolyData> HeatmapPolyData(const TriangleMesh& mesh);
// Adds (or replaces) a point array of the values times `scale`; values must
// have one entry per point.
void SetPointArray(vtkPolyData* poly, const char* name, const std::vector<double>& values, double scale = 1.0);
// Every keyframe's alpha shapes, as triangles in g.
vtkSmartPointer<vtkPolyData> AlphaShapesPolyData(const std::vector<KeyframeShapes>& keyframes);
// Segments grouped per object, with the point array "object_index".
vtkSmartPointer<vtkPolyData> SegmentsPolyData(const std::vector<std::vector<std::array<Eigen::Vector3d, 2>>>& groups);
// Closed loops and segments of every outline, with the point array
// "object_index" (position in `outlines`) for picking.
vtkSmartPointer<vtkPolyData> OutlinesPolyData(const std::vector<ObjectOutline>& outlines);
// Four edges from the apex and the image rectangle of each frustum.
vtkSmartPointer<vtkPolyData> FrustaPolyData(const std::vector<Frustum>& frusta);

vtkSmartPointer<vtkMatrix4x4> PoseMatrix(const Pose& pose);

}  // namespace hull::ui
