// The main window: the 3-D scene in the centre, a dock per panel (layers,
// survey summary, pick details, parameters), the menus, drag and drop, and a
// status bar with the model placement and the job indicator (progress bar
// and Cancel). It wires the Session, the DocumentController, the JobRunner
// and the views together; the work itself happens in those.
//
// Later rounds add their views as further docks (AddView) and their jobs
// through jobs(); their results go into the Session.
#pragma once

#include <Eigen/Core>
#include <QMainWindow>
#include <QPointer>
#include <functional>
#include <optional>
#include <vector>

#include "ui/app/command_line.h"
#include "ui/jobs/status_label.h"
#include "ui/models/report_source.h"

class QAction;
class QDockWidget;
class QLabel;
class QMenu;
class QSettings;

namespace hull::ui {

class CrossSectionView;
class DocumentController;
class FrontEndController;
class ImagesView;
class InspectionController;
class JobRunner;
class JobStatusWidget;
class KeyframeView;
class LayersPanel;
class MosaicController;
class ReportExportController;
class ObjectsPanel;
class ParameterPanel;
class PickInfoPanel;
class RecentFiles;
class ResultExporter;
class SceneView;
class Session;
class SolverPlotsView;
class SonarPanel;
class SurveyComparePanel;
class SurveyCompareController;
class SurveySummaryPanel;

// Receives every error the window reports (title, message naming the file,
// line and column for bad input). The default shows a non-blocking dialog;
// tests install their own.
using ErrorSink = std::function<void(const QString& title, const QString& message)>;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Applies the command line: --demo, or meshes, a bundle, a project.
  void Launch(const LaunchOptions& options);
  // The window's geometry and docks as the last session left them
  // (window_layout.h), saved there again on close; false when `settings`
  // had none (then the docks take their default sizes). `settings` must
  // outlive the window.
  bool RestoreLayout(QSettings* settings);

  void SetErrorSink(ErrorSink sink) { error_sink_ = std::move(sink); }
  void ReportError(const QString& title, const QString& message);

  // Without dialogs (the menu entries ask for the path, then call these).
  void OpenPaths(const QStringList& paths);
  void OpenDemo();
  bool SaveProject(const QString& path);
  // PNG of `view`, or (nullptr) of the active view: the 3-D scene, or the
  // dock last clicked. F12 saves the 3-D view, Shift+F12 the active one.
  bool SaveScreenshot(const QString& path, QWidget* view = nullptr);
  // A PNG of every view (<objectName>.png) into a folder; the paths written.
  QStringList SaveAllScreenshots(const QString& directory);
  QImage GrabView(QWidget* view);
  // What a report needs of the current state (nullopt before the first run):
  // see report_source.h.
  std::optional<ReportSource> CollectReport() const;
  QImage GrabActiveView();
  void SetActiveView(QWidget* view);
  QWidget* activeView() const { return active_view_; }

  // A view as a dock, with its toggle in the View menu and as a candidate
  // for screenshots. `area` is a Qt::DockWidgetArea.
  QDockWidget* AddView(QWidget* view, const QString& title, Qt::DockWidgetArea area);

  Session* session() const { return session_; }
  JobRunner* jobs() const { return jobs_; }
  DocumentController* documents() const { return documents_; }
  InspectionController* inspection() const { return inspection_; }
  FrontEndController* frontEnd() const { return front_end_; }
  MosaicController* mosaicBuilder() const { return mosaic_; }
  ReportExportController* reportExporter() const { return report_export_; }
  ImagesView* imagesView() const { return images_; }
  SceneView* sceneView() const { return scene_; }
  LayersPanel* layersPanel() const { return layers_; }
  ParameterPanel* parameterPanel() const { return parameters_; }
  PickInfoPanel* pickInfoPanel() const { return pick_info_; }
  SurveySummaryPanel* surveyPanel() const { return summary_; }
  CrossSectionView* crossSectionView() const { return cross_section_; }
  SolverPlotsView* solverPlotsView() const { return solver_plots_; }
  ObjectsPanel* objectsPanel() const { return objects_; }
  SurveyComparePanel* comparePanel() const { return compare_panel_; }
  SurveyCompareController* surveyCompare() const { return survey_compare_; }
  KeyframeView* keyframeView() const { return keyframe_view_; }
  SonarPanel* sonarPanel() const { return sonar_; }
  ResultExporter* exporter() const { return exporter_; }
  JobStatusWidget* jobStatus() const { return job_status_; }
  StatusLabel* placementLabel() const { return placement_label_; }
  StatusLabel* resultsLabel() const { return results_label_; }
  QAction* action(const QString& object_name) const;

 protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  void showEvent(QShowEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

 private:
  void CreateDocks();
  void CreateMenus();
  void ConnectSession();
  // The inspection's result views, menus and exports (main_window_results.cc).
  void CreateResultDocks();
  void ConnectResults();
  void ConnectSurveyLayers();
  void ConnectPanelsAndExports();
  void CreateInspectionMenu();
  // The images view and the feature extraction (main_window_images.cc).
  void CreateImagesDock();
  void ConnectImages();
  void AddImagesEntries(QMenu* inspect);
  void UpdateImagesActions();
  void AddResultFileEntries(QMenu* file);
  void AddResultExportEntries(QMenu* exports);
  void AddResultHelpEntries(QMenu* help);
  void UpdateResultActions();
  void AskOpenSonarSequence();
  void AskCompareSurveys();
  void AskExportResult(const QString& what);
  void AskExportScreenshots();
  void AskBuildMosaic();
  // File > Export > Report: the report of the results on screen into a
  // folder the user chooses (a job; see controllers/report_export_controller.h).
  void AskExportReport();
  // A folder of files HullInspect did not write: true when the user agrees
  // to write `what` into it anyway (their files kept), false to stop.
  bool ConfirmForeignFolder(const QString& folder, const QString& what);
  void RebuildRecentMenu();
  void UpdatePlacement();
  // Details after the results changed: the object shown again by its id,
  // values of the earlier results dropped (RefreshPick).
  void RefreshDetails();
  void UpdateTitle();
  // main_window_work.cc: unsaved work (the parameters changed, by their undo
  // stack, or results computed since the last save or open), the title's
  // modified mark, and Save / Discard / Cancel before it would be lost;
  // MayDiscardWork is true when the caller may go on.
  void ConnectWork();
  bool HasUnsavedWork() const;
  void MarkWorkSaved();
  void UpdateModified();
  bool MayDiscardWork(const QString& action);
  void UpdateActions();
  void UpdateResults();
  QAction* NewAction(const QString& name, const QString& text, QObject* receiver, std::function<void()> slot,
                     const QKeySequence& shortcut = {});

  // Menu slots with dialogs.
  void AskOpenMesh();
  void AskOpenSurvey();
  void AskOpenProject();
  void AskSaveProject();
  void AskSaveProjectAs();
  void AskExportHull();
  void AskScreenshot(QWidget* view);
  void ShowAbout();

  Session* session_ = nullptr;
  JobRunner* jobs_ = nullptr;
  DocumentController* documents_ = nullptr;
  InspectionController* inspection_ = nullptr;
  FrontEndController* front_end_ = nullptr;
  MosaicController* mosaic_ = nullptr;
  ReportExportController* report_export_ = nullptr;
  bool results_unsaved_ = false;
  ImagesView* images_ = nullptr;
  QDockWidget* images_dock_ = nullptr;
  RecentFiles* recent_ = nullptr;
  SceneView* scene_ = nullptr;
  LayersPanel* layers_ = nullptr;
  ParameterPanel* parameters_ = nullptr;
  PickInfoPanel* pick_info_ = nullptr;
  SurveySummaryPanel* summary_ = nullptr;
  CrossSectionView* cross_section_ = nullptr;
  SolverPlotsView* solver_plots_ = nullptr;
  ObjectsPanel* objects_ = nullptr;
  SurveyComparePanel* compare_panel_ = nullptr;
  QDockWidget* compare_dock_ = nullptr;
  SurveyCompareController* survey_compare_ = nullptr;
  KeyframeView* keyframe_view_ = nullptr;
  SonarPanel* sonar_ = nullptr;
  ResultExporter* exporter_ = nullptr;
  bool selecting_from_pick_ = false;  // a row selected by a pick in the scene: no flight
  QDockWidget* section_dock_ = nullptr;
  QDockWidget* sonar_dock_ = nullptr;
  void PrepareResultDocks();  // once the window is shown
  JobStatusWidget* job_status_ = nullptr;
  StatusLabel* placement_label_ = nullptr;
  StatusLabel* results_label_ = nullptr;
  QMenu* view_menu_ = nullptr;
  QMenu* recent_menu_ = nullptr;
  QAction* dock_toggles_end_ = nullptr;       // separator after the dock toggles in View
  std::vector<QWidget*> views_;               // screenshot candidates, the scene first
  std::vector<QDockWidget*> initial_docks_;   // sized once, when first shown
  QSettings* layout_settings_ = nullptr;      // where the layout is kept (RestoreLayout)
  std::optional<Eigen::Vector3d> last_pick_;  // the distance tool's previous point (g)
  bool layout_restored_ = false;              // then the docks keep their restored sizes
  QPointer<QWidget> active_view_;
  ErrorSink error_sink_;
};

}  // namespace hull::ui
