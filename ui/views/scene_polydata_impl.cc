#include "ui/views/scene_polydata_impl.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

namespace hull::ui {

namespace {

vtkSmartPointer<vtkPoints> MakePoints(const std::vector<Eigen::Vector3d>& points) {
  auto out = vtkSmartPointer<vtkPoints>::New();
  out->SetDataTypeToDouble();
  out->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) out->SetPoint(static_cast<vtkIdType>(i), points[i].data());
  return out;
}

vtkSmartPointer<vtkCellArray> Vertices(vtkIdType n) {
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->AllocateExact(n, n);
  for (vtkIdType i = 0; i < n; ++i) verts->InsertNextCell(1, &i);
  return verts;
}

}  // namespace

vtkSmartPointer<vtkPolyData> MeshPolyData(const TriangleMesh& mesh) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(mesh.vertices));
  vtkNew<vtkCellArray> triangles;
  triangles->AllocateExact(static_cast<vtkIdType>(mesh.faces.size()), static_cast<vtkIdType>(3 * mesh.faces.size()));
  for (const Face& f : mesh.faces) {
    const vtkIdType ids[3] = {f[0], f[1], f[2]};
    triangles->InsertNextCell(3, ids);
  }
  poly->SetPolys(triangles);
  return poly;
}

vtkSmartPointer<vtkPolyData> TexturedObjPolyData(const std::string& obj_path) {
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(obj_path.c_str());
  reader->Update();
  vtkPolyData* read = reader->GetOutput();
  if (!read || read->GetNumberOfPoints() == 0 || !read->GetPointData()->GetTCoords()) {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  // The OBJ has no normals: smooth ones (not split at edges, so that a
  // vertex shared by two charts is lit alike on both).
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(read);
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->Update();
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(normals->GetOutput());
  return out;
}

vtkSmartPointer<vtkTexture> AtlasTexture(const std::string& png_path) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png_path.c_str());
  reader->Update();
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(reader->GetOutput());
  texture->InterpolateOn();
  texture->RepeatOff();
  texture->EdgeClampOn();
  return texture;
}

vtkSmartPointer<vtkPolyData> PolylinePolyData(const std::vector<Eigen::Vector3d>& points) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(points));
  vtkNew<vtkCellArray> lines;
  if (points.size() >= 2) {
    lines->InsertNextCell(static_cast<vtkIdType>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) lines->InsertCellPoint(static_cast<vtkIdType>(i));
  }
  poly->SetLines(lines);
  return poly;
}

vtkSmartPointer<vtkPolyData> PointCloudPolyData(const std::vector<Eigen::Vector3d>& points) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(points));
  poly->SetVerts(Vertices(static_cast<vtkIdType>(points.size())));
  return poly;
}

namespace {

constexpr unsigned char kOnHull[3] = {40, 200, 60}, kForeign[3] = {230, 40, 40}, kNoTruth[3] = {200, 200, 200};

// Landmarks as vertices with a "label_rgb" colour and their "deviation":
// `colour(i)` and `deviation(i)` for the i-th of n points.
template <class Position, class Colour, class Deviation>
vtkSmartPointer<vtkPolyData> LabelledPoints(std::size_t n, Position position, Colour colour, Deviation deviation) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(n);
  for (std::size_t i = 0; i < n; ++i) positions.push_back(position(i));
  auto poly = PointCloudPolyData(positions);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("label_rgb");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(n));
  vtkNew<vtkDoubleArray> dev;
  dev->SetName("deviation");
  dev->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) {
    rgb->SetTypedTuple(static_cast<vtkIdType>(i), colour(i));
    dev->SetValue(static_cast<vtkIdType>(i), deviation(i));
  }
  poly->GetPointData()->AddArray(rgb);
  poly->GetPointData()->AddArray(dev);
  return poly;
}

}  // namespace

vtkSmartPointer<vtkPolyData> LandmarksPolyData(const std::vector<LandmarkMarker>& landmarks) {
  return LabelledPoints(
      landmarks.size(), [&](std::size_t i) { return landmarks[i].position; },
      [&](std::size_t i) {
        const LandmarkMarker& l = landmarks[i];
        return !l.has_truth ? kNoTruth : (l.foreign() ? kForeign : kOnHull);
      },
      [&](std::size_t i) { return landmarks[i].deviation; });
}

vtkSmartPointer<vtkPolyData> AdjustedLandmarksPolyData(const std::vector<AdjustedLandmark>& landmarks) {
  return LabelledPoints(
      landmarks.size(), [&](std::size_t i) { return landmarks[i].position; },
      [&](std::size_t i) { return landmarks[i].label == 1 ? kOnHull : kForeign; },
      [&](std::size_t i) { return landmarks[i].deviation; });
}

vtkSmartPointer<vtkPolyData> SlabPolyData(const SlabBox& slab) {
  std::vector<Eigen::Vector3d> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d s((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
    corners.push_back(slab.centre + slab.axes * s.cwiseProduct(slab.half_extents));
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(corners));
  vtkNew<vtkCellArray> quads;
  const vtkIdType faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : faces) quads->InsertNextCell(4, f);
  poly->SetPolys(quads);
  return poly;
}

