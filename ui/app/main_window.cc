#include "ui/app/main_window.h"

#include "plugin/plugin_registry.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QStatusBar>
#include <QTimer>
#include <QUndoStack>
#include <QUrl>
#include <algorithm>

#include "geometry/mesh_io.h"
#include "ui/app/app_setup.h"
#include "ui/app/recent_files.h"
#include "ui/controllers/document_controller.h"
#include "ui/controllers/front_end_controller.h"
#include "ui/controllers/inspection_controller.h"
#include "ui/controllers/mosaic_controller.h"
#include "ui/controllers/report_export_controller.h"
#include "ui/jobs/job_runner.h"
#include "ui/jobs/job_status_widget.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/pick_info_panel.h"
#include "ui/panels/survey_summary_panel.h"
#include "ui/session/session.h"
#include "ui/views/scene_view.h"

namespace hull::ui {

namespace {

// The open dialog's mesh formats: the built-in ones and what plugins read (STEP, IGES).
QString MeshFilter() {
  QString patterns =
      QStringLiteral("*.ply *.stl *.obj *.off *.gltf *.glb *.dae *.3ds *.fbx *.ply.gz *.stl.gz *.obj.gz *.off.gz");
  for (const std::string& e : plugin::Registry::Global().MeshExtensions())
    patterns += QStringLiteral(" *") + QString::fromStdString(e);
  return QStringLiteral("Meshes (%1);;All files (*)").arg(patterns);
}

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setObjectName(QStringLiteral("mainWindow"));
  setAcceptDrops(true);
  setDockNestingEnabled(true);
  session_ = new Session(this);
  jobs_ = new JobRunner(this);
  documents_ = new DocumentController(session_, jobs_, this);
  inspection_ = new InspectionController(session_, jobs_, this);
  front_end_ = new FrontEndController(session_, jobs_, this);
  mosaic_ = new MosaicController(session_, jobs_, this);
  report_export_ = new ReportExportController(jobs_, this);
  recent_ = new RecentFiles(this);

  scene_ = new SceneView(this);
  setCentralWidget(scene_);
  views_.push_back(scene_);
  active_view_ = scene_;

  CreateDocks();
  CreateResultDocks();
  CreateImagesDock();
  CreateMenus();
  ConnectSession();
  ConnectResults();
  ConnectWork();
  ConnectImages();

  results_label_ = new StatusLabel(640, this);
  results_label_->setObjectName(QStringLiteral("resultsLabel"));
  statusBar()->addPermanentWidget(results_label_);
  placement_label_ = new StatusLabel(420, this);
  placement_label_->setObjectName(QStringLiteral("placementLabel"));
  statusBar()->addPermanentWidget(placement_label_);
  job_status_ = new JobStatusWidget(jobs_, this);
  statusBar()->addPermanentWidget(job_status_);

  error_sink_ = [this](const QString& title, const QString& message) {
    auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();  // window-modal, does not block the caller
  };
  connect(jobs_, &JobRunner::jobFailed, this,
          [this](JobId, const QString&, const QString& title, const QString& message) {
            ReportError(title + QStringLiteral(" failed"), message);
          });
  connect(jobs_, &JobRunner::jobCancelled, this, [this](JobId, const QString&) {
    statusBar()->showMessage(QStringLiteral("Cancelled; the views keep what they showed"), 5000);
  });
  connect(jobs_, &JobRunner::busyChanged, this, [this] { UpdateActions(); });
  connect(documents_, &DocumentController::failed, this, &MainWindow::ReportError);
  connect(documents_, &DocumentController::message, this,
          [this](const QString& text) { statusBar()->showMessage(text, 8000); });
  connect(documents_, &DocumentController::opened, recent_, &RecentFiles::Add);
  connect(qApp, &QApplication::focusChanged, this, [this](QWidget*, QWidget* now) {
    for (QWidget* w = now; w; w = w->parentWidget()) {
      if (std::find(views_.begin(), views_.end(), w) != views_.end()) {
        active_view_ = w;
        return;
      }
    }
  });

  documents_->SetParameterSchema(parameters_->table(), parameters_->validator());
  ProjectHooks hooks;
  hooks.capture = [this](ProjectData* p) {
    p->parameters = parameters_->values();
    p->scene = scene_->options();
    p->camera = scene_->Camera();
  };
  hooks.restore_settings = [this](const ProjectData& p) {
    parameters_->ResetValues(p.parameters);
    layers_->SetOptions(p.scene);
    scene_->SetOptions(p.scene);
  };
  hooks.restore_camera = [this](const ProjectData& p) {
    if (p.camera) {
      scene_->SetCamera(*p.camera);
    } else {
      scene_->ResetCamera();
    }
  };
  documents_->SetProjectHooks(hooks);

