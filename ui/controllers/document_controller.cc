#include "ui/controllers/document_controller.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>
#include <memory>
#include <utility>

#include "geometry/mesh_io.h"
#include "survey/survey_import.h"
#include "ui/jobs/error_text.h"
#include "ui/session/demo_cache.h"

namespace hull::ui {

const QString DocumentController::kOpenJob = QStringLiteral("open");
const QString DocumentController::kExportJob = QStringLiteral("export");
const QString DocumentController::kMosaicJob = QStringLiteral("open-mosaic");

namespace {

std::string Native(const QString& path) { return QFile::encodeName(path).toStdString(); }
QString FromNative(const std::string& path) { return QFile::decodeName(QByteArray::fromStdString(path)); }

// What an open job hands to the GUI thread.
struct OpenResult {
  std::optional<LoadedMesh> mesh;
  std::optional<LoadedSurvey> survey;
  bool demo_simulated = false;
};

OpenResult RunOpen(const OpenRequest& request, bool load_model_hint, const std::string& cache_root,
                   Progress& progress) {
  OpenResult r;
  std::string mesh_path = Native(request.mesh_path);
  std::string bundle_path = Native(request.bundle_path);
  double start = 0.0;
  if (request.demo) {
    SubProgress demo(progress, 0.0, 0.6);
    const DemoFiles files = PrepareDemo(cache_root, demo);
    mesh_path = files.mesh;
    bundle_path = files.directory;
    r.demo_simulated = files.simulated;
    start = 0.6;
  }
  if (!bundle_path.empty()) {
    progress.Update(start, "reading the survey bundle " + bundle_path);
    auto bundle = std::make_shared<SurveyBundle>(OpenSurveyBundle(bundle_path));
    progress.ThrowIfCancelled();
    if (mesh_path.empty() && load_model_hint) {
      const std::string hint = bundle->ModelHintPath();
      if (!hint.empty() && QFileInfo::exists(FromNative(hint))) mesh_path = hint;
    }
    progress.Update(start + 0.5 * (1 - start), "preparing the survey for display");
    auto overlays = std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*bundle));
    r.survey = LoadedSurvey{QDir::cleanPath(QFileInfo(FromNative(bundle_path)).absoluteFilePath()), std::move(bundle),
                            std::move(overlays)};
    progress.ThrowIfCancelled();
  }
  if (!mesh_path.empty()) {
    progress.Update(start + 0.7 * (1 - start), "reading the mesh " + mesh_path);
    auto mesh = std::make_shared<TriangleMesh>(LoadMesh(mesh_path));
    r.mesh = LoadedMesh{QDir::cleanPath(QFileInfo(FromNative(mesh_path)).absoluteFilePath()), std::move(mesh)};
  }
  progress.Update(1.0, "opened");
  return r;
}

QString Describe(const OpenRequest& r) {
  if (r.demo) return QStringLiteral("Open the demo survey");
  QStringList names;
  if (!r.mesh_path.isEmpty()) names << QFileInfo(r.mesh_path).fileName();
  if (!r.bundle_path.isEmpty()) names << QFileInfo(r.bundle_path).fileName();
  return QStringLiteral("Open %1").arg(names.join(QStringLiteral(" and ")));
}

}  // namespace