vtkSmartPointer<vtkPolyData> HeatmapPolyData(const TriangleMesh& mesh) {
  auto poly = MeshPolyData(mesh);
  if (mesh.vertex_normals.size() == mesh.vertices.size()) {
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(static_cast<vtkIdType>(mesh.vertices.size()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      normals->SetTuple(static_cast<vtkIdType>(i), mesh.vertex_normals[i].data());
    }
    poly->GetPointData()->SetNormals(normals);
  }
  vtkNew<vtkDoubleArray> deviation;
  deviation->SetName("deviation");
  deviation->SetNumberOfTuples(static_cast<vtkIdType>(mesh.vertices.size()));
  const std::vector<double>* d = mesh.FindScalar("deviation");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    deviation->SetValue(static_cast<vtkIdType>(i), d ? (*d)[i] : 0.0);
  }
  poly->GetPointData()->AddArray(deviation);
  return poly;
}

void SetPointArray(vtkPolyData* poly, const char* name, const std::vector<double>& values, double scale) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) array->SetValue(static_cast<vtkIdType>(i), values[i] * scale);
  poly->GetPointData()->RemoveArray(name);
  poly->GetPointData()->AddArray(array);
  poly->Modified();
}

vtkSmartPointer<vtkPolyData> AlphaShapesPolyData(const std::vector<KeyframeShapes>& keyframes) {
  std::vector<Eigen::Vector3d> points;
  vtkNew<vtkCellArray> triangles;
  for (const KeyframeShapes& k : keyframes) {
    for (const DetectedShape& s : k.shapes) {
      const vtkIdType base = static_cast<vtkIdType>(points.size());
      points.insert(points.end(), s.vertices_g.begin(), s.vertices_g.end());
      for (const Face& f : s.triangles) {
        const vtkIdType ids[3] = {base + f[0], base + f[1], base + f[2]};
        triangles->InsertNextCell(3, ids);
      }
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(points));
  poly->SetPolys(triangles);
  return poly;
}

namespace {

// Line cells over `points`, each point tagged with the index of the object it
// belongs to (the "object_index" array picking reads).
void AddSegment(const std::array<Eigen::Vector3d, 2>& segment, int k, std::vector<Eigen::Vector3d>& points,
                std::vector<int>& owner, vtkCellArray* lines) {
  const vtkIdType ids[2] = {static_cast<vtkIdType>(points.size()), static_cast<vtkIdType>(points.size() + 1)};
  lines->InsertNextCell(2, ids);
  points.push_back(segment[0]);
  points.push_back(segment[1]);
  owner.push_back(k);
  owner.push_back(k);
}

vtkSmartPointer<vtkPolyData> OwnedLinesPolyData(const std::vector<Eigen::Vector3d>& points,
                                                const std::vector<int>& owner, vtkCellArray* lines) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(points));
  poly->SetLines(lines);
  vtkNew<vtkIntArray> index;
  index->SetName("object_index");
  index->SetNumberOfTuples(static_cast<vtkIdType>(owner.size()));
  for (std::size_t i = 0; i < owner.size(); ++i) index->SetValue(static_cast<vtkIdType>(i), owner[i]);
  poly->GetPointData()->AddArray(index);
  return poly;
}

}  // namespace

vtkSmartPointer<vtkPolyData> SegmentsPolyData(const std::vector<std::vector<std::array<Eigen::Vector3d, 2>>>& groups) {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> owner;
  vtkNew<vtkCellArray> lines;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    for (const auto& segment : groups[k]) {
      AddSegment(segment, static_cast<int>(k), points, owner, lines);
    }
  }
  return OwnedLinesPolyData(points, owner, lines);
}

vtkSmartPointer<vtkPolyData> OutlinesPolyData(const std::vector<ObjectOutline>& outlines) {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> owner;
  vtkNew<vtkCellArray> lines;
  for (std::size_t k = 0; k < outlines.size(); ++k) {
    const ObjectOutline& o = outlines[k];
    for (const auto& loop : o.loops) {
      const vtkIdType first = static_cast<vtkIdType>(points.size());
      lines->InsertNextCell(static_cast<vtkIdType>(loop.size() + 1));
      for (std::size_t i = 0; i < loop.size(); ++i) {
        lines->InsertCellPoint(static_cast<vtkIdType>(points.size()));
        points.push_back(loop[i]);
        owner.push_back(static_cast<int>(k));
      }
      lines->InsertCellPoint(first);
    }
    for (const auto& segment : o.segments) {
      AddSegment(segment, static_cast<int>(k), points, owner, lines);
    }
  }
  return OwnedLinesPolyData(points, owner, lines);
}

vtkSmartPointer<vtkPolyData> FrustaPolyData(const std::vector<Frustum>& frusta) {
  std::vector<Eigen::Vector3d> points;
  vtkNew<vtkCellArray> lines;
  for (const Frustum& f : frusta) {
    const vtkIdType apex = static_cast<vtkIdType>(points.size());
    points.push_back(f.apex);
    for (const auto& c : f.corners) points.push_back(c);
    for (vtkIdType k = 0; k < 4; ++k) {
      const vtkIdType edge[2] = {apex, apex + 1 + k};
      lines->InsertNextCell(2, edge);
    }
    const vtkIdType rect[5] = {apex + 1, apex + 2, apex + 3, apex + 4, apex + 1};
    lines->InsertNextCell(5, rect);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(points));
  poly->SetLines(lines);
  return poly;
}

vtkSmartPointer<vtkMatrix4x4> PoseMatrix(const Pose& pose) {
  const Eigen::Matrix4d T = pose.Matrix();
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m->SetElement(r, c, T(r, c));
  }
  return m;
}

}  // namespace hull::ui
