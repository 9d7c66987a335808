// The step-iges plugin: CAD hulls in STEP (ISO 10303-21) and IGES read and
// tessellated by OpenCASCADE, so that `hullinspect-cli run --mesh hull.step`
// and the GUI take the CAD as it usually arrives.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "plugin/plugin_api.h"
#include "step_iges/cad_tessellation.h"

namespace hull::step_iges {
namespace {

std::string LowerExtension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

// An IGES file is 80-column records, the first one a Start ('S') or a flag
// ('F') record: the letter in column 73, a sequence number after it.
bool LooksLikeIges(std::string_view head) {
  const std::size_t eol = head.find_first_of("\r\n");
  if (eol == std::string_view::npos || eol < 80) return false;
  const char section = head[72];
  return (section == 'S' || section == 'F') && std::isdigit(static_cast<unsigned char>(head[79]));
}

double Number(const plugin::Settings& s, const std::string& key) { return std::stod(s.at(key)); }

class CadImporter final : public plugin::MeshImporter {
 public:
  explicit CadImporter(CadFormat format) : format_(format) {}

  std::string Name() const override {
    return format_ == CadFormat::kStep ? "STEP (OpenCASCADE)" : "IGES (OpenCASCADE)";
  }
  std::vector<std::string> Extensions() const override {
    if (format_ == CadFormat::kStep) return {".step", ".stp"};
    return {".iges", ".igs"};
  }
  int CanRead(const std::string& path, std::string_view head) const override {
    const bool content = format_ == CadFormat::kStep ? head.rfind("ISO-10303-21;", 0) == 0 : LooksLikeIges(head);
    if (content) return plugin::kByContent;
    const auto exts = Extensions();
    // By the name alone: above assimp, which claims .stp/.step for IFC only.
    return std::find(exts.begin(), exts.end(), LowerExtension(path)) != exts.end() ? plugin::kByExtension
                                                                                   : plugin::kCannotRead;
  }
  plugin::ImportedMesh Read(const std::string& path, const plugin::Settings& settings) const override {
    TessellationOptions o;
    o.chord_tolerance = Number(settings, "chord-tolerance");
    o.angular_tolerance = Number(settings, "angular-tolerance");
    return ReadAndTessellate(path, format_, o);
  }

 private:
  CadFormat format_;
};

class StepIgesPlugin final : public plugin::Plugin {
 public:
  std::string Version() const override { return HI_VERSION; }
  std::string Description() const override {
    return "STEP and IGES CAD hulls through OpenCASCADE " HI_OCCT_VERSION
           ": read in the file's unit, tessellated at a chord tolerance";
  }
  std::vector<plugin::OptionSpec> Options() const override {
    plugin::OptionSpec chord{
        "chord-tolerance", "0.005", "largest distance of a triangle from the CAD surface, metres", true, 1e-6, 10.0};
    plugin::OptionSpec angle{
        "angular-tolerance", "0.5", "largest angle between neighbouring triangles' normals, radians", true, 0.01, 1.5};
    return {chord, angle};
  }
  std::vector<std::unique_ptr<plugin::MeshImporter>> MeshImporters() const override {
    std::vector<std::unique_ptr<plugin::MeshImporter>> v;
    v.push_back(std::make_unique<CadImporter>(CadFormat::kStep));
    v.push_back(std::make_unique<CadImporter>(CadFormat::kIges));
    return v;
  }
};

}  // namespace
}  // namespace hull::step_iges

HULLINSPECT_PLUGIN(hull::step_iges::StepIgesPlugin, "step-iges")