  UpdatePlacement();
  UpdateTitle();
  UpdateResults();
  resize(1280, 860);
}

MainWindow::~MainWindow() = default;

void MainWindow::CreateDocks() {
  layers_ = new LayersPanel(this);
  summary_ = new SurveySummaryPanel(this);
  parameters_ = new ParameterPanel(DefaultParameterTable(), CheckDefaultParameters, this);
  pick_info_ = new PickInfoPanel(this);
  QDockWidget* layers = AddView(layers_, QStringLiteral("Layers"), Qt::LeftDockWidgetArea);
  QDockWidget* summary = AddView(summary_, QStringLiteral("Survey"), Qt::LeftDockWidgetArea);
  tabifyDockWidget(layers, summary);
  layers->raise();
  QDockWidget* params = AddView(parameters_, QStringLiteral("Parameters"), Qt::RightDockWidgetArea);
  QDockWidget* details = AddView(pick_info_, QStringLiteral("Details"), Qt::RightDockWidgetArea);
  initial_docks_ = {layers, params, details};
}

QDockWidget* MainWindow::AddView(QWidget* view, const QString& title, Qt::DockWidgetArea area) {
  auto* dock = new QDockWidget(title, this);
  dock->setObjectName(view->objectName() + QStringLiteral("Dock"));
  dock->setWidget(view);
  addDockWidget(area, dock);
  views_.push_back(view);
  if (view_menu_) {
    QAction* toggle = dock->toggleViewAction();
    toggle->setObjectName(QStringLiteral("toggle_") + dock->objectName());
    view_menu_->insertAction(dock_toggles_end_, toggle);
  }
  return dock;
}

QAction* MainWindow::NewAction(const QString& name, const QString& text, QObject* receiver, std::function<void()> slot,
                               const QKeySequence& shortcut) {
  auto* a = new QAction(text, this);
  a->setObjectName(name);
  if (!shortcut.isEmpty()) a->setShortcut(shortcut);
  connect(a, &QAction::triggered, receiver, [slot = std::move(slot)] { slot(); });
  return a;
}

QAction* MainWindow::action(const QString& object_name) const { return findChild<QAction*>(object_name); }

void MainWindow::CreateMenus() {
  QMenu* file = menuBar()->addMenu(QStringLiteral("&File"));
  file->addAction(NewAction(
      QStringLiteral("openMesh"), QStringLiteral("Open &mesh…"), this, [this] { AskOpenMesh(); },
      QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_M)));
  file->addAction(NewAction(
      QStringLiteral("openSurvey"), QStringLiteral("Open &survey…"), this, [this] { AskOpenSurvey(); },
      QKeySequence::Open));
  file->addAction(NewAction(
      QStringLiteral("openProject"), QStringLiteral("Open &project…"), this, [this] { AskOpenProject(); },
      QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_O)));
  AddResultFileEntries(file);
  file->addSeparator();
  file->addAction(NewAction(
      QStringLiteral("saveProject"), QStringLiteral("&Save project"), this, [this] { AskSaveProject(); },
      QKeySequence::Save));
  file->addAction(NewAction(
      QStringLiteral("saveProjectAs"), QStringLiteral("Save project &as…"), this, [this] { AskSaveProjectAs(); },
      QKeySequence::SaveAs));
  file->addSeparator();
  recent_menu_ = file->addMenu(QStringLiteral("&Recent files"));
  recent_menu_->setObjectName(QStringLiteral("recentMenu"));
  connect(recent_menu_, &QMenu::aboutToShow, this, &MainWindow::RebuildRecentMenu);
  QMenu* exports = file->addMenu(QStringLiteral("&Export"));
  exports->addAction(NewAction(QStringLiteral("exportPlacedHull"), QStringLiteral("&Hull placed in the survey frame…"),
                               this, [this] { AskExportHull(); }));
  AddResultExportEntries(exports);
  file->addSeparator();
  file->addAction(NewAction(
      QStringLiteral("quit"), QStringLiteral("&Quit"), this, [this] { close(); }, QKeySequence::Quit));

  QMenu* edit = menuBar()->addMenu(QStringLiteral("&Edit"));
  QAction* undo = parameters_->undoStack()->createUndoAction(this, QStringLiteral("&Undo"));
  undo->setObjectName(QStringLiteral("undo"));
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = parameters_->undoStack()->createRedoAction(this, QStringLiteral("&Redo"));
  redo->setObjectName(QStringLiteral("redo"));
  redo->setShortcut(QKeySequence::Redo);
  edit->addAction(undo);
  edit->addAction(redo);

  CreateInspectionMenu();

  view_menu_ = menuBar()->addMenu(QStringLiteral("&View"));
  dock_toggles_end_ = view_menu_->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) {
    QAction* toggle = dock->toggleViewAction();
    toggle->setObjectName(QStringLiteral("toggle_") + dock->objectName());
    view_menu_->insertAction(dock_toggles_end_, toggle);
  }
  QAction* measure = NewAction(QStringLiteral("measureDistance"), QStringLiteral("&Measure distances"), this, [this] {
    last_pick_.reset();
    scene_->SetMeasurement(std::nullopt);
  });
  measure->setCheckable(true);
  measure->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_M));
  measure->setToolTip(
      QStringLiteral("Each click in the 3-D view is measured from the one before: the distance in "
                     "Details and a line between the two points"));
  view_menu_->addAction(measure);
  view_menu_->addAction(NewAction(
      QStringLiteral("resetCamera"), QStringLiteral("Reset &camera"), this, [this] { scene_->ResetCamera(); },
      QKeySequence(Qt::CTRL | Qt::Key_R)));
  // F12 always the 3-D view (what an inspector means by a screenshot);
  // Shift+F12 the panel last clicked.
  view_menu_->addAction(NewAction(
      QStringLiteral("screenshot"), QStringLiteral("&Screenshot of the 3-D view…"), this,
      [this] { AskScreenshot(scene_); }, QKeySequence(Qt::Key_F12)));
  view_menu_->addAction(NewAction(
      QStringLiteral("screenshotPanel"), QStringLiteral("Screenshot of the active &panel…"), this,
      [this] { AskScreenshot(active_view_ ? active_view_.data() : scene_); }, QKeySequence(Qt::SHIFT | Qt::Key_F12)));

  QMenu* help = menuBar()->addMenu(QStringLiteral("&Help"));
  help->addAction(NewAction(QStringLiteral("openDemo"), QStringLiteral("Open &demo"), this, [this] {
    if (MayDiscardWork(QStringLiteral("opening the demo"))) OpenDemo();
  }));
  AddResultHelpEntries(help);
  help->addAction(
      NewAction(QStringLiteral("about"), QStringLiteral("&About HullInspect"), this, [this] { ShowAbout(); }));
}

