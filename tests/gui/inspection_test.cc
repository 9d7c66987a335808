// The inspection in the window, on the demo survey: Run aligns and adjusts
// in a worker (the event loop keeps turning), the scene shows the adjusted
// landmarks, trajectory and DVL hits and places the hull by the adjusted
// x_gM; a change of sigma re-runs the adjustment warm-started and changes
// the results, a change of the model re-runs it; undo and redo bring back
// the earlier results without running anything; a cancelled run leaves the
// last good result on screen; Compare models fills the cross-section's three
// columns and the time plot. Screenshots of the new views go to the test
// output folder.
#include <QAction>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTableView>
#include <QTemporaryDir>
#include <QTimer>
#include <QUndoStack>
#include <set>
#include <string>

#include "geometry/mesh_io.h"
#include "gui_test_support.h"
#include "inspection_window.h"
#include "mapping/object_identity.h"
#include "results/mapping_files.h"
#include "ui/app/main_window.h"
#include "ui/controllers/inspection_controller.h"
#include "ui/controllers/result_exports.h"
#include "ui/jobs/job_status_widget.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/objects_panel.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/pick_info_panel.h"
#include "ui/panels/sonar_panel.h"
#include "ui/session/session.h"
#include "ui/views/cross_section_view.h"
#include "ui/views/keyframe_view.h"
#include "ui/views/profile_canvas.h"
#include "ui/views/scene_view.h"
#include "ui/views/solver_plots_view.h"

using namespace hull::ui;
using hull::ui::testing::LoadDemo;
using hull::ui::testing::OutputDir;
using hull::ui::testing::Window;

