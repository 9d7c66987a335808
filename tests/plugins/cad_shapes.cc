#include "cad_shapes.h"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Writer.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopoDS_Wire.hxx>
#include <cmath>
#include <stdexcept>

namespace hull::test {
namespace {

// One section of the hull at x: half an ellipse from the port deck edge
// down through the keel to the starboard one, closed by the deck line.
TopoDS_Wire HullSection(double x, const Eigen::Vector3d& size) {
  const double half_beam = size.y() / 2 * (1 - std::pow(2 * x / size.x(), 2));
  const int n = 17;
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
  for (int i = 0; i < n; ++i) {
    const double t = M_PI * i / (n - 1);
    points->SetValue(i + 1, gp_Pnt(x, half_beam * std::cos(t), -size.z() * std::sin(t)));
  }
  GeomAPI_Interpolate curve(points, Standard_False, 1e-7);
  curve.Perform();
  if (!curve.IsDone()) throw std::runtime_error("cannot interpolate a hull section");
  const TopoDS_Edge bottom = BRepBuilderAPI_MakeEdge(curve.Curve());
  const TopoDS_Edge deck = BRepBuilderAPI_MakeEdge(points->Value(n), points->Value(1));
  return BRepBuilderAPI_MakeWire(bottom, deck);
}

TopoDS_Shape MakeShape(CadShape shape, const Eigen::Vector3d& size) {
  if (shape == CadShape::kBox) return BRepPrimAPI_MakeBox(size.x(), size.y(), size.z()).Shape();
  BRepOffsetAPI_ThruSections loft(Standard_True, Standard_False);
  for (int i = 0; i <= 8; ++i) loft.AddWire(HullSection(size.x() * (-0.45 + 0.9 * i / 8), size));
  loft.Build();
  if (!loft.IsDone() || !BRepCheck_Analyzer(loft.Shape()).IsValid()) {
    throw std::runtime_error("the lofted hull is not a valid solid");
  }
  return loft.Shape();
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

CadFacts WriteCadShape(CadShape kind, const Eigen::Vector3d& size, const std::string& path,
                       const std::string& iges_unit) {
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More(); it.Next()) {
    it.Value()->SetTraceLevel(Message_Fail);
  }
  const TopoDS_Shape shape = MakeShape(kind, size);
  if (EndsWith(path, ".step") || EndsWith(path, ".stp")) {
    STEPControl_Writer writer;
    if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone ||
        writer.Write(path.c_str()) != IFSelect_RetDone) {
      throw std::runtime_error("cannot write " + path);
    }
  } else {
    IGESControl_Controller::Init();
    IGESControl_Writer writer(iges_unit.c_str(), 1);  // 1: B-rep (faces, shells, solids)
    if (!writer.AddShape(shape) || !writer.Write(path.c_str())) throw std::runtime_error("cannot write " + path);
  }
  CadFacts facts;
  GProp_GProps surface, volume;
  BRepGProp::SurfaceProperties(shape, surface);
  BRepGProp::VolumeProperties(shape, volume);
  facts.area = surface.Mass();
  facts.volume = volume.Mass();
  Bnd_Box box;
  BRepBndLib::AddOptimal(shape, box, Standard_False, Standard_False);
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  facts.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
  return facts;
}

}  // namespace hull::test