ClassifiedPaths ClassifyPaths(const QStringList& paths) {
  ClassifiedPaths c;
  auto put = [&c](QString& slot, const QString& path, const char* what) {
    if (!slot.isEmpty()) {
      c.error =
          QStringLiteral("Only one %1 can be opened at a time (got %2 and %3).").arg(QLatin1String(what), slot, path);
      return false;
    }
    slot = path;
    return true;
  };
  for (const QString& path : paths) {
    const QFileInfo info(path);
    if (!info.exists()) {
      c.error = QStringLiteral("%1:\nno such file or folder.").arg(QDir::toNativeSeparators(path));
      return c;
    }
    bool ok = true;
    if (info.isDir()) {
      ok = put(c.bundle, info.absoluteFilePath(), "survey bundle");
    } else if (info.fileName() == QLatin1String("survey.json")) {
      ok = put(c.bundle, info.absolutePath(), "survey bundle");
    } else if (info.suffix().compare(QLatin1String("hiproj"), Qt::CaseInsensitive) == 0) {
      ok = put(c.project, info.absoluteFilePath(), "project");
    } else if (IsMeshFile(Native(path))) {
      ok = put(c.mesh, info.absoluteFilePath(), "mesh");
    } else if (IsSurveyPath(Native(path))) {  // a survey log a plugin converts
      ok = put(c.bundle, info.absoluteFilePath(), "survey bundle");
    } else {
      c.error = QStringLiteral(
                    "%1:\nnot a mesh (PLY, STL, OBJ, OFF, glTF, … also .gz), a survey bundle folder or a .hiproj "
                    "project.")
                    .arg(QDir::toNativeSeparators(path));
      return c;
    }
    if (!ok) return c;
  }
  if (!c.project.isEmpty() && (!c.mesh.isEmpty() || !c.bundle.isEmpty())) {
    c.error = QStringLiteral("A project brings its own mesh and survey: open it alone.");
  }
  return c;
}

DocumentController::DocumentController(Session* session, JobRunner* jobs, QObject* parent)
    : QObject(parent),
      session_(session),
      jobs_(jobs),
      demo_cache_root_(QStandardPaths::writableLocation(QStandardPaths::CacheLocation)),
      table_(DefaultParameterTable()),
      validator_(CheckDefaultParameters) {}

void DocumentController::SetParameterSchema(ParameterTable table, ParameterValidator validator) {
  table_ = std::move(table);
  validator_ = std::move(validator);
}

void DocumentController::Open(OpenRequest request, std::function<void()> then) {
  if (jobs_->IsBusy(kOpenJob) && !request.demo && !pending_.demo) {
    if (request.mesh_path.isEmpty()) request.mesh_path = pending_.mesh_path;
    if (request.bundle_path.isEmpty()) request.bundle_path = pending_.bundle_path;
    if (!request.placement) request.placement = pending_.placement;
    request.replace = request.replace || pending_.replace;
    if (!then) then = pending_then_;
  }
  pending_ = request;
  pending_then_ = then;
  const bool load_hint = request.mesh_path.isEmpty() && !request.demo && !request.replace && !session_->mesh();
  const std::string cache_root = Native(demo_cache_root_);
  jobs_->Run<OpenResult>(
      kOpenJob, Describe(request),
      [request, load_hint, cache_root](Progress& p) { return RunOpen(request, load_hint, cache_root, p); },
      [this, request, then](OpenResult& r) {
        if (r.mesh) {
          session_->SetMesh(*r.mesh);
        } else if (request.replace) {
          session_->ClearMesh();
        }
        if (r.survey) {
          session_->SetSurvey(*r.survey, request.placement);
        } else if (request.replace) {
          session_->ClearSurvey();
        }
        if (!request.demo) {
          if (!request.mesh_path.isEmpty()) emit opened(request.mesh_path);
          if (!request.bundle_path.isEmpty()) emit opened(request.bundle_path);
        }
        emit message(request.demo ? (r.demo_simulated ? QStringLiteral("Demo survey simulated and opened")
                                                      : QStringLiteral("Demo survey opened (from the cache)"))
                                  : Describe(request).replace(0, 4, QStringLiteral("Opened")));
        if (then) then();
      });
}

void DocumentController::OpenPaths(const QStringList& paths, std::function<void()> then) {
  const ClassifiedPaths c = ClassifyPaths(paths);
  if (!c.error.isEmpty()) {
    emit failed(QStringLiteral("Cannot open"), c.error);
    return;
  }
  if (!c.project.isEmpty()) {
    OpenProject(c.project);
    return;
  }
  if (c.mesh.isEmpty() && c.bundle.isEmpty()) return;
  OpenRequest request;
  request.mesh_path = c.mesh;
  request.bundle_path = c.bundle;
  Open(request, std::move(then));
}

