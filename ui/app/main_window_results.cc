// The main window's result views: the docks that show the inspection's
// results (cross-section, solver plots, objects and zones, keyframe) and
// their wiring to the Session, the InspectionController and the 3-D scene.
#include <QAction>
#include <QDesktopServices>
#include <QDir>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QTimer>
#include <QUrl>
#include <algorithm>

#include "plugin/plugin_registry.h"
#include "results/results_folder.h"
#include "ui/app/main_window.h"
#include "ui/controllers/document_controller.h"
#include "ui/controllers/inspection_controller.h"
#include "ui/controllers/mosaic_controller.h"
#include "ui/controllers/report_export_controller.h"
#include "ui/controllers/result_exports.h"
#include "ui/controllers/survey_compare_controller.h"
#include "ui/jobs/job_runner.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/objects_panel.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/pick_info_panel.h"
#include "ui/panels/sonar_panel.h"
#include "ui/panels/survey_compare_panel.h"
#include "ui/session/inspection_parameters.h"
#include "ui/session/session.h"
#include "ui/session/sonar_parameters.h"
#include "ui/views/cross_section_view.h"
#include "ui/views/keyframe_view.h"
#include "ui/views/scene_view.h"
#include "ui/views/solver_plots_view.h"

namespace hull::ui {

void MainWindow::CreateResultDocks() {
  cross_section_ = new CrossSectionView(this);
  solver_plots_ = new SolverPlotsView(this);
  QDockWidget* section = AddView(cross_section_, QStringLiteral("Cross-section"), Qt::BottomDockWidgetArea);
  QDockWidget* plots = AddView(solver_plots_, QStringLiteral("Solver plots"), Qt::BottomDockWidgetArea);
  objects_ = new ObjectsPanel(this);
  keyframe_view_ = new KeyframeView(this);
  QDockWidget* objects = AddView(objects_, QStringLiteral("Objects and zones"), Qt::BottomDockWidgetArea);
  QDockWidget* keyframe = AddView(keyframe_view_, QStringLiteral("Keyframe"), Qt::BottomDockWidgetArea);
  tabifyDockWidget(section, plots);
  tabifyDockWidget(plots, objects);
  sonar_ = new SonarPanel(jobs_, this);
  QDockWidget* sonar = AddView(sonar_, QStringLiteral("Sonar"), Qt::BottomDockWidgetArea);
  tabifyDockWidget(objects, keyframe);
  tabifyDockWidget(keyframe, sonar);
  compare_panel_ = new SurveyComparePanel(this);
  compare_dock_ = AddView(compare_panel_, QStringLiteral("Change between surveys"), Qt::BottomDockWidgetArea);
  tabifyDockWidget(sonar, compare_dock_);
  survey_compare_ = new SurveyCompareController(session_, jobs_, this);
  section->raise();
  section_dock_ = section;
  sonar_dock_ = sonar;
  initial_docks_.push_back(section);
  exporter_ = new ResultExporter(session_, jobs_, this);
}

void MainWindow::ConnectResults() {
  auto update_runs = [this] {
    const auto& run = session_->adjustment();
    cross_section_->SetRuns(run, session_->modelRuns());
    solver_plots_->SetRuns(run, session_->modelRuns());
  };
  connect(session_, &Session::adjustmentChanged, this, [this, update_runs] {
    const auto& run = session_->adjustment();
    if (run && !scene_->Stats(SceneLayer::kAdjustedLandmarks).present) {
      // The first results: show them rather than the survey's own
      // landmarks, DVL hits and true trajectory (still a click away).
      SceneOptions o = layers_->options();
      for (SceneLayer layer : {SceneLayer::kLandmarks, SceneLayer::kDvlHits, SceneLayer::kTrueTrajectory}) {
        o.visible[layer] = false;
      }
      layers_->SetOptions(o);
      scene_->SetOptions(o);
    }
    scene_->SetAdjusted(run ? run->overlays : nullptr);
    update_runs();
    RefreshDetails();
    UpdatePlacement();
  });
  connect(session_, &Session::modelRunsChanged, this, update_runs);
  connect(session_, &Session::mappingChanged, this, [this] {
    const auto& mapping = session_->mapping();
    if (mapping && !scene_->Stats(SceneLayer::kHeatmap).present) {
      // The first map: its heatmap covers the plain hull.
      SceneOptions o = layers_->options();
      o.visible[SceneLayer::kHull] = false;
      layers_->SetOptions(o);
      scene_->SetOptions(o);
    }
    scene_->SetMapping(mapping);
    objects_->SetMapping(mapping);
    keyframe_view_->SetMapping(mapping);
    RefreshDetails();
    UpdatePlacement();
  });
  connect(objects_, &ObjectsPanel::objectSelected, this, [this](int index) {
    const auto& mapping = session_->mapping();
    if (!mapping) return;
    keyframe_view_->ShowObject(index);
    scene_->HighlightObject(index);
    if (selecting_from_pick_) return;
    pick_info_->Show(DescribeDetectedObject(*mapping, index));
    const DetectedObject& o = mapping->result->objects[index];
    scene_->FlyTo(mapping->x_gM() * o.centroid_m, 2.0 * mapping->overlays->object_radius[index]);
  });
  connect(objects_, &ObjectsPanel::zoneSelected, this, [this](int zone) {
    const auto& mapping = session_->mapping();
    if (!mapping || zone < 0 || zone >= static_cast<int>(mapping->overlays->zone_centres.size())) return;
    const Eigen::Vector3d& c = mapping->overlays->zone_centres[zone];
    if (!c.allFinite()) return;
    scene_->FlyTo(mapping->x_gM() * c, 0.6 * mapping->overlays->zone_radius[zone]);
  });
  auto update_mesh = [this] {
    const SurveyBundle* bundle = session_->bundle();
    cross_section_->SetMesh(session_->mesh() ? session_->mesh()->mesh : nullptr,
                            bundle ? bundle->manifest.model_axes : std::nullopt);
  };
  connect(session_, &Session::meshChanged, this, update_mesh);
  connect(session_, &Session::surveyChanged, this, update_mesh);

  connect(cross_section_, &CrossSectionView::slabMoved, this,
          [this] { scene_->SetSlab(cross_section_->SlabBoxInG()); });
  connect(cross_section_, &CrossSectionView::compareRequested, inspection_, &InspectionController::CompareModels);
  connect(inspection_, &InspectionController::stateChanged, this,
          [this] { cross_section_->SetCompareEnabled(inspection_->CanCompare()); });
  connect(scene_, &SceneView::picked, this, [this](const PickInfo& info) {
    cross_section_->SetPickedPoint(info.position);
    const auto& mapping = session_->mapping();
    if (info.kind != PickKind::kDetectedObject || !mapping) return;
    const auto& objects = mapping->result->objects;
    for (int i = 0; i < static_cast<int>(objects.size()); ++i) {
      if (QString::fromStdString(objects[i].id) != info.id) continue;
      selecting_from_pick_ = true;
      objects_->SelectObject(i);
      selecting_from_pick_ = false;
    }
  });

  auto update_sigmas = [this](const ParameterValues& values) {
    const AdjustmentOptions o = AdjustmentOptionsFrom(values);
    solver_plots_->SetSigmas(o.sigma0, o.sigma1);
    // k: the significance heatmap's mask, recomputed at once (no re-run).
    const double k = MappingOptionsFrom(values).significance_k;
    scene_->SetSignificanceK(k);
    SurveyCompareOptions compare = survey_compare_->options();
    compare.significance_k = k;
    survey_compare_->SetOptions(compare);
  };
  connect(parameters_, &ParameterPanel::parametersChanged, this, update_sigmas);
  update_sigmas(parameters_->values());

  ConnectSurveyLayers();
  ConnectPanelsAndExports();
}

void MainWindow::RefreshDetails() {
  const PickInfo& shown = pick_info_->info();
  if (!shown.from_results) return;
  const auto& mapping = session_->mapping();
  const PickInfo now = RefreshPick(shown, mapping.get());
  if (now.kind == PickKind::kNone) {
    pick_info_->Clear(QStringLiteral("The results changed: click again for the values of those on screen."));
    return;
  }
  pick_info_->Show(now);
  const int index = mapping ? FindDetectedObject(*mapping, now.id) : -1;
  if (index < 0) return;
  selecting_from_pick_ = true;  // the row and the outline follow; the camera stays
  objects_->SelectObject(index);
  selecting_from_pick_ = false;
}

// The comparison and the photomosaic on screen: their layers, legends and panels.
void MainWindow::ConnectSurveyLayers() {
  connect(session_, &Session::comparisonChanged, this, [this] {
    const auto& comparison = session_->comparison();
    if (comparison && !scene_->Stats(SceneLayer::kHeightChange).present) {
      // The first comparison: its layer covers the heatmaps.
      SceneOptions o = layers_->options();
      for (SceneLayer layer :
           {SceneLayer::kHull, SceneLayer::kHeatmap, SceneLayer::kSigmaHeatmap, SceneLayer::kSignificance}) {
        o.visible[layer] = false;
      }
      o.visible[SceneLayer::kHeightChange] = true;
      layers_->SetOptions(o);
      scene_->SetOptions(o);
    }
    scene_->SetComparison(comparison);
    RefreshDetails();
    if (comparison && !session_->survey() && !session_->mesh()) scene_->ResetCamera();
    compare_panel_->SetComparison(comparison);
    compare_dock_->show();
    compare_dock_->raise();
    UpdatePlacement();
  });
  connect(session_, &Session::mosaicChanged, this, [this] {
    const auto& mosaic = session_->mosaic();
    if (mosaic && !scene_->Stats(SceneLayer::kPhotomosaic).present) {
      // The first mosaic: shown instead of the surfaces it would cover.
      SceneOptions o = layers_->options();
      for (SceneLayer layer : {SceneLayer::kHull, SceneLayer::kHeatmap, SceneLayer::kSigmaHeatmap,
                               SceneLayer::kSignificance, SceneLayer::kHeightChange}) {
        o.visible[layer] = false;
      }
      o.visible[SceneLayer::kPhotomosaic] = true;
      layers_->SetOptions(o);
      scene_->SetOptions(o);
    }
    scene_->SetMosaic(mosaic);
    if (mosaic && !session_->survey() && !session_->mesh()) scene_->ResetCamera();
    if (mosaic) {
      statusBar()->showMessage(QStringLiteral("Photomosaic: %1 triangles from %2")
                                   .arg(mosaic->faces)
                                   .arg(QDir::toNativeSeparators(QString::fromStdString(mosaic->dir))),
                               8000);
    }
    UpdatePlacement();
  });
}

// The compare and sonar panels, the exports and the report, the mosaic builder:
// their failures and messages, the actions they enable, the parameters they use.
void MainWindow::ConnectPanelsAndExports() {
  connect(compare_panel_, &SurveyComparePanel::compareRequested, this, &MainWindow::AskCompareSurveys);
  connect(compare_panel_, &SurveyComparePanel::objectSelected, this, [this](int index) {
    const auto& comparison = session_->comparison();
    if (!comparison || index < 0 || index >= static_cast<int>(comparison->comparison.objects.size())) return;
    scene_->FlyTo(session_->ModelPose() * comparison->comparison.objects[index].centroid, 0.6);
  });

  connect(sonar_, &SonarPanel::runChanged, this, [this] {
    sonar_dock_->show();
    sonar_dock_->raise();
  });
  connect(exporter_, &ResultExporter::failed, this, &MainWindow::ReportError);
  connect(exporter_, &ResultExporter::message, this,
          [this](const QString& text) { statusBar()->showMessage(text, 8000); });
  connect(session_, &Session::mappingChanged, this, &MainWindow::UpdateResultActions);
  connect(mosaic_, &MosaicController::failed, this, &MainWindow::ReportError);
  connect(mosaic_, &MosaicController::message, this,
          [this](const QString& text) { statusBar()->showMessage(text, 15000); });
  connect(mosaic_, &MosaicController::stateChanged, this, &MainWindow::UpdateResultActions);
  // The parameter table's Sonar rows: the dock runs again when they change.
  const auto sonar_tuning = [this](const ParameterValues& values) {
    sonar_->SetTuning(SonarTuningFrom(values), SonarKey(values));
  };
  connect(parameters_, &ParameterPanel::parametersChanged, this, sonar_tuning);
  sonar_tuning(parameters_->values());
  connect(report_export_, &ReportExportController::failed, this, &MainWindow::ReportError);
  connect(report_export_, &ReportExportController::message, this,
          [this](const QString& text) { statusBar()->showMessage(text, 15000); });
  connect(report_export_, &ReportExportController::exported, this, &MainWindow::UpdateResultActions);
  connect(session_, &Session::adjustmentChanged, this, &MainWindow::UpdateResultActions);
  // The Photomosaic group: used by the next build, re-runs nothing.
  connect(parameters_, &ParameterPanel::parametersChanged, mosaic_,
          [this](const ParameterValues& values) { mosaic_->SetOptions(MosaicOptionsFrom(values)); });
  mosaic_->SetOptions(MosaicOptionsFrom(parameters_->values()));
  cross_section_->SetCompareEnabled(false);
}

void MainWindow::PrepareResultDocks() {
  // The sonar view's OpenGL starts the first time its tab is shown (tens of
  // milliseconds with a software OpenGL): do it now, while the window
  // appears, rather than when the first sonar run arrives.
  sonar_dock_->raise();
  QTimer::singleShot(0, this, [this] { section_dock_->raise(); });
}

void MainWindow::CreateInspectionMenu() {
  QMenu* inspect = menuBar()->addMenu(QStringLiteral("&Inspection"));
  QAction* run = NewAction(
      QStringLiteral("runInspection"), QStringLiteral("&Run"), this, [this] { inspection_->Run(); },
      QKeySequence(Qt::Key_F5));
  run->setToolTip(QStringLiteral("Align the survey to the model, run the bundle adjustment, then map"));
  inspect->addAction(run);
  QAction* compare = NewAction(QStringLiteral("compareModels"), QStringLiteral("&Compare models"), this,
                               [this] { inspection_->CompareModels(); });
  compare->setToolTip(
      QStringLiteral("Also run the naive and all-on-surface models, for the cross-section and "
                     "the solver plots"));
  inspect->addAction(compare);
  AddImagesEntries(inspect);
  QAction* mosaic = NewAction(QStringLiteral("buildMosaic"), QStringLiteral("Build p&hotomosaic…"), this,
                              [this] { AskBuildMosaic(); });
  inspect->addAction(mosaic);
  QAction* surveys = NewAction(QStringLiteral("compareSurveys"), QStringLiteral("Compare &with…"), this,
                               [this] { AskCompareSurveys(); });
  surveys->setToolTip(
      QStringLiteral("The change between two surveys of this hull: an earlier survey's results against the map "
                     "on screen, or two results folders"));
  inspect->addAction(surveys);
  inspect->addAction(NewAction(
      QStringLiteral("cancelJobs"), QStringLiteral("C&ancel"), jobs_, [this] { jobs_->CancelAll(); },
      QKeySequence(Qt::Key_Escape)));
}

void MainWindow::AddResultFileEntries(QMenu* file) {
  file->addAction(NewAction(QStringLiteral("openSonarSequence"), QStringLiteral("Open s&onar sequence…"), this,
                            [this] { AskOpenSonarSequence(); }));
  file->addAction(NewAction(QStringLiteral("openSonarResults"), QStringLiteral("Open sonar res&ults…"), this, [this] {
    const QString folder = QFileDialog::getExistingDirectory(
        this, QStringLiteral("Open sonar results (a folder hullinspect-cli sonar wrote)"));
    if (!folder.isEmpty()) sonar_->OpenResults(folder);
  }));
  QAction* mosaic = NewAction(QStringLiteral("openMosaic"), QStringLiteral("Open p&hotomosaic…"), this, [this] {
    const QString folder = QFileDialog::getExistingDirectory(
        this, QStringLiteral("Open the photomosaic of a results folder (or its mosaic folder)"));
    if (!folder.isEmpty()) documents_->OpenMosaic(folder);
  });
  mosaic->setToolTip(
      QStringLiteral("The remeshed model textured from the camera images, as 'hullinspect-cli mosaic' wrote it"));
  file->addAction(mosaic);
}

void MainWindow::AddResultExportEntries(QMenu* exports) {
  exports->addAction(NewAction(QStringLiteral("exportModel"), QStringLiteral("&Remeshed model (PLY, OBJ, STL)…"), this,
                               [this] { AskExportResult(QStringLiteral("model")); }));
  exports->addAction(NewAction(QStringLiteral("exportObjects"), QStringLiteral("Detected &objects (CSV)…"), this,
                               [this] { AskExportResult(QStringLiteral("objects")); }));
  exports->addAction(NewAction(QStringLiteral("exportZones"), QStringLiteral("&Zones and ratings (CSV)…"), this,
                               [this] { AskExportResult(QStringLiteral("zones")); }));
  exports->addAction(NewAction(QStringLiteral("exportSonarResults"), QStringLiteral("So&nar results…"), this, [this] {
    const QString folder = QFileDialog::getExistingDirectory(this, QStringLiteral("Save the sonar results into"));
    if (folder.isEmpty()) return;
    const bool foreign = ClassifyOutputFolder(QFile::encodeName(folder).toStdString()) == OutputFolderState::kForeign;
    if (foreign && !ConfirmForeignFolder(folder, QStringLiteral("the sonar results"))) return;
    sonar_->SaveResults(folder, foreign);
  }));
  exports->addSeparator();
  exports->addAction(NewAction(QStringLiteral("exportReport"), QStringLiteral("R&eport (PDF, HTML)…"), this,
                               [this] { AskExportReport(); }));
  exports->addAction(NewAction(QStringLiteral("openLastReport"), QStringLiteral("Open the last report's &PDF"), this,
                               [this] { QDesktopServices::openUrl(QUrl::fromLocalFile(report_export_->lastPdf())); }));
  exports->addSeparator();
  exports->addAction(NewAction(QStringLiteral("exportScreenshots"), QStringLiteral("&Screenshots of every view…"), this,
                               [this] { AskExportScreenshots(); }));
}

void MainWindow::AddResultHelpEntries(QMenu* help) {
  QMenu* sonar = help->addMenu(QStringLiteral("Open &sonar demo"));
  const struct {
    const char* name;
    const char* preset;
    const char* text;
  } demos[] = {{"openSonarDemoPrism", "prism", "&Prism (the simulation of Mai et al.)"},
               {"openSonarDemoTank", "tank", "&Tank (their experiment)"},
               {"openSonarDemoAbove", "above", "&Above the object"}};
  for (const auto& d : demos) {
    const QString preset = QString::fromLatin1(d.preset);
    sonar->addAction(NewAction(QString::fromLatin1(d.name), QString::fromUtf8(d.text), this,
                               [this, preset] { sonar_->OpenDemo(preset); }));
  }
}

void MainWindow::UpdateResultActions() {
  if (QAction* a = action(QStringLiteral("runInspection"))) a->setEnabled(inspection_->CanRun());
  if (QAction* a = action(QStringLiteral("compareModels"))) a->setEnabled(inspection_->CanCompare());
  if (QAction* a = action(QStringLiteral("cancelJobs"))) a->setEnabled(jobs_->IsBusy());
  UpdateImagesActions();
  if (QAction* a = action(QStringLiteral("buildMosaic")); a && mosaic_) {
    const QString why = mosaic_->Unavailable();
    a->setEnabled(why.isEmpty() && !mosaic_->busy());
    a->setToolTip(why.isEmpty() ? QStringLiteral("Texture the remeshed model from the survey's camera images with the "
                                                 "adjusted poses, into a results folder's mosaic/")
                                : why);
  }
  if (QAction* a = action(QStringLiteral("exportReport")); a && report_export_) {
    a->setEnabled(session_->adjustment() != nullptr);  // a second export replaces one running
    a->setToolTip(session_->adjustment() ? QStringLiteral("Write the inspection report (PDF, HTML, figures) of the "
                                                          "results on screen into a folder")
                                         : QStringLiteral("Run the inspection first (Inspection ▸ Run)."));
  }
  if (QAction* a = action(QStringLiteral("openLastReport")); a && report_export_) {
    a->setEnabled(!report_export_->lastPdf().isEmpty());
  }
  for (const char* name : {"exportModel", "exportObjects", "exportZones"}) {
    if (QAction* a = action(QString::fromLatin1(name))) a->setEnabled(exporter_ && exporter_->CanExport());
  }
}

void MainWindow::AskOpenSonarSequence() {
  const QString path = QFileDialog::getExistingDirectory(this, QStringLiteral("Open an acoustic sequence folder"));
  if (!path.isEmpty()) sonar_->OpenSequence(path);
}

void MainWindow::AskCompareSurveys() {
  if (survey_compare_->CanCompareWithMapping()) {
    const QString a = QFileDialog::getExistingDirectory(
        this, QStringLiteral("Compare with: the results folder of the earlier survey (A)"));
    if (!a.isEmpty()) survey_compare_->CompareWithMapping(a);
    return;
  }
  const QString a =
      QFileDialog::getExistingDirectory(this, QStringLiteral("Compare: the results folder of the earlier survey (A)"));
  if (a.isEmpty()) return;
  const QString b =
      QFileDialog::getExistingDirectory(this, QStringLiteral("Compare: the results folder of the later survey (B)"));
  if (!b.isEmpty()) survey_compare_->CompareFolders(a, b);
}

void MainWindow::AskExportResult(const QString& what) {
  QString filter = QStringLiteral("CSV (*.csv)");
  QString name = what + QStringLiteral(".csv");
  if (what == QLatin1String("model")) {
    filter = QStringLiteral("PLY with deviation (*.ply);;OBJ (*.obj);;STL (*.stl)");
    for (const auto& p : plugin::Registry::Global().Plugins()) {  // exporter plugins: glTF, ...
      for (const auto& e : p->result_exporters) {
        QStringList patterns;
        for (const std::string& x : e->Extensions()) patterns << QStringLiteral("*") + QString::fromStdString(x);
        filter += QStringLiteral(";;%1 (%2)").arg(QString::fromStdString(e->Name()), patterns.join(QLatin1Char(' ')));
      }
    }
    name = QStringLiteral("remeshed-model.ply");
  }
  const QString path = QFileDialog::getSaveFileName(this, QStringLiteral("Export"), name, filter);
  if (path.isEmpty()) return;
  if (what == QLatin1String("model")) {
    exporter_->ExportModel(path);
  } else if (what == QLatin1String("objects")) {
    exporter_->ExportObjects(path);
  } else {
    exporter_->ExportZones(path);
  }
}

QStringList MainWindow::SaveAllScreenshots(const QString& directory) {
  QStringList written;
  if (!QDir().mkpath(directory)) {
    ReportError(QStringLiteral("Cannot save the screenshots"),
                QStringLiteral("%1:\ncannot be created.").arg(QDir::toNativeSeparators(directory)));
    return written;
  }
  for (QWidget* view : views_) {
    if (!view->isVisible()) continue;  // a closed dock or a hidden tab
    const QImage image = GrabView(view);
    const QString path = QDir(directory).filePath(view->objectName() + QStringLiteral(".png"));
    if (image.isNull() || !image.save(path, "PNG")) {
      ReportError(QStringLiteral("Cannot save a screenshot"),
                  QStringLiteral("%1:\ncannot be written.").arg(QDir::toNativeSeparators(path)));
      continue;
    }
    written << path;
  }
  statusBar()->showMessage(
      QStringLiteral("Saved %1 screenshots in %2").arg(written.size()).arg(QDir::toNativeSeparators(directory)), 8000);
  return written;
}

void MainWindow::AskExportScreenshots() {
  const QString dir = QFileDialog::getExistingDirectory(this, QStringLiteral("Save a screenshot of every view into"));
  if (!dir.isEmpty()) SaveAllScreenshots(dir);
}

void MainWindow::AskBuildMosaic() {
  QString start = mosaic_->lastFolder();
  if (start.isEmpty() && session_->survey()) start = QFileInfo(session_->survey()->path).absolutePath();
  const QString folder = QFileDialog::getExistingDirectory(
      this, QStringLiteral("Build the photomosaic into a results folder (its mosaic/ folder)"), start);
  if (folder.isEmpty()) return;
  const bool foreign = ClassifyOutputFolder(QFile::encodeName(folder).toStdString()) == OutputFolderState::kForeign;
  if (foreign && !ConfirmForeignFolder(folder, QStringLiteral("the results and the photomosaic"))) return;
  mosaic_->Build(folder, foreign);
}

// A folder of other files: the results go in beside them only when the user
// says so (hullinspect-cli's --force); nothing of theirs is replaced.
bool MainWindow::ConfirmForeignFolder(const QString& folder, const QString& what) {
  const auto answer = QMessageBox::question(
      this, QStringLiteral("Write into a folder of other files?"),
      QStringLiteral("%1 holds files HullInspect did not write. Write %2 into it anyway? Your files are kept and none "
                     "of them is replaced.")
          .arg(QDir::toNativeSeparators(folder), what));
  return answer == QMessageBox::Yes;
}

void MainWindow::AskExportReport() {
  const std::optional<ReportSource> source = CollectReport();
  if (!source) {
    ReportError(QStringLiteral("Cannot export the report"),
                QStringLiteral("There are no results to report: run the inspection first (Inspection ▸ Run)."));
    return;
  }
  if (!source->up_to_date &&
      QMessageBox::question(this, QStringLiteral("Report results of other parameters?"),
                            QStringLiteral("The results on screen were computed with other parameters than those "
                                           "now set (Inspection ▸ Run updates them). Write the report of the results "
                                           "on screen?")) != QMessageBox::Yes) {
    return;
  }
  const QString folder = QFileDialog::getExistingDirectory(
      this, QStringLiteral("Write the report (report.pdf, report.html, figures/) into the folder"));
  if (folder.isEmpty()) return;
  const bool foreign = ClassifyOutputFolder(QFile::encodeName(folder).toStdString()) == OutputFolderState::kForeign;
  if (foreign && !ConfirmForeignFolder(folder, QStringLiteral("the report"))) return;
  report_export_->Export(ReportInputsOf(*source), folder, foreign);
}

std::optional<ReportSource> MainWindow::CollectReport() const {
  return CollectReportSource(*session_, parameters_->values(), inspection_->UpToDate());
}

}  // namespace hull::ui
