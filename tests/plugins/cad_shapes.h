// CAD files made with OpenCASCADE for the step-iges plugin's tests (the
// tests' one OpenCASCADE unit), with the exact area, volume and bounds of
// the shape (BRepGProp on the B-rep) to hold the tessellation against.
#pragma once

#include <Eigen/Geometry>
#include <string>

namespace hull::test {

enum class CadShape {
  kBox,  // a box from the origin to `size`
  kHull  // a Wigley-like hull lofted through B-spline sections: length, beam, depth = size
};

struct CadFacts {
  double area = 0;    // in the shape's units squared
  double volume = 0;  // cubed
  Eigen::AlignedBox3d bounds;
};

// Makes the shape (in OpenCASCADE's unit, millimetres) and writes it to
// `path`: STEP when the name ends in .step/.stp (the file declares
// millimetres), IGES for .iges/.igs with `iges_unit` ("MM", "M", "IN": the
// writer converts). Returns the exact facts in millimetres.
CadFacts WriteCadShape(CadShape shape, const Eigen::Vector3d& size, const std::string& path,
                       const std::string& iges_unit = "MM");

}  // namespace hull::test