void MainWindow::ConnectSession() {
  connect(session_, &Session::meshChanged, this, [this] {
    scene_->SetMesh(session_->mesh() ? session_->mesh()->mesh : nullptr);
    scene_->SetModelPose(session_->ModelPose());
    summary_->Update(*session_);
    UpdatePlacement();
    UpdateActions();
    UpdateTitle();
  });
  connect(session_, &Session::surveyChanged, this, [this] {
    const auto& survey = session_->survey();
    scene_->SetSurvey(survey ? survey->bundle : nullptr, survey ? survey->overlays : nullptr);
    scene_->SetModelPose(session_->ModelPose());
    pick_info_->Clear();
    summary_->Update(*session_);
    UpdatePlacement();
    UpdateActions();
    UpdateTitle();
  });
  connect(session_, &Session::placementChanged, this, [this] {
    scene_->SetModelPose(session_->ModelPose());
    summary_->Update(*session_);
    UpdatePlacement();
  });
  connect(session_, &Session::projectPathChanged, this, [this] { UpdateTitle(); });
  connect(inspection_, &InspectionController::stateChanged, this, &MainWindow::UpdateResults);
  connect(parameters_, &ParameterPanel::parametersChanged, inspection_, &InspectionController::SetParameters);
  connect(layers_, &LayersPanel::optionsChanged, this, [this](const SceneOptions& options) {
    scene_->SetOptions(options);
    const auto [lo, hi] = scene_->LegendRange();
    layers_->SetAutoRange(lo, hi);
  });
  connect(layers_, &LayersPanel::placementChosen, session_, &Session::SetPlacement);
  connect(scene_, &SceneView::picked, this, [this](const PickInfo& info) {
    PickInfo shown = info;
    // The distance tool: each pick measured from the one before.
    if (action(QStringLiteral("measureDistance"))->isChecked() && info.position) {
      if (last_pick_) {
        shown = WithDistanceFrom(info, *last_pick_);
        scene_->SetMeasurement(std::make_pair(*last_pick_, *info.position));
        statusBar()->showMessage(QStringLiteral("Distance from the previous pick: %1 m")
                                     .arg((*info.position - *last_pick_).norm(), 0, 'f', 3));
      }
      last_pick_ = info.position;
    }
    pick_info_->Show(shown);
    if (info.kind != PickKind::kNone) {
      if (auto* dock = qobject_cast<QDockWidget*>(pick_info_->parentWidget())) dock->raise();
    }
  });
  connect(parameters_, &ParameterPanel::parametersChanged, this, [this] {
    statusBar()->showMessage(QStringLiteral("Parameters changed; they are saved with the project"), 5000);
  });
}

