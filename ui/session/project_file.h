// Project files (*.hiproj): the session saved as JSON — inputs by path
// relative to the project file, parameters, model placement and view state
// (camera, layers, colouring). Written atomically (QSaveFile: write a
// temporary file, then rename). Reading restores everything without running
// any job; the pipeline's results join the format in later versions.
#pragma once

#include <QString>
#include <optional>

#include "ui/session/parameters.h"
#include "ui/session/scene_options.h"

namespace hull::ui {

struct ProjectData {
  QString mesh_path;    // absolute ("" when none)
  QString bundle_path;  // absolute ("" when none)
  ParameterValues parameters;
  QString placement;  // ModelPlacement key (ui/session/model_placement.h; "" when unspecified)
  SceneOptions scene;
  std::optional<CameraState> camera;
};

constexpr int kProjectVersion = 1;

// Throws hull::InputError naming the file, and the line and column for
// malformed JSON or the key path ("parameters.sigma1") for a bad value.
// Parameters are checked against the table and the validator.
ProjectData ReadProject(const QString& path, const ParameterTable& table, const ParameterValidator& validator);

// Throws std::runtime_error when the file cannot be written; an existing
// project file is then left as it was.
void WriteProject(const QString& path, const ProjectData& project);

// The JSON text itself (paths made relative to project_dir).
QByteArray ProjectToJson(const ProjectData& project, const QString& project_dir);

}  // namespace hull::ui
