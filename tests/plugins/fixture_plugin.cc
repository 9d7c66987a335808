// A plugin for the registry tests (built into tests/plugin-fixtures, never
// installed): a toy mesh format, a broken importer, an exporter and a survey
// importer, each small enough to check by hand.
//   .hitri   "HITRI" then "v x y z" and "f a b c" lines (0-based indices)
//   .hibad   any content: a triangle whose index is out of range
//   .hisum   the exporter writes "vertices N", "triangles M", "results R"
//   .hisurvey  "bundle DIR": the survey importer copies DIR's files
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "plugin/plugin_api.h"

namespace {
namespace fs = std::filesystem;
using namespace hull::plugin;

std::string Ext(const std::string& path) { return fs::path(path).extension().string(); }

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class TriImporter final : public MeshImporter {
 public:
  std::string Name() const override { return "toy triangles"; }
  std::vector<std::string> Extensions() const override { return {".hitri"}; }
  int CanRead(const std::string& path, std::string_view head) const override {
    if (head.rfind("HITRI", 0) == 0) return kByContent;  // whatever the extension (also ".stl")
    if (Ext(path) == ".hitri") return kByExtension;
    if (Ext(path) == ".stl") return kFallback + 1;  // below the built-in STL reader
    return kCannotRead;
  }
  ImportedMesh Read(const std::string& path, const Settings& settings) const override {
    const double scale = std::stod(settings.at("scale"));
    std::istringstream in(ReadAll(path));
    std::string line;
    if (!std::getline(in, line) || line != "HITRI") throw std::runtime_error("line 1: expected HITRI");
    ImportedMesh out;
    int number = 1;
    while (std::getline(in, line)) {
      ++number;
      std::istringstream ls(line);
      std::string kind;
      ls >> kind;
      if (kind == "v") {
        double x = 0, y = 0, z = 0;
        if (!(ls >> x >> y >> z)) throw std::runtime_error("line " + std::to_string(number) + ": expected x y z");
        out.mesh.positions.insert(out.mesh.positions.end(), {scale * x, scale * y, scale * z});
      } else if (kind == "f") {
        int a = 0, b = 0, c = 0;
        if (!(ls >> a >> b >> c)) throw std::runtime_error("line " + std::to_string(number) + ": expected a b c");
        out.mesh.triangles.insert(out.mesh.triangles.end(), {a, b, c});
      } else if (!kind.empty()) {
        throw std::runtime_error("line " + std::to_string(number) + ": unknown record '" + kind + "'");
      }
    }
    std::vector<double> height;
    for (std::size_t v = 0; v < out.mesh.num_vertices(); ++v) height.push_back(out.mesh.positions[3 * v + 2]);
    out.mesh.vertex_scalars.emplace_back("height", std::move(height));
    out.report = {{"unit", "toy units x " + settings.at("scale")}};
    return out;
  }
};

class BadImporter final : public MeshImporter {
 public:
  std::string Name() const override { return "broken"; }
  std::vector<std::string> Extensions() const override { return {".hibad"}; }
  int CanRead(const std::string& path, std::string_view) const override {
    return Ext(path) == ".hibad" ? kByExtension : kCannotRead;
  }
  ImportedMesh Read(const std::string&, const Settings&) const override {
    ImportedMesh out;
    out.mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    out.mesh.triangles = {0, 1, 7};
    return out;
  }
};

class SumExporter final : public ResultExporter {
 public:
  std::string Name() const override { return "summary"; }
  std::vector<std::string> Extensions() const override { return {".hisum"}; }
  Report Export(const Results& r, const std::string& target, const Settings&) const override {
    std::ofstream out(target);
    out << "vertices " << r.model.num_vertices() << "\ntriangles " << r.model.num_triangles() << "\nresults "
        << r.results_dir << "\n";
    if (!out) throw std::runtime_error("cannot write " + target);
    return {{"lines", "3"}};
  }
};

class CopySurveyImporter final : public SurveyImporter {
 public:
  std::string Name() const override { return "bundle copy"; }
  std::vector<std::string> Extensions() const override { return {".hisurvey"}; }
  int CanRead(const std::string& path, std::string_view head) const override {
    return Ext(path) == ".hisurvey" && head.rfind("bundle ", 0) == 0 ? kByContent : kCannotRead;
  }
  Report Convert(const std::string& path, const std::string& bundle_dir, const Settings&) const override {
    std::string text = ReadAll(path);
    text.erase(std::remove(text.begin(), text.end(), '\n'), text.end());
    const fs::path source = text.substr(7);
    if (!fs::is_directory(source)) throw std::runtime_error("no bundle at " + source.string());
    fs::copy(source, bundle_dir, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    return {{"copied from", source.string()}};
  }
};

class FixturePlugin final : public Plugin {
 public:
  std::string Version() const override { return "1.2.3"; }
  std::string Description() const override { return "registry test fixture"; }
  std::vector<OptionSpec> Options() const override {
    return {{"scale", "1", "coordinates times this", true, 0.001, 1000.0}, {"label", "none", "free text"}};
  }
  std::vector<std::unique_ptr<MeshImporter>> MeshImporters() const override {
    std::vector<std::unique_ptr<MeshImporter>> v;
    v.push_back(std::make_unique<TriImporter>());
    v.push_back(std::make_unique<BadImporter>());
    return v;
  }
  std::vector<std::unique_ptr<SurveyImporter>> SurveyImporters() const override {
    std::vector<std::unique_ptr<SurveyImporter>> v;
    v.push_back(std::make_unique<CopySurveyImporter>());
    return v;
  }
  std::vector<std::unique_ptr<ResultExporter>> ResultExporters() const override {
    std::vector<std::unique_ptr<ResultExporter>> v;
    v.push_back(std::make_unique<SumExporter>());
    return v;
  }
};

}  // namespace

HULLINSPECT_PLUGIN(FixturePlugin, "fixture")
