// The GUI's project files (*.hiproj, ui/session/project_file): ReadProject
// with the GUI's own parameter table and validator (CheckDefaultParameters),
// as File > Open project reads them. A project the reader accepts must also
// survive the GUI's save: written back with WriteProject (paths made
// relative, the view state, the parameters) it must read back to the same
// data; a refusal or a difference there is a finding (std::logic_error).
#include <QString>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "ui/session/parameters.h"
#include "ui/session/project_file.h"

namespace {

using hull::ui::ProjectData;

ProjectData Read(const QString& path) {
  return hull::ui::ReadProject(path, hull::ui::DefaultParameterTable(), hull::ui::CheckDefaultParameters);
}

// Which part of two projects differs ("" when none).
std::string Difference(const ProjectData& a, const ProjectData& b) {
  if (a.mesh_path != b.mesh_path)
    return "inputs.mesh: " + a.mesh_path.toStdString() + " / " + b.mesh_path.toStdString();
  if (a.bundle_path != b.bundle_path) {
    return "inputs.survey: " + a.bundle_path.toStdString() + " / " + b.bundle_path.toStdString();
  }
  for (auto it = a.parameters.begin(); it != a.parameters.end(); ++it) {
    if (b.parameters.value(it.key()) != it.value()) {
      return "parameters." + it.key().toStdString() + ": " + it.value().toString().toStdString() + " / " +
             b.parameters.value(it.key()).toString().toStdString();
    }
  }
  if (a.parameters.size() != b.parameters.size()) return "parameters: a different number of keys";
  if (a.placement != b.placement) return "model_placement";
  if (a.scene != b.scene) return "view";
  if (a.camera.has_value() != b.camera.has_value() || (a.camera && !(*a.camera == *b.camera))) return "view.camera";
  return {};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = hull::fuzz::ScratchDir();
  static const QString input = QString::fromStdString(dir + "/input.hiproj");
  static const QString saved = QString::fromStdString(dir + "/saved.hiproj");
  hull::fuzz::WriteInput(input.toStdString(), data, size);
  std::optional<ProjectData> project;
  hull::fuzz::ExpectOnlyInputError([&] { project = Read(input); });
  if (!project) return 0;
  // Saved as the GUI saves it, next to the input (same folder: the relative
  // paths resolve to the same files). Any exception here is a finding.
  hull::ui::WriteProject(saved, *project);
  const ProjectData again = Read(saved);
  const std::string difference = Difference(*project, again);
  if (!difference.empty()) throw std::logic_error("a saved project reads back differently: " + difference);
  return 0;
}
