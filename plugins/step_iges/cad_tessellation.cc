#include "step_iges/cad_tessellation.h"

#include "step_iges/step_references.h"

#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_WorkSession.hxx>
#include <algorithm>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>

namespace hull::step_iges {
namespace {

// OpenCASCADE's data exchange keeps global state (Interface_Static, the
// messenger): one file at a time.
std::mutex& OcctMutex() {
  static std::mutex m;
  return m;
}

// Collects OpenCASCADE's failure messages (a STEP syntax error with its line)
// for the error the user sees, instead of printing them.
class FailureCollector final : public Message_Printer {
 public:
  std::string Text() const { return text_; }

 protected:
  void send(const TCollection_AsciiString& message, const Message_Gravity gravity) const override {
    if (gravity < Message_Fail) return;
    const std::string m = message.ToCString();
    const auto keep = [](char c) { return c != '*' && c != ' ' && c != '\n'; };
    const auto first = std::find_if(m.begin(), m.end(), keep);
    const auto last = std::find_if(m.rbegin(), m.rend(), keep).base();
    if (first < last) text_ += (text_.empty() ? "" : "; ") + std::string(first, last);
  }

 private:
  mutable std::string text_;
};

// While alive, OpenCASCADE's messages go to a FailureCollector instead of
// standard output (which it fills with every step of a transfer).
class CollectMessages {
 public:
  CollectMessages() : collector_(new FailureCollector) {
    Message_SequenceOfPrinters& printers = Message::DefaultMessenger()->ChangePrinters();
    saved_ = printers;
    printers.Clear();
    printers.Append(collector_);
  }
  ~CollectMessages() { Message::DefaultMessenger()->ChangePrinters() = saved_; }
  CollectMessages(const CollectMessages&) = delete;
  CollectMessages& operator=(const CollectMessages&) = delete;
  // " (OpenCASCADE: ...)" with what failed, or "".
  std::string Detail() const {
    const std::string t = collector_->Text();
    return t.empty() ? "" : " (OpenCASCADE: " + t.substr(0, 300) + ")";
  }

 private:
  Handle(FailureCollector) collector_;
  Message_SequenceOfPrinters saved_;
};

const char* StatusText(IFSelect_ReturnStatus s) {
  switch (s) {
    case IFSelect_RetVoid:
      return "the file holds nothing to read";
    case IFSelect_RetError:
      return "cannot open the file, or it is not in this format";
    case IFSelect_RetFail:
      return "the file is malformed";
    case IFSelect_RetStop:
      return "reading stopped on a fatal error";
    default:
      return "unknown failure";
  }
}

int Count(const TopoDS_Shape& shape, TopAbs_ShapeEnum type) {
  int n = 0;
  for (TopExp_Explorer ex(shape, type); ex.More(); ex.Next()) ++n;
  return n;
}

// Edges that bound one face only: gaps between surface patches that were
// never sewn into a shell (seams of closed surfaces and degenerate edges
// aside). They tessellate into a mesh with holes along the patch borders.
int FreeEdges(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape faces_of;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces_of);
  int n = 0;
  for (int i = 1; i <= faces_of.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(faces_of.FindKey(i));
    const TopTools_ListOfShape& faces = faces_of(i);
    if (BRep_Tool::Degenerated(edge) || faces.Extent() != 1) continue;
    if (!BRep_Tool::IsClosed(edge, TopoDS::Face(faces.First()))) ++n;
  }
  return n;
}

std::string Format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Reads the file into a shape in OpenCASCADE's length unit; *unit receives
// the unit the file declares.
TopoDS_Shape ReadShape(const std::string& path, CadFormat format, const CollectMessages& messages, std::string* unit) {
  if (format == CadFormat::kStep) {
    // OpenCASCADE's reader follows references recursively as it loads:
    // a reference cycle must not reach it.
    RefuseReferenceCycles(path);
    STEPControl_Reader reader;
    const IFSelect_ReturnStatus status = reader.ReadFile(path.c_str());
    if (status != IFSelect_RetDone)
      throw std::runtime_error(std::string("not a readable STEP file: ") + StatusText(status) + messages.Detail());
    // OpenCASCADE keeps an entity whose parameters failed to parse, with null
    // references where the parameters were, and its translation then
    // dereferences them (a crash found by fuzzing, docs/reliability.md):
    // refuse a file with any load failure before translating.
    const Interface_CheckIterator checks = reader.WS()->ModelCheckList();
    if (!checks.IsEmpty(Standard_True)) {
      std::string first;
      int failed = 0;
      for (checks.Start(); checks.More(); checks.Next()) {
        const Handle(Interface_Check)& check = checks.Value();
        if (!check->HasFailed()) continue;
        if (failed++ == 0 && check->NbFails() > 0) {
          first = std::string(": ") + check->CFail(1) + " (entity " + std::to_string(checks.Number()) + ")";
        }
      }
      throw std::runtime_error("malformed STEP file: " + std::to_string(failed) + " entities failed to load" + first);
    }
    TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
    reader.FileUnits(lengths, angles, solid_angles);
    std::set<std::string> names;
    for (int i = 1; i <= lengths.Length(); ++i) names.insert(lengths.Value(i).ToCString());
    for (const std::string& n : names) *unit += (unit->empty() ? "" : ", ") + n;
    if (reader.TransferRoots() == 0) throw std::runtime_error("the STEP file has no shape OpenCASCADE can transfer");
    return reader.OneShape();
  }
  IGESControl_Reader reader;
  const IFSelect_ReturnStatus status = reader.ReadFile(path.c_str());
  if (status != IFSelect_RetDone)
    throw std::runtime_error(std::string("not a readable IGES file: ") + StatusText(status) + messages.Detail());
  const IGESData_GlobalSection& global = reader.IGESModel()->GlobalSection();
  if (!global.UnitName().IsNull()) *unit = global.UnitName()->ToCString();
  if (reader.TransferRoots() == 0) throw std::runtime_error("the IGES file has no shape OpenCASCADE can transfer");
  return reader.OneShape();
}

}  // namespace

