// Opening and saving: meshes, survey bundles, the demo and project files go
// into the Session through jobs (kind "open": a newer request replaces an
// older one and inherits what it does not set itself, so opening a mesh and
// then a survey in quick succession loads both); projects are read and
// written here, their view state through hooks the main window provides.
// Errors are reported through failed(); nothing here shows a dialog.
#pragma once

#include <QObject>
#include <QString>
#include <QStringList>
#include <functional>
#include <optional>

#include "ui/jobs/job_runner.h"
#include "ui/session/parameters.h"
#include "ui/session/project_file.h"
#include "ui/session/session.h"

namespace hull::ui {

struct OpenRequest {
  QString mesh_path;     // "" keeps the current mesh (or loads the bundle's model_hint when there is none)
  QString bundle_path;   // "" keeps the current survey
  bool demo = false;     // prepare the cached demo and open its hull and bundle
  bool replace = false;  // drop the current mesh/survey the request does not set (opening a project)
  std::optional<ModelPlacement> placement;
};

// Sorted command-line or dropped paths.
struct ClassifiedPaths {
  QString mesh, bundle, project;
  QString error;  // non-empty: what cannot be opened and why
};
ClassifiedPaths ClassifyPaths(const QStringList& paths);

// How the main window saves and restores the rest of a project.
struct ProjectHooks {
  std::function<void(ProjectData*)> capture;                 // parameters, scene options, camera
  std::function<void(const ProjectData&)> restore_settings;  // before the inputs load
  std::function<void(const ProjectData&)> restore_camera;    // once they are on screen
};

class DocumentController : public QObject {
  Q_OBJECT

 public:
  static const QString kOpenJob;
  static const QString kExportJob;
  static const QString kMosaicJob;

  DocumentController(Session* session, JobRunner* jobs, QObject* parent = nullptr);

  // Where the demo is cached (default: QStandardPaths::CacheLocation).
  void SetDemoCacheRoot(const QString& root) { demo_cache_root_ = root; }
  const QString& demoCacheRoot() const { return demo_cache_root_; }
  void SetParameterSchema(ParameterTable table, ParameterValidator validator);
  void SetProjectHooks(ProjectHooks hooks) { hooks_ = std::move(hooks); }

  // `then` runs on the GUI thread once the session holds the result.
  void Open(OpenRequest request, std::function<void()> then = {});
  // Meshes, bundle folders (or their survey.json) and one .hiproj.
  void OpenPaths(const QStringList& paths, std::function<void()> then = {});
  void OpenDemo(std::function<void()> then = {});
  void OpenProject(const QString& path);
  // Writes the project (synchronously: it is small); false after failed().
  bool SaveProject(const QString& path);
  // Writes the hull transformed into g by the current placement (PLY, OBJ
  // or STL by the extension) in a job of kind "export".
  void ExportPlacedHull(const QString& path);
  // Reads the photomosaic of a results folder (its mosaic/) or of a mosaic
  // folder into the session, in a job of kind "open-mosaic".
  void OpenMosaic(const QString& folder);

 signals:
  void failed(const QString& title, const QString& message);
  void opened(const QString& path);   // each file or folder opened or saved, for Recent files
  void message(const QString& text);  // for the status bar

 private:
  Session* session_;
  JobRunner* jobs_;
  QString demo_cache_root_;
  ParameterTable table_;
  ParameterValidator validator_;
  ProjectHooks hooks_;
  // The request of the open job in flight (merged into a newer one).
  OpenRequest pending_;
  std::function<void()> pending_then_;
};

}  // namespace hull::ui