void DocumentController::OpenDemo(std::function<void()> then) {
  OpenRequest request;
  request.demo = true;
  request.replace = true;
  Open(request, std::move(then));
}

void DocumentController::OpenProject(const QString& path) {
  ProjectData project;
  try {
    project = ReadProject(path, table_, validator_);
  } catch (...) {
    emit failed(QStringLiteral("Cannot open the project"), DescribeException(std::current_exception()));
    return;
  }
  if (hooks_.restore_settings) hooks_.restore_settings(project);
  auto finish = [this, project, path] {
    session_->SetProjectPath(path);
    if (hooks_.restore_camera) hooks_.restore_camera(project);
    emit opened(path);
    emit message(QStringLiteral("Opened the project %1").arg(QFileInfo(path).fileName()));
  };
  OpenRequest request;
  request.mesh_path = project.mesh_path;
  request.bundle_path = project.bundle_path;
  request.replace = true;
  ModelPlacement placement;
  if (ModelPlacementFromKey(project.placement.toStdString(), &placement)) request.placement = placement;
  if (request.mesh_path.isEmpty() && request.bundle_path.isEmpty()) {
    session_->ClearMesh();
    session_->ClearSurvey();
    finish();
    return;
  }
  Open(request, finish);
}

bool DocumentController::SaveProject(const QString& path) {
  ProjectData project;
  if (hooks_.capture) hooks_.capture(&project);
  if (session_->mesh()) project.mesh_path = session_->mesh()->path;
  if (session_->survey()) project.bundle_path = session_->survey()->path;
  project.placement = QString::fromLatin1(ModelPlacementKey(session_->placement()));
  try {
    WriteProject(path, project);
  } catch (...) {
    emit failed(QStringLiteral("Cannot save the project"), DescribeException(std::current_exception()));
    return false;
  }
  session_->SetProjectPath(path);
  emit opened(path);
  emit message(QStringLiteral("Saved the project %1").arg(QFileInfo(path).fileName()));
  return true;
}

void DocumentController::OpenMosaic(const QString& folder) {
  const std::string dir = Native(folder);
  Session* session = session_;
  jobs_->Run<std::shared_ptr<const MosaicLayer>>(
      kMosaicJob, QStringLiteral("Opening the photomosaic of %1").arg(QFileInfo(folder).fileName()),
      [dir](Progress& progress) {
        progress.Update(0.0, "reading the photomosaic");
        return std::shared_ptr<const MosaicLayer>(std::make_shared<MosaicLayer>(LoadMosaicLayer(dir)));
      },
      [session](std::shared_ptr<const MosaicLayer>& mosaic) { session->SetMosaic(mosaic); });
}

void DocumentController::ExportPlacedHull(const QString& path) {
  if (!session_->mesh()) {
    emit failed(QStringLiteral("Cannot export"), QStringLiteral("No hull model is open."));
    return;
  }
  const std::shared_ptr<const TriangleMesh> mesh = session_->mesh()->mesh;
  const Pose x_gM = session_->ModelPose();
  const std::string target = Native(path);
  jobs_->Start(
      kExportJob, QStringLiteral("Export %1").arg(QFileInfo(path).fileName()),
      [mesh, x_gM, target](Progress& progress) {
        progress.Update(0.0, "placing the hull in g");
        TriangleMesh placed = *mesh;
        placed.Transform(x_gM);
        progress.ThrowIfCancelled();
        progress.Update(0.5, "writing " + target);
        SaveMesh(placed, target);
      },
      [this, path] {
        emit message(QStringLiteral("Exported the placed hull to %1").arg(QDir::toNativeSeparators(path)));
      });
}

}  // namespace hull::ui
