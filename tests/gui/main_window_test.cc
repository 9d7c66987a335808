// The application shell: opening the demo (simulate + load) fills the scene
// with the expected actors; picking shows details; a cancelled open leaves
// the previous state; bad files are reported (through an error sink, so no
// dialog blocks) and the window stays usable; projects round-trip; drops,
// the command line, screenshots and exports work; without a display the
// program explains itself and exits with code 2.
#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QMessageBox>
#include <QMimeData>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTimer>
#include <QUndoStack>
#include <QUrl>
#include <filesystem>

#include "geometry/mesh_io.h"
#include "gui_test_support.h"
#include "ui/app/main_window.h"
#include "ui/controllers/document_controller.h"
#include "ui/jobs/job_status_widget.h"
#include "ui/jobs/status_label.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/pick_info_panel.h"
#include "ui/panels/survey_summary_panel.h"
#include "ui/session/demo_cache.h"
#include "ui/session/session.h"
#include "ui/views/scene_view.h"

using namespace hull::ui;
using hull::ui::testing::LoadDemo;

namespace {

struct Error {
  QString title, message;
};

// A shown main window whose errors are collected instead of shown.
class Window {
 public:
  Window() {
    w.SetErrorSink([this](const QString& title, const QString& message) { errors.push_back({title, message}); });
    w.resize(1280, 860);
    w.show();
  }
  MainWindow w;
  std::vector<Error> errors;
};

void CopyFolder(const QString& from, const QString& to) {
  std::filesystem::copy(QFile::encodeName(from).toStdString(), QFile::encodeName(to).toStdString(),
                        std::filesystem::copy_options::recursive);
}

}  // namespace

class MainWindowTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { LoadDemo(); }  // the shared demo cache exists from here on

  void openingTheDemoFillsTheScene() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY2(win.errors.empty(), win.errors.empty() ? "" : qPrintable(win.errors.front().message));
    const auto& demo = LoadDemo();
    QVERIFY(win.w.session()->mesh() && win.w.session()->survey());
    SceneView* scene = win.w.sceneView();
    QCOMPARE(scene->Stats(SceneLayer::kHull).cells, static_cast<long long>(demo.mesh->num_faces()));
    QVERIFY(scene->Stats(SceneLayer::kHull).visible);
    QCOMPARE(scene->Stats(SceneLayer::kTrajectory).points, static_cast<long long>(demo.bundle->nav.size()));
    QCOMPARE(scene->Stats(SceneLayer::kTrajectory).cells, 1LL);
    QCOMPARE(scene->Stats(SceneLayer::kTrueTrajectory).points,
             static_cast<long long>(demo.bundle->truth->poses.size()));
    QCOMPARE(scene->Stats(SceneLayer::kDvlHits).points, static_cast<long long>(demo.overlays->dvl_hits.size()));
    QCOMPARE(scene->Stats(SceneLayer::kLandmarks).points, static_cast<long long>(demo.bundle->truth->landmarks.size()));
    QVERIFY(scene->Stats(SceneLayer::kTruthObjects).cells >=
            static_cast<long long>(demo.bundle->truth->objects.size()));
    QVERIFY(!scene->Stats(SceneLayer::kFrusta).present);  // on demand
    QVERIFY(!scene->LegendVisible());
    QVERIFY(win.w.placementLabel()->fullText().contains(QStringLiteral("ground truth")));
    QVERIFY(win.w.surveyPanel()->rowsText().join('\n').contains(
        QStringLiteral("Keyframes: %1").arg(demo.bundle->nav.size())));

    // Frusta on demand: one per 10th keyframe, 5 lines each.
    QCOMPARE(win.w.layersPanel()->options().frustum_stride, 10);
    win.w.layersPanel()->layerCheckBox(SceneLayer::kFrusta)->setChecked(true);
    QCOMPARE(scene->Stats(SceneLayer::kFrusta).cells, static_cast<long long>(5 * ((demo.bundle->nav.size() + 9) / 10)));
    // Colouring by deviation shows the legend with the data's range.
    auto* colouring = win.w.layersPanel()->colouringBox();
    colouring->setCurrentIndex(colouring->findData(QStringLiteral("deviation")));
    QVERIFY(scene->LegendVisible());
    QVERIFY(std::abs(scene->LegendRange().second - demo.overlays->max_deviation) < 1e-9);
    // Hiding a layer hides its actor.
    win.w.layersPanel()->layerCheckBox(SceneLayer::kDvlHits)->setChecked(false);
    QVERIFY(!scene->Stats(SceneLayer::kDvlHits).visible);
    // Placement: the guess moves the hull.
    auto* placement = win.w.layersPanel()->placementBox();
    placement->setCurrentIndex(placement->findData(QStringLiteral("guess")));
    QCOMPARE(win.w.session()->placement(), ModelPlacement::kGuess);
    QVERIFY(win.w.placementLabel()->fullText().contains(QStringLiteral("model_pose_guess")));
  }

  void pickingALandmarkShowsItsDetails() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    const auto& demo = LoadDemo();
    SceneView* scene = win.w.sceneView();
    QTest::qWait(100);
    scene->Grab();  // rendered at its size
    // A foreign landmark: it stands off the hull, nothing hides it.
    int index = -1;
    for (int i = 0; i < static_cast<int>(demo.overlays->landmarks.size()); ++i) {
      if (demo.overlays->landmarks[i].foreign()) index = i;
    }
    QVERIFY(index >= 0);
    const auto& landmark = demo.overlays->landmarks[index];
    const std::optional<QPoint> at = scene->WidgetPosition(landmark.position);
    QVERIFY(at && scene->rect().contains(*at));
    QSignalSpy picked(scene, &SceneView::picked);
    // A click (press and release in place) on the view picks.
    QWidget* vtk = scene->findChildren<QWidget*>().value(0);
    QVERIFY(vtk);
    QTest::mouseClick(vtk, Qt::LeftButton, Qt::NoModifier, vtk->mapFrom(scene, *at));
    QCOMPARE(picked.count(), 1);
    const PickInfo info = win.w.pickInfoPanel()->info();
    QCOMPARE(info.kind, PickKind::kLandmark);
    // Whatever landmark was hit is within a few pixels of the click.
    const auto hit = std::find_if(demo.overlays->landmarks.begin(), demo.overlays->landmarks.end(),
                                  [&](const LandmarkMarker& l) { return QString::number(l.id) == info.id; });
    QVERIFY(hit != demo.overlays->landmarks.end());
    QVERIFY(((*scene->WidgetPosition(hit->position)) - *at).manhattanLength() <= 12);
    QVERIFY(win.w.pickInfoPanel()->title().startsWith(QStringLiteral("Landmark")));
    QVERIFY(win.w.pickInfoPanel()->rowsText().join('\n').contains(QStringLiteral("True deviation")));

    // A keyframe on the trajectory.
    SceneOptions o = win.w.layersPanel()->options();
    o.visible[SceneLayer::kLandmarks] = false;
    o.visible[SceneLayer::kTrueTrajectory] = false;
    o.visible[SceneLayer::kTruthObjects] = false;
    win.w.layersPanel()->SetOptions(o);
    scene->SetOptions(o);
    const Eigen::Vector3d keyframe = demo.overlays->trajectory[40];
    const PickInfo k = scene->PickAt(*scene->WidgetPosition(keyframe));
    QCOMPARE(k.kind, PickKind::kKeyframe);
    QVERIFY(win.w.pickInfoPanel()->title().startsWith(QStringLiteral("Keyframe")));
  }

  void statusLinesNeverHideTheirText() {
    // A status longer than its line: elided in the middle, whole in the
    // tooltip, the line no wider than its bound (issue 25.7).
    StatusLabel label(300);
    const QString text = QStringLiteral("max-mixture: 8 iterations, 4.9 s, 91.1 % of the features on the hull; ") +
                         QStringLiteral("12 objects; parameters changed since: Run to update");
    label.SetStatus(text);
    QVERIFY(label.elided());
    QCOMPARE(label.fullText(), text);
    QCOMPARE(label.toolTip(), text);
    QVERIFY(label.text().contains(QStringLiteral("…")));
    QVERIFY(label.text().endsWith(QStringLiteral("Run to update")));
    QVERIFY(label.sizeHint().width() <= 300);
    label.SetStatus(QStringLiteral("short"));
    QVERIFY(!label.elided());
    QCOMPARE(label.text(), QStringLiteral("short"));
  }

  void theDistanceToolMeasuresBetweenTwoPicks() {
    // Measure distances on: each pick is measured from the one before (two
    // keyframes of the demo's trajectory, their distance known).
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    const auto& demo = LoadDemo();
    SceneView* scene = win.w.sceneView();
    SceneOptions o = win.w.layersPanel()->options();
    for (SceneLayer layer : {SceneLayer::kLandmarks, SceneLayer::kTrueTrajectory, SceneLayer::kTruthObjects}) {
      o.visible[layer] = false;
    }
    win.w.layersPanel()->SetOptions(o);
    scene->SetOptions(o);
    QTest::qWait(100);
    scene->Grab();
    QAction* measure = win.w.action(QStringLiteral("measureDistance"));
    QVERIFY(measure && measure->isCheckable());
    measure->trigger();
    QVERIFY(measure->isChecked());
    const PickInfo a = scene->PickAt(*scene->WidgetPosition(demo.overlays->trajectory[40]));
    QCOMPARE(a.kind, PickKind::kKeyframe);
    QVERIFY(!win.w.pickInfoPanel()->rowsText().join('\n').contains(QStringLiteral("Distance")));
    const PickInfo b = scene->PickAt(*scene->WidgetPosition(demo.overlays->trajectory[80]));
    QCOMPARE(b.kind, PickKind::kKeyframe);
    QVERIFY(a.position && b.position);
    const QString expected =
        QStringLiteral("Distance from the previous pick: %1 m").arg((*b.position - *a.position).norm(), 0, 'f', 3);
    QVERIFY2(win.w.pickInfoPanel()->rowsText().contains(expected), qPrintable(expected));
    QVERIFY(scene->MeasurementShown());
    QVERIFY(scene->Grab().save(hull::ui::testing::OutputDir() + QStringLiteral("/scene_distance.png")));
    // Off: no line, no distance.
    measure->trigger();
    QVERIFY(!scene->MeasurementShown());
    scene->PickAt(*scene->WidgetPosition(demo.overlays->trajectory[40]));
    QVERIFY(!win.w.pickInfoPanel()->rowsText().join('\n').contains(QStringLiteral("Distance")));
  }

  void aCancelledOpenLeavesThePreviousState() {
    Window win;
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    const QString mesh_before = win.w.session()->mesh()->path;
    const long long hull_cells = win.w.sceneView()->Stats(SceneLayer::kHull).cells;
    const CameraState camera = win.w.sceneView()->Camera();

    // A fresh cache: the demo must be simulated again, which takes a while.
    QTemporaryDir fresh;
    win.w.documents()->SetDemoCacheRoot(fresh.path());
    QSignalSpy progress(win.w.jobs(), &JobRunner::jobProgress);
    QSignalSpy cancelled(win.w.jobs(), &JobRunner::jobCancelled);
    QSignalSpy succeeded(win.w.jobs(), &JobRunner::jobSucceeded);
    win.w.OpenDemo();
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() > 0, 10000);
    QVERIFY(win.w.jobStatus()->isVisible());
    QTest::mouseClick(win.w.jobStatus()->cancelButton(), Qt::LeftButton);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(succeeded.count(), 0);
    QCOMPARE(win.w.session()->mesh()->path, mesh_before);
    QCOMPARE(win.w.sceneView()->Stats(SceneLayer::kHull).cells, hull_cells);
    QVERIFY(win.w.sceneView()->Camera() == camera);
    QVERIFY(win.errors.empty());
    QVERIFY(!win.w.jobStatus()->isVisible());
    // Nothing half-written is left in the cache: no partial folder, and a
    // demo folder only if it was complete before the cancel arrived.
    for (const QString& entry : QDir(fresh.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot)) {
      QCOMPARE(entry, QStringLiteral("demo-1"));
      QVERIFY(IsValidDemo(QFile::encodeName(fresh.filePath(entry)).toStdString()));
    }
  }

  void badFilesAreReportedAndTheWindowStaysUp() {
    Window win;
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    const QString mesh_before = win.w.session()->mesh()->path;
    QTemporaryDir dir;

    // A survey bundle with a bad number in nav.csv.
    const QString bundle = dir.filePath(QStringLiteral("broken-survey"));
    CopyFolder(LoadDemo().directory, bundle);
    QFile nav(bundle + QStringLiteral("/nav.csv"));
    QVERIFY(nav.open(QIODevice::ReadOnly));
    QList<QByteArray> lines = nav.readAll().split('\n');
    nav.close();
    QList<QByteArray> fields = lines[3].split(',');
    fields[4] = "deep";  // the z column of the third keyframe
    lines[3] = fields.join(',');
    QVERIFY(nav.open(QIODevice::WriteOnly | QIODevice::Truncate));
    nav.write(lines.join('\n'));
    nav.close();
    win.w.OpenPaths({bundle});
    HI_WAIT_IDLE(win.w.jobs(), 30000);
    QCOMPARE(win.errors.size(), std::size_t(1));
    QVERIFY2(win.errors[0].message.contains(QStringLiteral("nav.csv")) &&
                 win.errors[0].message.contains(QStringLiteral("line 4")) &&
                 win.errors[0].message.contains(QStringLiteral("column")),
             qPrintable(win.errors[0].message));

    // A mesh file that is not what its name says.
    const QString mesh = dir.filePath(QStringLiteral("hull.ply"));
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n2\n");
    f.close();
    win.w.OpenPaths({mesh});
    HI_WAIT_IDLE(win.w.jobs(), 30000);
    QCOMPARE(win.errors.size(), std::size_t(2));
    QVERIFY2(win.errors[1].message.contains(QStringLiteral("hull.ply")), qPrintable(win.errors[1].message));

    // Something that is no input at all, and a file that does not exist.
    const QString text = dir.filePath(QStringLiteral("notes.txt"));
    QFile t(text);
    QVERIFY(t.open(QIODevice::WriteOnly));
    t.close();
    win.w.OpenPaths({text});
    win.w.OpenPaths({dir.filePath(QStringLiteral("nothing.stl"))});
    QCOMPARE(win.errors.size(), std::size_t(4));
    QVERIFY(win.errors[2].message.contains(QStringLiteral("notes.txt")));
    QVERIFY(win.errors[3].message.contains(QStringLiteral("nothing.stl")));

    // A broken project.
    const QString project = dir.filePath(QStringLiteral("p.hiproj"));
    QFile p(project);
    QVERIFY(p.open(QIODevice::WriteOnly));
    p.write("{\n  \"format\": \"hullinspect-project\",\n  \"version\": 1,\n  \"inputs\": [\n");
    p.close();
    win.w.OpenPaths({project});
    QCOMPARE(win.errors.size(), std::size_t(5));
    QVERIFY2(win.errors[4].message.contains(QStringLiteral("p.hiproj, line")), qPrintable(win.errors[4].message));

    // Projects whose JSON is fine but a field is not, and one with a key
    // twice (tests/fuzz/regressions/project): the message names the file and
    // the field or key; the parameters on screen stay as they were.
    const ParameterValues parameters_before = win.w.parameterPanel()->values();
    auto open_project = [&](const QByteArray& text) {
      QVERIFY(p.open(QIODevice::WriteOnly | QIODevice::Truncate));
      p.write(text);
      p.close();
      win.w.OpenPaths({project});
    };
    open_project(
        "{\"format\": \"hullinspect-project\", \"version\": 1,\n \"inputs\": {\"mesh\": \"hull.ply\"},\n"
        " \"parameters\": {\"sigma1\": \"big\"}}\n");
    QCOMPARE(win.errors.size(), std::size_t(6));
    QVERIFY2(win.errors[5].message.contains(QStringLiteral("p.hiproj, line 3")) &&
                 win.errors[5].message.contains(QStringLiteral("parameters.sigma1")),
             qPrintable(win.errors[5].message));
    open_project(
        "{\"format\": \"hullinspect-project\", \"version\": 1,\n \"view\": {\"layers\": [1], \"layers\": [2]}}\n");
    QCOMPARE(win.errors.size(), std::size_t(7));
    QVERIFY2(win.errors[6].message.contains(QStringLiteral("p.hiproj, line 2")) &&
                 win.errors[6].message.contains(QStringLiteral("duplicate key \"layers\"")),
             qPrintable(win.errors[6].message));
    QCOMPARE(win.w.parameterPanel()->values(), parameters_before);

    // Still the demo on screen, and the window still opens things.
    QCOMPARE(win.w.session()->mesh()->path, mesh_before);
    win.w.OpenPaths({LoadDemo().mesh_path});
    HI_WAIT_IDLE(win.w.jobs(), 30000);
    QCOMPARE(win.errors.size(), std::size_t(7));
  }

  void projectsRoundTripWithoutRerunningAnything() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("inspection.hiproj"));
    CameraState camera;
    ParameterValues parameters;
    SceneOptions options;
    {
      Window win;
      QVERIFY(QTest::qWaitForWindowExposed(&win.w));
      win.w.OpenDemo();
      HI_WAIT_IDLE(win.w.jobs(), 60000);
      qobject_cast<QDoubleSpinBox*>(win.w.parameterPanel()->editor(QStringLiteral("sigma1")))->setValue(0.03);
      auto* colouring = win.w.layersPanel()->colouringBox();
      colouring->setCurrentIndex(colouring->findData(QStringLiteral("deviation")));
      win.w.layersPanel()->layerCheckBox(SceneLayer::kDvlHits)->setChecked(false);
      auto* placement = win.w.layersPanel()->placementBox();
      placement->setCurrentIndex(placement->findData(QStringLiteral("guess")));
      camera = win.w.sceneView()->Camera();
      camera.position[2] += 3.0;
      camera.view_angle = 24.0;
      win.w.sceneView()->SetCamera(camera);
      camera = win.w.sceneView()->Camera();
      parameters = win.w.parameterPanel()->values();
      options = win.w.sceneView()->options();
      QVERIFY(win.w.SaveProject(file));
      QCOMPARE(win.w.session()->projectPath(), file);
      QVERIFY(win.w.windowTitle().contains(QStringLiteral("inspection.hiproj")));
      QVERIFY(win.errors.empty());
    }
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    // Reopening only reads files: a demo cache that would need simulating is never touched.
    QTemporaryDir unused;
    win.w.documents()->SetDemoCacheRoot(unused.path());
    QSignalSpy started(win.w.jobs(), &JobRunner::jobStarted);
    win.w.OpenPaths({file});
    HI_WAIT_IDLE(win.w.jobs(), 30000);
    QVERIFY2(win.errors.empty(), win.errors.empty() ? "" : qPrintable(win.errors.front().message));
    QCOMPARE(started.count(), 1);
    QVERIFY(QDir(unused.path()).isEmpty());
    QCOMPARE(win.w.session()->projectPath(), file);
    QCOMPARE(win.w.session()->mesh()->path, QDir::cleanPath(LoadDemo().mesh_path));
    QCOMPARE(win.w.session()->survey()->path, QDir::cleanPath(LoadDemo().directory));
    QCOMPARE(win.w.session()->placement(), ModelPlacement::kGuess);
    QCOMPARE(win.w.parameterPanel()->values(), parameters);
    QCOMPARE(win.w.parameterPanel()->undoStack()->count(), 0);
    QVERIFY(win.w.sceneView()->options() == options);
    QVERIFY(win.w.layersPanel()->options() == options);
    const CameraState restored = win.w.sceneView()->Camera();
    for (int i = 0; i < 3; ++i) {
      QVERIFY(std::abs(restored.position[i] - camera.position[i]) < 1e-9);
      QVERIFY(std::abs(restored.focal_point[i] - camera.focal_point[i]) < 1e-9);
      QVERIFY(std::abs(restored.view_up[i] - camera.view_up[i]) < 1e-9);
    }
    QCOMPARE(restored.view_angle, 24.0);
  }

  // Work is never lost without asking (issue 25): a changed parameter marks
  // the title modified; Quit (and Open project) then asks Save / Discard /
  // Cancel: Cancel keeps the window, its parameters and undo; Discard goes
  // on; a saved project is unmodified again.
  void unsavedWorkIsAskedAboutBeforeItIsLost() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    QVERIFY(!win.w.isWindowModified());
    QVERIFY(win.w.windowTitle().contains(QStringLiteral("[*]")));  // where the mark goes
    auto* sigma1 = qobject_cast<QDoubleSpinBox*>(win.w.parameterPanel()->editor(QStringLiteral("sigma1")));
    QVERIFY(sigma1);
    sigma1->setValue(0.03);
    QVERIFY(win.w.isWindowModified());
    // Answers the next question with `button`, recording its text.
    QString asked;
    const auto answer = [&](QMessageBox::StandardButton button) {
      asked.clear();
      QTimer::singleShot(200, [&asked, button] {
        if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
          asked = box->text() + QLatin1Char(' ') + box->informativeText();
          box->grab().save(hull::ui::testing::OutputDir() + QStringLiteral("/unsaved_work_question.png"));
          box->button(button)->click();
        }
      });
    };
    answer(QMessageBox::Cancel);
    win.w.action(QStringLiteral("quit"))->trigger();
    QVERIFY2(asked.contains(QStringLiteral("the parameters were changed")), qPrintable(asked));
    QVERIFY2(asked.contains(QStringLiteral("before quitting")), qPrintable(asked));
    QVERIFY(win.w.isVisible());
    QCOMPARE(sigma1->value(), 0.03);
    QCOMPARE(win.w.parameterPanel()->undoStack()->count(), 1);
    // Undo back to the saved state: nothing to ask.
    win.w.parameterPanel()->undoStack()->undo();
    QVERIFY(!win.w.isWindowModified());
    win.w.parameterPanel()->undoStack()->redo();
    QVERIFY(win.w.isWindowModified());
    QTemporaryDir dir;
    QVERIFY(win.w.SaveProject(dir.filePath(QStringLiteral("p.hiproj"))));
    QVERIFY(!win.w.isWindowModified());
    sigma1->setValue(0.04);
    answer(QMessageBox::Discard);
    win.w.action(QStringLiteral("quit"))->trigger();
    QVERIFY(!asked.isEmpty());
    QTRY_VERIFY(!win.w.isVisible());
  }

  void theLayoutIsKeptAcrossSessions() {
    // Settings of the test's own: the first window finds none, takes the
    // default layout and leaves its own on close; the next one opens so.
    QTemporaryDir dir;
    QSettings settings(dir.filePath(QStringLiteral("layout.ini")), QSettings::IniFormat);
    QDockWidget* details = nullptr;
    QSize saved;
    {
      MainWindow first;
      QVERIFY(!first.RestoreLayout(&settings));
      first.resize(1100, 760);
      first.show();
      QVERIFY(QTest::qWaitForWindowExposed(&first));
      details = first.findChild<QDockWidget*>(QStringLiteral("pickInfoPanelDock"));
      QVERIFY(details);
      details->hide();
      QTest::qWait(50);
      saved = first.size();  // at least the docks' minimum
      QVERIFY(first.close());
    }
    QVERIFY(settings.contains(QStringLiteral("window/geometry")));
    MainWindow second;
    QVERIFY(second.RestoreLayout(&settings));
    second.show();
    QVERIFY(QTest::qWaitForWindowExposed(&second));
    QTest::qWait(50);
    QCOMPARE(second.size(), saved);
    QVERIFY(!second.findChild<QDockWidget*>(QStringLiteral("pickInfoPanelDock"))->isVisible());
    QVERIFY(second.findChild<QDockWidget*>(QStringLiteral("layersPanelDock"))->isVisible());
    // A layout of another version of the docks is not applied.
    settings.setValue(QStringLiteral("window/state"), QByteArray("not a state"));
    MainWindow third;
    QVERIFY(third.RestoreLayout(&settings));  // the geometry still applies
    third.show();
    QVERIFY(QTest::qWaitForWindowExposed(&third));
    QVERIFY(third.findChild<QDockWidget*>(QStringLiteral("pickInfoPanelDock"))->isVisible());
  }

  void droppedFilesAndTheCommandLineOpen() {
    const auto& demo = LoadDemo();
    {
      Window win;
      auto* mime = new QMimeData;
      mime->setUrls({QUrl::fromLocalFile(demo.mesh_path), QUrl::fromLocalFile(demo.directory)});
      QDragEnterEvent enter(QPoint(10, 10), Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
      enter.setAccepted(false);
      QApplication::sendEvent(&win.w, &enter);
      QVERIFY(enter.isAccepted());
      QDropEvent drop(QPointF(10, 10), Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
      QApplication::sendEvent(&win.w, &drop);
      HI_WAIT_IDLE(win.w.jobs(), 30000);
      QVERIFY(win.errors.empty());
      QVERIFY(win.w.session()->mesh() && win.w.session()->survey());
      delete mime;
    }
    {
      Window win;
      win.w.Launch(ParseCommandLine({demo.mesh_path, demo.directory}));
      HI_WAIT_IDLE(win.w.jobs(), 30000);
      QVERIFY(win.w.session()->mesh() && win.w.session()->survey());
    }
    {
      // A survey alone brings its model_hint mesh; opened one after the
      // other in quick succession, a mesh and a survey both arrive.
      Window win;
      win.w.OpenPaths({demo.directory});
      HI_WAIT_IDLE(win.w.jobs(), 30000);
      QVERIFY(win.w.session()->mesh().has_value());
      Window win2;
      win2.w.OpenPaths({demo.mesh_path});
      win2.w.OpenPaths({demo.directory});
      HI_WAIT_IDLE(win2.w.jobs(), 30000);
      QVERIFY(win2.w.session()->mesh() && win2.w.session()->survey());
    }
  }

  void screenshotsOfTheActiveView() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QTemporaryDir dir;
    const QString scene_png = dir.filePath(QStringLiteral("scene.png"));
    QVERIFY(win.w.SaveScreenshot(scene_png));
    QImage image(scene_png);
    QCOMPARE(image.size(), win.w.sceneView()->size());
    // Not a blank frame: the hull and each overlay give their colours (the
    // views draw without antialiasing: about one colour per layer).
    QSet<QRgb> colours;
    for (int y = 0; y < image.height(); y += 4) {
      for (int x = 0; x < image.width(); x += 4) colours.insert(image.pixel(x, y));
    }
    QVERIFY2(colours.size() > 5, qPrintable(QString::number(colours.size())));

    win.w.SetActiveView(win.w.parameterPanel());
    const QString panel_png = dir.filePath(QStringLiteral("parameters.png"));
    QVERIFY(win.w.SaveScreenshot(panel_png));
    QCOMPARE(QImage(panel_png).size(), win.w.parameterPanel()->size());
    // F12 is the 3-D view whatever is active; Shift+F12 the active panel.
    const QString scene_again = dir.filePath(QStringLiteral("scene-again.png"));
    QVERIFY(win.w.SaveScreenshot(scene_again, win.w.sceneView()));
    QCOMPARE(QImage(scene_again).size(), win.w.sceneView()->size());
    QCOMPARE(win.w.action(QStringLiteral("screenshot"))->shortcut(), QKeySequence(Qt::Key_F12));
    QCOMPARE(win.w.action(QStringLiteral("screenshotPanel"))->shortcut(), QKeySequence(Qt::SHIFT | Qt::Key_F12));
    QVERIFY(!win.w.SaveScreenshot(dir.filePath(QStringLiteral("no/such/folder/x.png"))));
    QCOMPARE(win.errors.size(), std::size_t(1));
  }

  void theWindowAsTheUserGuideShowsIt() {
    // The demo as a user first sees it, then coloured by deviation with a
    // landmark picked; the grabs (written to the test output folder) are the
    // user guide's screenshots.
    Window win;
    win.w.setFixedSize(1280, 860);
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    win.w.statusBar()->clearMessage();
    QTest::qWait(300);
    auto colourful = [](const QImage& image, const QRect& r) {
      QSet<QRgb> colours;
      for (int y = r.top(); y < r.bottom(); y += 3) {
        for (int x = r.left(); x < r.right(); x += 3) colours.insert(image.pixel(x, y));
      }
      return colours.size();
    };
    const QRect scene_rect(win.w.sceneView()->mapTo(&win.w, QPoint(0, 0)), win.w.sceneView()->size());
    QImage first = win.w.grab().toImage();
    QVERIFY(colourful(first, scene_rect) > 5);
    QVERIFY(first.save(hull::ui::testing::OutputDir() + QStringLiteral("/user_guide_demo.png")));

    auto* colouring = win.w.layersPanel()->colouringBox();
    colouring->setCurrentIndex(colouring->findData(QStringLiteral("deviation")));
    win.w.layersPanel()->layerCheckBox(SceneLayer::kDvlHits)->setChecked(false);
    const auto& demo = LoadDemo();
    const auto cylinder = std::find_if(demo.overlays->landmarks.begin(), demo.overlays->landmarks.end(),
                                       [](const LandmarkMarker& l) { return l.object.rfind("cyl", 0) == 0; });
    QVERIFY(cylinder != demo.overlays->landmarks.end());
    win.w.sceneView()->Grab();
    const PickInfo info = win.w.sceneView()->PickAt(*win.w.sceneView()->WidgetPosition(cylinder->position));
    QCOMPARE(info.kind, PickKind::kLandmark);
    QVERIFY(win.w.sceneView()->LegendVisible());
    QVERIFY(win.w.pickInfoPanel()->isVisible());
    QTest::qWait(300);
    const QImage second = win.w.grab().toImage();
    QVERIFY(colourful(second, scene_rect) > 5);
    QVERIFY(second != first);
    QVERIFY(second.save(hull::ui::testing::OutputDir() + QStringLiteral("/user_guide_deviation.png")));
  }

  void exportingThePlacedHull() {
    Window win;
    win.w.OpenDemo();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY(win.w.action(QStringLiteral("exportPlacedHull"))->isEnabled());
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("hull-in-g.ply"));
    win.w.documents()->ExportPlacedHull(path);
    HI_WAIT_IDLE(win.w.jobs(), 30000);
    QVERIFY(win.errors.empty());
    const hull::TriangleMesh placed = hull::LoadMesh(QFile::encodeName(path).toStdString());
    const auto& demo = LoadDemo();
    QCOMPARE(placed.num_faces(), demo.mesh->num_faces());
    const hull::Pose x_gM = win.w.session()->ModelPose();
    QVERIFY((placed.vertices[10] - x_gM * demo.mesh->vertices[10]).norm() < 1e-9);
  }

  void menusHaveTheirEntries() {
    Window win;
    for (const char* name :
         {"openMesh", "openSurvey", "openProject", "saveProject", "saveProjectAs", "exportPlacedHull", "quit", "undo",
          "redo", "resetCamera", "measureDistance", "screenshot", "screenshotPanel", "openDemo", "about"}) {
      QVERIFY2(win.w.action(QString::fromLatin1(name)), name);
    }
    // A toggle in View for each dock.
    for (QDockWidget* dock : win.w.findChildren<QDockWidget*>()) {
      QVERIFY(win.w.action(QStringLiteral("toggle_") + dock->objectName()));
    }
    QVERIFY(!win.w.action(QStringLiteral("exportPlacedHull"))->isEnabled());  // nothing to export yet
  }

  void withoutADisplayTheProgramSaysWhatToRun() {
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.remove(QStringLiteral("DISPLAY"));
    env.remove(QStringLiteral("WAYLAND_DISPLAY"));
    p.setProcessEnvironment(env);
    // Nothing to run headless (--demo would run the headless main job:
    // tests/report/headless_test.cc), so it says what would.
    p.start(QStringLiteral(HI_BINARY_DIR "/bin/hullinspect"), QStringList());
    QVERIFY(p.waitForFinished(30000));
    QCOMPARE(p.exitStatus(), QProcess::NormalExit);
    QCOMPARE(p.exitCode(), 2);
    const QString said = QString::fromLocal8Bit(p.readAllStandardError());
    QVERIFY(said.contains(QStringLiteral("hullinspect --demo [--out DIR]")));
    QVERIFY(said.contains(QStringLiteral("hullinspect-cli run --demo --out DIR")));
    p.start(QStringLiteral(HI_BINARY_DIR "/bin/hullinspect"), {QStringLiteral("--bogus")});
    QVERIFY(p.waitForFinished(30000));
    QCOMPARE(p.exitCode(), 2);
  }
};

HI_GUI_TEST_MAIN(MainWindowTest)
#include "main_window_test.moc"