void MainWindow::UpdatePlacement() {
  const ModelPlacement p = session_->placement();
  placement_label_->SetStatus(QStringLiteral("Model placed by: %1").arg(QString::fromUtf8(ModelPlacementLabel(p))));
  layers_->SetPlacements(session_->AvailablePlacements(), p);
  std::map<SceneLayer, bool> has_data;
  for (SceneLayer layer : AllSceneLayers()) has_data[layer] = scene_->Stats(layer).present;
  // Frusta are built on demand: available whenever a survey is open.
  has_data[SceneLayer::kFrusta] = session_->survey().has_value();
  layers_->SetLayersWithData(has_data);
  const auto [lo, hi] = scene_->LegendRange();
  layers_->SetAutoRange(lo, hi);
}

void MainWindow::UpdateTitle() {
  QString what;
  if (!session_->projectPath().isEmpty()) {
    what = QFileInfo(session_->projectPath()).fileName();
  } else if (session_->survey()) {
    what = QString::fromStdString(session_->survey()->bundle->manifest.name);
  } else if (session_->mesh()) {
    what = QFileInfo(session_->mesh()->path).fileName();
  }
  // [*]: Qt's place for the modified mark (setWindowModified).
  setWindowTitle(what.isEmpty() ? QStringLiteral("HullInspect[*]") : what + QStringLiteral("[*] — HullInspect"));
}

void MainWindow::UpdateActions() {
  if (QAction* a = action(QStringLiteral("exportPlacedHull"))) a->setEnabled(session_->mesh().has_value());
  UpdateResultActions();
}

void MainWindow::UpdateResults() {
  const QString text = inspection_->StatusText();
  results_label_->SetStatus(text);
  results_label_->setVisible(!text.isEmpty());
  results_label_->setStyleSheet(inspection_->UpToDate() || text.isEmpty() ? QString()
                                                                          : QStringLiteral("color: #b9770e;"));
  UpdateActions();
}

void MainWindow::RebuildRecentMenu() {
  recent_menu_->clear();
  const QStringList paths = recent_->paths();
  for (const QString& path : paths) {
    QAction* a = recent_menu_->addAction(QDir::toNativeSeparators(path));
    connect(a, &QAction::triggered, this, [this, path] {
      if (MayDiscardWork(QStringLiteral("opening ") + QFileInfo(path).fileName())) OpenPaths({path});
    });
  }
  if (paths.isEmpty()) {
    recent_menu_->addAction(QStringLiteral("(none yet)"))->setEnabled(false);
  } else {
    recent_menu_->addSeparator();
    recent_menu_->addAction(QStringLiteral("Clear the list"), recent_, &RecentFiles::Clear);
  }
}

void MainWindow::Launch(const LaunchOptions& options) {
  if (options.demo) {
    OpenDemo();
  } else if (!options.paths.isEmpty()) {
    OpenPaths(options.paths);
  }
}

void MainWindow::ReportError(const QString& title, const QString& message) {
  statusBar()->showMessage(title, 8000);
  if (error_sink_) error_sink_(title, message);
}

void MainWindow::OpenPaths(const QStringList& paths) {
  documents_->OpenPaths(paths, [this] { scene_->ResetCamera(); });
}

void MainWindow::OpenDemo() {
  documents_->OpenDemo([this] { scene_->ResetCamera(); });
}

bool MainWindow::SaveProject(const QString& path) {
  const bool saved = documents_->SaveProject(path);
  if (saved) MarkWorkSaved();
  return saved;
}

QImage MainWindow::GrabActiveView() { return GrabView(active_view_ ? active_view_.data() : scene_); }

QImage MainWindow::GrabView(QWidget* view) {
  if (view == scene_) return scene_->Grab();
  return view->grab().toImage();
}

void MainWindow::SetActiveView(QWidget* view) {
  if (std::find(views_.begin(), views_.end(), view) != views_.end()) active_view_ = view;
}