namespace {

// After a change of the object threshold h_min (issue 25.6; 5 -> 9 cm on
// the demo: 12 objects -> 8, one of them split in two): every object whose
// centroid lies within the footprint disc of a first-run object keeps that
// one's id, no id is given twice, new ones come after the first run's, and
// Details shows the selected object with the new run's values. On the demo
// fresh numbering would rename objects: the test checks that it would, so
// that it cannot pass by the ids never changing order.
void IdsFollowTheObjects(Window& win, const std::shared_ptr<const MappingRun>& first) {
  const QString selected = win.w.pickInfoPanel()->info().id;
  QVERIFY(!selected.isEmpty());
  win.Real("object_min_height")->setValue(0.09);
  HI_WAIT_IDLE(win.w.jobs(), 60000);
  const auto second = win.w.session()->mapping();
  QVERIFY(second && second != first);
  const auto& before = first->result->objects;
  const auto& after = second->result->objects;
  int max_first = 0, renamed_by_fresh_numbering = 0, kept = 0;
  std::set<std::string> ids;  // each given once
  for (const auto& o : before) max_first = std::max(max_first, hull::ObjectIdNumber(o.id));
  for (std::size_t i = 0; i < after.size(); ++i) {
    const hull::DetectedObject& o = after[i];
    const hull::DetectedObject* same = nullptr;
    for (const auto& b : before) {
      const double r = std::max({0.05, std::sqrt(b.area / M_PI), std::sqrt(o.area / M_PI)});
      if ((b.centroid_m - o.centroid_m).norm() <= r &&
          (!same || (b.centroid_m - o.centroid_m).norm() < (same->centroid_m - o.centroid_m).norm())) {
        same = &b;
      }
    }
    if (same) {
      // Its centroid within the first object's footprint disc: that one.
      QCOMPARE(QString::fromStdString(o.id), QString::fromStdString(same->id));
    }
    // Otherwise a first-run id (found on its footprint: mapping/object_identity.h) or a new one.
    kept += hull::ObjectIdNumber(o.id) <= max_first;
    QVERIFY2(ids.insert(o.id).second, o.id.c_str());
    renamed_by_fresh_numbering += o.id != "obj-" + std::to_string(i + 1);
  }
  qInfo("object_min_height 0.09 m: %zu objects (of %zu), %d kept their ids, %d would be renamed by fresh numbering",
        after.size(), before.size(), kept, renamed_by_fresh_numbering);
  QVERIFY(kept > 0);
  QVERIFY(renamed_by_fresh_numbering > 0);
  // Details follows the selected object by its id.
  const hull::ui::PickInfo& shown = win.w.pickInfoPanel()->info();
  QCOMPARE(shown.id, selected);
  const int index = hull::ui::FindDetectedObject(*second, selected);
  if (index >= 0) {
    QCOMPARE(shown.rows, hull::ui::DescribeDetectedObject(*second, index).rows);
    QCOMPARE(win.w.sceneView()->HighlightedObject(), index);
  } else {
    QVERIFY(win.w.pickInfoPanel()->rowsText().join('\n').contains(QStringLiteral("not detected")));
  }
  // Back to the first threshold: the first run's ids, from the cache.
  win.w.parameterPanel()->undoStack()->undo();
  QCOMPARE(win.w.session()->mapping(), first);
  QCOMPARE(win.w.pickInfoPanel()->info().id, selected);
}

// Exports after a run (outside the test class: it may throw, the test catches).
void ExportChecks() {
  Window win;
  QVERIFY(!win.w.action(QStringLiteral("exportModel"))->isEnabled());
  QVERIFY(win.OpenAndRun());
  QVERIFY(win.w.action(QStringLiteral("exportModel"))->isEnabled());
  const auto mapping = win.w.session()->mapping();
  QTemporaryDir dir;
  for (const char* name : {"model.ply", "model.obj", "model.stl"}) {
    win.w.exporter()->ExportModel(dir.filePath(QString::fromLatin1(name)));
  }
  win.w.exporter()->ExportObjects(dir.filePath(QStringLiteral("objects.csv")));
  win.w.exporter()->ExportZones(dir.filePath(QStringLiteral("zones.csv")));
  HI_WAIT_IDLE(win.w.jobs(), 60000);
  QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
  // The PLY keeps the per-vertex deviation; every format the geometry.
  const hull::TriangleMesh ply =
      hull::LoadMesh(QFile::encodeName(dir.filePath(QStringLiteral("model.ply"))).toStdString());
  QCOMPARE(ply.num_faces(), mapping->result->model.num_faces());
  const std::vector<double>* deviation = ply.FindScalar("deviation");
  QVERIFY(deviation && deviation->size() == ply.num_vertices());
  QCOMPARE(*deviation, *mapping->result->model.FindScalar("deviation"));
  for (const char* name : {"model.obj", "model.stl"}) {
    const hull::TriangleMesh m =
        hull::LoadMesh(QFile::encodeName(dir.filePath(QString::fromLatin1(name))).toStdString());
    QCOMPARE(m.num_faces(), mapping->result->model.num_faces());
  }
  QFile objects(dir.filePath(QStringLiteral("objects.csv")));
  QVERIFY(objects.open(QIODevice::ReadOnly));
  const QList<QByteArray> lines = objects.readAll().trimmed().split('\n');
  QCOMPARE(lines.size(), static_cast<int>(mapping->result->objects.size()) + 1);
  QVERIFY(lines[0].startsWith("id,x,y,z"));
  QFile zones(dir.filePath(QStringLiteral("zones.csv")));
  QVERIFY(zones.open(QIODevice::ReadOnly));
  QCOMPARE(zones.readAll().trimmed().split('\n').size(), static_cast<int>(mapping->result->zones.size()) + 1);
  QCOMPARE(QString::fromStdString(hull::ObjectsCsv(*mapping->result)).count('\n'),
           static_cast<int>(mapping->result->objects.size()) + 1);

  // A screenshot of every visible view, each a real picture.
  const QStringList shots = win.w.SaveAllScreenshots(dir.filePath(QStringLiteral("shots")));
  QVERIFY2(shots.size() >= 5, qPrintable(shots.join(", ")));
  QVERIFY(shots.contains(dir.filePath(QStringLiteral("shots/sceneView.png"))));
  QVERIFY(shots.contains(dir.filePath(QStringLiteral("shots/crossSectionView.png"))));
  for (const QString& shot : shots) {
    const QImage image(shot);
    QVERIFY2(!image.isNull() && image.width() > 50 && image.height() > 50, qPrintable(shot));
  }
  QVERIFY(win.errors.isEmpty());

  // The report hook sees the same results.
  const auto report = win.w.CollectReport();
  QVERIFY(report && report->up_to_date && report->mapping == mapping->result);
  QCOMPARE(report->pipeline.adjustment.landmarks.size(), win.w.session()->adjustment()->result->landmarks.size());
}

}  // namespace

class InspectionTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { LoadDemo(); }

  void runningTheDemoShowsTheAdjustment() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY(win.w.action(QStringLiteral("runInspection"))->isEnabled());
    QVERIFY(!win.w.action(QStringLiteral("compareModels"))->isEnabled());

    // The event loop keeps turning while the job runs: a 10 ms timer fires
    // throughout, with no long gap.
    int ticks = 0;
    qint64 longest_gap = 0;
    QElapsedTimer since_tick;
    QTimer timer;
    timer.setInterval(10);
    connect(&timer, &QTimer::timeout, [&] {
      if (since_tick.isValid()) longest_gap = std::max(longest_gap, since_tick.elapsed());
      since_tick.restart();
      ++ticks;
    });
    QSignalSpy progress(win.w.jobs(), &JobRunner::jobProgress);
    timer.start();
    QElapsedTimer clock;
    clock.start();
    win.w.action(QStringLiteral("runInspection"))->trigger();
    QVERIFY(win.w.jobs()->IsBusy(InspectionController::kAdjustJob));
    HI_WAIT_IDLE(win.w.jobs(), 120000);
    timer.stop();
    const qint64 elapsed = clock.elapsed();
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    QVERIFY(progress.count() > 3);
    QVERIFY2(ticks > elapsed / 40, qPrintable(QStringLiteral("%1 ticks in %2 ms").arg(ticks).arg(elapsed)));
    QVERIFY2(longest_gap < 500, qPrintable(QStringLiteral("longest gap %1 ms").arg(longest_gap)));
    qInfo("adjustment job: %lld ms, %d timer ticks, longest gap %lld ms", elapsed, ticks, longest_gap);

    const auto& run = win.w.session()->adjustment();
    QVERIFY(run && run->result && run->overlays && run->evaluation);
    QCOMPARE(run->model(), hull::SurfaceModel::kMaxMixture);
    QVERIFY(win.w.session()->alignment());
    QVERIFY(win.w.inspection()->UpToDate());
    // The method's result on the demo: labels agree with truth, the
    // cylinder keeps its height.
    QVERIFY(run->evaluation->label_agreement > 0.95);
    const auto* cylinder = run->evaluation->Object("cyl-1");
    QVERIFY(cylinder && std::abs(cylinder->mean_deviation - 0.11) < 0.015);

    // The scene: adjusted layers, the hull placed by the adjusted x_gM.
    SceneView* scene = win.w.sceneView();
    QCOMPARE(scene->Stats(SceneLayer::kAdjustedLandmarks).points,
             static_cast<long long>(run->result->landmarks.size()));
    QCOMPARE(scene->Stats(SceneLayer::kAdjustedTrajectory).points, static_cast<long long>(run->result->poses.size()));
    QCOMPARE(scene->Stats(SceneLayer::kAdjustedDvlHits).points, static_cast<long long>(run->overlays->dvl_hits.size()));
    QVERIFY(scene->Stats(SceneLayer::kAdjustedLandmarks).visible);
    QCOMPARE(win.w.session()->placement(), ModelPlacement::kAdjusted);
    QVERIFY(win.w.placementLabel()->fullText().contains(QStringLiteral("bundle adjustment")));
    QVERIFY(win.w.resultsLabel()->fullText().contains(QStringLiteral("max-mixture")));
    QVERIFY(win.w.action(QStringLiteral("compareModels"))->isEnabled());

    // Mapping followed: the heatmap replaces the plain hull, the objects
    // fill their table.
    const auto& mapping = win.w.session()->mapping();
    QVERIFY(mapping && mapping->result && !mapping->result->objects.empty());
    QCOMPARE(scene->Stats(SceneLayer::kHeatmap).cells, static_cast<long long>(mapping->result->model.num_faces()));
    QVERIFY(scene->Stats(SceneLayer::kHeatmap).visible && !scene->Stats(SceneLayer::kHull).visible);
    QVERIFY(scene->Stats(SceneLayer::kDetectedObjects).visible);
    QVERIFY(scene->LegendVisible());
    QCOMPARE(win.w.objectsPanel()->objectsTable()->model()->rowCount(),
             static_cast<int>(mapping->result->objects.size()));
    QVERIFY(win.w.objectsPanel()->zonesTable()->model()->rowCount() > 0);
    QVERIFY(win.w.keyframeView()->keyframe() >= 0);

    // Solver plots and the cross-section (only the max-mixture column yet).
    QVERIFY(win.w.solverPlotsView()->fractionPlot()->HasPoints());
    QVERIFY(win.w.solverPlotsView()->costPlot()->HasPoints());
    QVERIFY(win.w.solverPlotsView()->dvlPlot()->HasPoints());
    QVERIFY(!win.w.solverPlotsView()->timePlot()->HasPoints());
    const auto& panels = win.w.crossSectionView()->canvas()->panels();
    QCOMPARE(panels.size(), std::size_t(3));
    QVERIFY(!panels[0].present && !panels[1].present && panels[2].present);
    QVERIFY(!panels[2].profile.features.empty() && !panels[2].profile.dvl.empty());
    QVERIFY(win.w.crossSectionView()->canvas()->cadSegments() > 0);
    QVERIFY(scene->Stats(SceneLayer::kSlab).visible);

    // Picking an adjusted landmark on the cylinder shows its label and deviation.
    const auto it = std::find_if(run->overlays->landmarks.begin(), run->overlays->landmarks.end(),
                                 [](const AdjustedLandmark& l) { return l.object == "cyl-1"; });
    QVERIFY(it != run->overlays->landmarks.end());
    scene->Grab();
    const PickInfo info = scene->PickAt(*scene->WidgetPosition(it->position));
    QCOMPARE(info.kind, PickKind::kLandmark);
    const QString rows = win.w.pickInfoPanel()->rowsText().join('\n');
    QVERIFY2(rows.contains(QStringLiteral("Label")) && rows.contains(QStringLiteral("True deviation")),
             qPrintable(rows));

    win.w.statusBar()->clearMessage();
    QTest::qWait(200);
    QVERIFY(win.w.grab().toImage().save(OutputDir() + QStringLiteral("/inspection_window.png")));
  }

  void sigmaReRunsWarmAndUndoRestores() {
    Window win;
    QVERIFY(win.OpenAndRun());
    const auto first = win.w.session()->adjustment();
    QSignalSpy started(win.w.jobs(), &JobRunner::jobStarted);
    win.Real("sigma1")->setValue(0.05);
    QCOMPARE(started.count(), 1);
    QVERIFY(!win.w.inspection()->UpToDate());
    HI_WAIT_IDLE(win.w.jobs(), 120000);
    const auto second = win.w.session()->adjustment();
    QVERIFY(second && second != first);
    QVERIFY(second->warm_started);
    QCOMPARE(second->result->options.sigma1, 0.05);
    QVERIFY(win.w.inspection()->UpToDate());
    // A wider on-surface sigma moves the decision boundary out: more
    // features count as on the hull.
    QVERIFY(second->result->FractionOnSurface() > first->result->FractionOnSurface());
    hull::AdjustmentOptions wide;
    wide.sigma1 = 0.05;
    QVERIFY(
        win.w.solverPlotsView()->mixturePlot()->data().note.contains(QString::number(wide.DecisionBoundary(), 'f', 4)));

    // Undo brings back the first result at once, without a job; redo the second.
    started.clear();
    win.w.parameterPanel()->undoStack()->undo();
    QCOMPARE(win.w.session()->adjustment(), first);
    QVERIFY(win.w.inspection()->UpToDate());
    win.w.parameterPanel()->undoStack()->redo();
    QCOMPARE(win.w.session()->adjustment(), second);
    QCOMPARE(started.count(), 0);

    // The model (at the default sigmas again): a cold re-run from the alignment.
    win.w.parameterPanel()->undoStack()->undo();
    QCOMPARE(win.w.session()->adjustment(), first);
    auto* model = qobject_cast<QComboBox*>(win.w.parameterPanel()->editor(QStringLiteral("model")));
    model->setCurrentIndex(model->findData(QStringLiteral("all-on-surface")));
    QCOMPARE(started.count(), 1);
    HI_WAIT_IDLE(win.w.jobs(), 120000);
    const auto third = win.w.session()->adjustment();
    QCOMPARE(third->model(), hull::SurfaceModel::kAllOnSurface);
    QVERIFY(!third->warm_started);
    // All on the surface pulls the cylinder's features toward the hull.
    QVERIFY(third->evaluation->Object("cyl-1")->mean_deviation < first->evaluation->Object("cyl-1")->mean_deviation);
    QVERIFY(win.errors.isEmpty());
  }

  void tauReRunsMappingOnlyAndUndoRestoresIt() {
    Window win;
    QVERIFY(win.OpenAndRun());
    const auto adjustment = win.w.session()->adjustment();
    const auto first = win.w.session()->mapping();
    QVERIFY(first);
    QSignalSpy started(win.w.jobs(), &JobRunner::jobStarted);
    QElapsedTimer clock;
    clock.start();
    win.Real("tau")->setValue(0.06);
    QCOMPARE(started.count(), 1);
    QCOMPARE(started.at(0).at(1).toString(), InspectionController::kMapJob);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    qInfo("mapping re-run after a change of tau: %lld ms", clock.elapsed());
    const auto second = win.w.session()->mapping();
    QVERIFY(second && second != first);
    QCOMPARE(win.w.session()->adjustment(), adjustment);  // not re-adjusted
    QCOMPARE(win.w.inspection()->mappers(), std::size_t(1));
    QCOMPARE(second->result->options.tau, 0.06);
    QVERIFY(second->result->summary.refinement_reused);
    // A higher tau clusters fewer features: fewer shapes.
    QVERIFY(second->result->summary.shapes < first->result->summary.shapes);
    QVERIFY(win.w.inspection()->UpToDate());
    started.clear();
    win.w.parameterPanel()->undoStack()->undo();
    QCOMPARE(win.w.session()->mapping(), first);
    QCOMPARE(started.count(), 0);

    // Selecting an object flies the view there and shows a view of it.
    const CameraState before = win.w.sceneView()->Camera();
    win.Raise(win.w.objectsPanel());
    QTableView* table = win.w.objectsPanel()->objectsTable();
    table->setCurrentIndex(table->model()->index(0, 0));
    const int object = table->currentIndex().data(Qt::UserRole + 2).toInt();
    const auto& o = first->result->objects[object];
    const Eigen::Vector3d centre = first->x_gM() * o.centroid_m;
    auto off = [&] {
      const CameraState c = win.w.sceneView()->Camera();
      return (Eigen::Vector3d(c.focal_point[0], c.focal_point[1], c.focal_point[2]) - centre).norm();
    };
    QTRY_VERIFY_WITH_TIMEOUT(off() < 1e-6, 5000);
    QVERIFY(!(win.w.sceneView()->Camera() == before));
    const auto& k = first->result->keyframes[win.w.keyframeView()->keyframe()];
    QVERIFY(std::binary_search(o.keyframes.begin(), o.keyframes.end(), k.id));
    QVERIFY(win.w.objectsPanel()->grab().toImage().save(OutputDir() + QStringLiteral("/objects_panel.png")));
    win.Raise(win.w.keyframeView());
    QTest::qWait(100);
    QVERIFY(win.w.keyframeView()->grab().toImage().save(OutputDir() + QStringLiteral("/keyframe_view.png")));
    QVERIFY(win.w.sceneView()->Grab().save(OutputDir() + QStringLiteral("/scene_object.png")));
    // Selecting the row highlighted the object and showed it in Details.
    QCOMPARE(win.w.sceneView()->HighlightedObject(), object);
    QCOMPARE(win.w.pickInfoPanel()->info().id, QString::fromStdString(o.id));
    QVERIFY(win.errors.isEmpty());
    IdsFollowTheObjects(win, first);
  }

  void exportsTheModelTheTablesAndScreenshots() {
    try {
      ExportChecks();
    } catch (const std::exception& e) {
      QFAIL(e.what());
    }
  }

  void aCancelledRunLeavesTheLastGoodResult() {
    Window win;
    QVERIFY(win.OpenAndRun());
    const auto good = win.w.session()->adjustment();
    const long long landmarks = win.w.sceneView()->Stats(SceneLayer::kAdjustedLandmarks).points;
    QSignalSpy cancelled(win.w.jobs(), &JobRunner::jobCancelled);
    QSignalSpy progress(win.w.jobs(), &JobRunner::jobProgress);
    win.Real("sigma0")->setValue(2.0);
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() > 0, 10000);
    QTest::mouseClick(win.w.jobStatus()->cancelButton(), Qt::LeftButton);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(win.w.session()->adjustment(), good);
    QCOMPARE(win.w.sceneView()->Stats(SceneLayer::kAdjustedLandmarks).points, landmarks);
    QVERIFY(!win.w.inspection()->UpToDate());
    QVERIFY2(win.w.resultsLabel()->fullText().contains(QStringLiteral("Run to update")),
             qPrintable(win.w.resultsLabel()->fullText()));
    QVERIFY(win.errors.isEmpty());
    // Run brings the results up to date.
    win.w.action(QStringLiteral("runInspection"))->trigger();
    HI_WAIT_IDLE(win.w.jobs(), 120000);
    QVERIFY(win.w.inspection()->UpToDate());
    QCOMPARE(win.w.session()->adjustment()->result->options.sigma0, 2.0);
  }

  // Issue 25: cancelling the first run clears the running state; the
  // status does not say "Adjusting…" for a run that is not coming, and a
  // parameter change does not start one until Run.
  void cancellingTheFirstRunLeavesTheInspectionIdle() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    QVERIFY(QTest::qWaitFor([&] { return !win.w.jobs()->IsBusy(); }, 240000));
    QSignalSpy progress(win.w.jobs(), &JobRunner::jobProgress);
    win.w.action(QStringLiteral("runInspection"))->trigger();
    QVERIFY(win.w.jobs()->IsBusy(InspectionController::kAdjustJob));
    QCOMPARE(win.w.inspection()->StatusText(), QStringLiteral("Adjusting…"));
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() > 0, 20000);
    QTest::mouseClick(win.w.jobStatus()->cancelButton(), Qt::LeftButton);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY(!win.w.session()->adjustment());
    QVERIFY2(win.w.inspection()->StatusText().isEmpty(), qPrintable(win.w.inspection()->StatusText()));
    win.Real("sigma0")->setValue(2.0);
    QVERIFY(!win.w.jobs()->IsBusy());
    QVERIFY(win.errors.isEmpty());
  }

  void compareModelsFillsTheCrossSectionAndTheTimePlot() {
    Window win;
    QVERIFY(win.OpenAndRun());
    win.w.crossSectionView()->compareButton()->click();
    QVERIFY(win.w.jobs()->IsBusy(InspectionController::kCompareJob));
    HI_WAIT_IDLE(win.w.jobs(), 240000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    QCOMPARE(win.w.session()->modelRuns().size(), std::size_t(3));
    const auto& panels = win.w.crossSectionView()->canvas()->panels();
    QVERIFY(panels[0].present && panels[1].present && panels[2].present);
    QVERIFY(win.w.solverPlotsView()->timePlot()->HasPoints());
    QCOMPARE(win.w.solverPlotsView()->costPlot()->data().series.size(), std::size_t(3));

    // The naive model ignores sigma: its run stays for the new sigma.
    const auto naive = win.w.session()->modelRuns().at(hull::SurfaceModel::kNaive);
    win.Real("sigma1")->setValue(0.03);
    HI_WAIT_IDLE(win.w.jobs(), 120000);
    QCOMPARE(win.w.session()->modelRuns().at(hull::SurfaceModel::kNaive), naive);
    QVERIFY(!win.w.session()->modelRuns().count(hull::SurfaceModel::kAllOnSurface));

    // The slab follows its controls; the views as the user guide shows them.
    SlabSpec spec = win.w.crossSectionView()->slab();
    spec.width = 0.4;
    win.w.crossSectionView()->SetSlab(spec);
    win.Raise(win.w.crossSectionView());
    QTest::qWait(200);
    QVERIFY(win.w.crossSectionView()->grab().toImage().save(OutputDir() + QStringLiteral("/cross_section.png")));
    win.Raise(win.w.solverPlotsView());
    QTest::qWait(200);
    QVERIFY(win.w.solverPlotsView()->grab().toImage().save(OutputDir() + QStringLiteral("/solver_plots.png")));
  }
};

HI_GUI_TEST_MAIN(InspectionTest)
#include "inspection_test.moc"