plugin::ImportedMesh ReadAndTessellate(const std::string& path, CadFormat format, const TessellationOptions& options) {
  std::lock_guard<std::mutex> lock(OcctMutex());
  const CollectMessages messages;
  try {
    std::string unit;
    TopoDS_Shape shape = ReadShape(path, format, messages, &unit);
    const int faces = shape.IsNull() ? 0 : Count(shape, TopAbs_FACE);
    if (faces == 0) throw std::runtime_error("the file holds no surfaces (faces) to tessellate");
    // Shapes come in OpenCASCADE's unit (millimetres unless changed),
    // whatever the file's: the reader converted them.
    const double metres_per_unit = UnitsMethods::GetCasCadeLengthUnit() * 1e-3;
    // Patches that meet within the sewing tolerance become one shell, so
    // their tessellations share the border points and the mesh is closed.
    const int free_before = FreeEdges(shape);
    std::string free_edges = std::to_string(free_before);
    if (free_before > 0 && options.sewing_tolerance > 0) {
      BRepBuilderAPI_Sewing sewing(options.sewing_tolerance / metres_per_unit);
      sewing.Add(shape);
      sewing.Perform();
      shape = sewing.SewedShape();
      free_edges +=
          ", " + std::to_string(FreeEdges(shape)) + " after sewing at " + Format("%g", options.sewing_tolerance) + " m";
    }
    BRepMesh_IncrementalMesh mesher(shape, options.chord_tolerance / metres_per_unit, Standard_False,
                                    options.angular_tolerance, Standard_False);
    if (!mesher.IsDone()) throw std::runtime_error("OpenCASCADE could not tessellate the shape");

    plugin::ImportedMesh out;
    plugin::MeshData& m = out.mesh;
    m.soup = true;  // each face's triangulation has its own copies of its edges' points
    int unmeshed = 0;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face& face = TopoDS::Face(ex.Current());
      TopLoc_Location location;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, location);
      if (tri.IsNull() || tri->NbTriangles() == 0) {
        ++unmeshed;
        continue;
      }
      const gp_Trsf trsf = location.Transformation();
      const auto base = static_cast<std::int32_t>(m.num_vertices());
      for (int i = 1; i <= tri->NbNodes(); ++i) {
        const gp_Pnt p = tri->Node(i).Transformed(trsf);
        m.positions.insert(m.positions.end(),
                           {p.X() * metres_per_unit, p.Y() * metres_per_unit, p.Z() * metres_per_unit});
      }
      // A reversed face's triangles wind the other way round.
      const bool reversed = face.Orientation() == TopAbs_REVERSED;
      for (int t = 1; t <= tri->NbTriangles(); ++t) {
        int a = 0, b = 0, c = 0;
        tri->Triangle(t).Get(a, b, c);
        if (reversed) std::swap(b, c);
        m.triangles.insert(m.triangles.end(), {base + a - 1, base + b - 1, base + c - 1});
      }
    }
    if (m.triangles.empty()) throw std::runtime_error("no face of the shape could be tessellated");
    out.report = {
        {"format", format == CadFormat::kStep ? "STEP" : "IGES"},
        {"file unit", (unit.empty() ? std::string("(none declared)") : unit) + ", converted to metres"},
        {"surfaces", std::to_string(faces) + (unmeshed ? " (" + std::to_string(unmeshed) + " not tessellated)" : "")},
        {"free edges", free_edges},
        {"shells", std::to_string(Count(shape, TopAbs_SHELL))},
        {"solids", std::to_string(Count(shape, TopAbs_SOLID))},
        {"tessellation", std::to_string(m.num_triangles()) + " triangles at chord tolerance " +
                             Format("%g", options.chord_tolerance) + " m, angle " +
                             Format("%g", options.angular_tolerance) + " rad"},
    };
    return out;
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("OpenCASCADE: ") + e.GetMessageString() + messages.Detail());
  }
}

}  // namespace hull::step_iges