bool MainWindow::SaveScreenshot(const QString& path, QWidget* view) {
  const QImage image = view ? GrabView(view) : GrabActiveView();
  if (image.isNull()) {
    ReportError(QStringLiteral("Cannot take a screenshot"), QStringLiteral("The view has not been drawn yet."));
    return false;
  }
  if (!image.save(path, "PNG")) {
    ReportError(QStringLiteral("Cannot save the screenshot"),
                QStringLiteral("%1:\ncannot be written.").arg(QDir::toNativeSeparators(path)));
    return false;
  }
  statusBar()->showMessage(QStringLiteral("Saved %1").arg(QDir::toNativeSeparators(path)), 5000);
  return true;
}

void MainWindow::AskOpenMesh() {
  if (!MayDiscardWork(QStringLiteral("opening another mesh"))) return;
  const QString path = QFileDialog::getOpenFileName(this, QStringLiteral("Open a hull mesh"), QString(), MeshFilter());
  if (!path.isEmpty()) OpenPaths({path});
}

void MainWindow::AskOpenSurvey() {
  if (!MayDiscardWork(QStringLiteral("opening another survey"))) return;
  const QString path = QFileDialog::getExistingDirectory(this, QStringLiteral("Open a survey bundle folder"));
  if (!path.isEmpty()) OpenPaths({path});
}

void MainWindow::AskOpenProject() {
  if (!MayDiscardWork(QStringLiteral("opening another project"))) return;
  const QString path = QFileDialog::getOpenFileName(this, QStringLiteral("Open a project"), QString(),
                                                    QStringLiteral("HullInspect projects (*.hiproj)"));
  if (!path.isEmpty()) OpenPaths({path});
}

void MainWindow::AskSaveProject() {
  if (session_->projectPath().isEmpty()) {
    AskSaveProjectAs();
  } else {
    SaveProject(session_->projectPath());
  }
}

void MainWindow::AskSaveProjectAs() {
  QString path = QFileDialog::getSaveFileName(this, QStringLiteral("Save the project"), session_->projectPath(),
                                              QStringLiteral("HullInspect projects (*.hiproj)"));
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".hiproj");
  SaveProject(path);
}

void MainWindow::AskExportHull() {
  const QString path = QFileDialog::getSaveFileName(this, QStringLiteral("Export the hull placed in g"), QString(),
                                                    QStringLiteral("PLY (*.ply);;OBJ (*.obj);;STL (*.stl)"));
  if (!path.isEmpty()) documents_->ExportPlacedHull(path);
}

void MainWindow::AskScreenshot(QWidget* view) {
  const QString path = QFileDialog::getSaveFileName(
      this, view == scene_ ? QStringLiteral("Save a screenshot of the 3-D view") : QStringLiteral("Save a screenshot"),
      view->objectName() + QStringLiteral(".png"), QStringLiteral("PNG images (*.png)"));
  if (!path.isEmpty()) SaveScreenshot(path, view);
}

void MainWindow::ShowAbout() {
  QMessageBox::about(this, QStringLiteral("About HullInspect"),
                     QStringLiteral("<h3>HullInspect %1</h3>"
                                    "<p>Inspection of ship hulls from underwater robot surveys: model-assisted "
                                    "bundle adjustment and mapping after Ozog, Johnson-Roberson and Eustice.</p>"
                                    "<p>Qt %2, VTK 9.</p>")
                         .arg(ApplicationVersion(), QString::fromLatin1(qVersion())));
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  const QMimeData* mime = event->mimeData();
  if (!mime->hasUrls()) return;
  for (const QUrl& url : mime->urls()) {
    if (!url.isLocalFile()) return;
  }
  event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  QStringList paths;
  for (const QUrl& url : event->mimeData()->urls()) {
    if (url.isLocalFile()) paths << url.toLocalFile();
  }
  if (paths.isEmpty()) return;
  event->acceptProposedAction();
  if (MayDiscardWork(QStringLiteral("opening what was dropped"))) OpenPaths(paths);
}

void MainWindow::showEvent(QShowEvent* event) {
  QMainWindow::showEvent(event);
  if (initial_docks_.size() != 4) return;
  // Dock sizes once the window has its size: most of the room for the scene.
  const std::vector<QDockWidget*> docks = std::move(initial_docks_);
  initial_docks_.clear();
  QTimer::singleShot(0, this, [this, docks] {
    if (!layout_restored_) {
      resizeDocks({docks[0], docks[1]}, {300, 340}, Qt::Horizontal);
      resizeDocks({docks[1], docks[2]}, {500, 260}, Qt::Vertical);
      resizeDocks({docks[3]}, {300}, Qt::Vertical);  // the result views under the scene
    }
    PrepareResultDocks();
  });
}

}  // namespace hull::ui
