// hullinspect-cli export: the remeshed model of a pipeline's results in
// another format (PLY, OBJ, STL, or what an exporter plugin writes: glTF 2.0).
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "base/error.h"
#include "base/file_io.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "geometry/mesh_io.h"
#include "pipeline/model_export.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli export RESULTS --out FILE

Writes the fused, remeshed model of RESULTS (the folder 'run' wrote, holding
mapping/model.ply, or a mapping folder itself) to FILE, the format by its
extension: .ply (with the per-vertex deviation and fusions), .obj, .stl, or
a format an exporter plugin writes, e.g. .glb / .gltf (glTF 2.0 with the
deviation as vertex colour, or textured with the photomosaic when
RESULTS/mosaic/ holds one). 'hullinspect-cli plugins' lists the exporters.
--quiet is accepted, as by every command (export prints no progress).
)";

}  // namespace

int RunExport(const CommandArgs& argv) {
  Args a(argv, {"quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"out", "quiet"});
  if (a.positionals().size() != 1) throw UsageError("expected one results folder");
  if (!a.Has("out")) throw UsageError("--out FILE is required");
  namespace fs = std::filesystem;
  const std::string target = a.Get("out");
  const std::vector<std::string> formats = ModelExportExtensions();
  if (std::find(formats.begin(), formats.end(), MeshExtension(target)) == formats.end()) {
    std::string list;
    for (const std::string& f : formats) list += " " + f;
    throw UsageError("cannot write '" + MeshExtension(target) + "' files; the formats are" + list);
  }
  CheckOutputFile(target);
  const fs::path results = a.positionals()[0];
  std::error_code ec;
  const fs::path model =
      fs::exists(results / "mapping" / "model.ply", ec) ? results / "mapping" / "model.ply" : results / "model.ply";
  if (!fs::exists(model, ec)) {
    throw InputError({results.string(), 0, 0, ""}, "holds neither mapping/model.ply nor model.ply: not results");
  }
  MeshLoadOptions lo;  // as written: no welding, no reorientation
  lo.weld = false;
  lo.orient_outward = false;
  const TriangleMesh mesh = LoadMesh(model.string(), lo);
  const auto report = ExportModel(mesh, results.string(), target);
  std::printf("wrote %s (%zu vertices, %zu triangles)\n", target.c_str(), mesh.num_vertices(), mesh.num_faces());
  for (const auto& [key, value] : report) std::printf("  %-12s %s\n", key.c_str(), value.c_str());
  return kExitOk;
}

}  // namespace hull::cli
