// The inspection as the user guide shows it (docs/user-guide.md): the demo
// run with the models compared, the slab through the cylinder, and each
// result view floated to a readable size. The grabs go to the test output
// folder as user_guide_*.png; the guide's screenshots are copies of them.
// The images view is shot on a small rendered version 2 survey.
#include <QAction>
#include <QDockWidget>
#include <QStatusBar>
#include <QTableView>

#include "gui_test_support.h"
#include "images_survey.h"
#include "inspection_window.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/objects_panel.h"
#include "ui/panels/sonar_panel.h"
#include "ui/views/cross_section_view.h"
#include "ui/views/images_view.h"
#include "ui/views/keyframe_view.h"
#include "ui/views/profile_canvas.h"
#include "ui/views/scene_view.h"
#include "ui/views/solver_plots_view.h"

using namespace hull::ui;
using hull::ui::testing::LoadDemo;
using hull::ui::testing::OutputDir;
using hull::ui::testing::Window;

class UserGuideShots : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { LoadDemo(); }

  void theInspectionAsTheUserGuideShowsIt() {
    Window win;
    QVERIFY(win.OpenAndRun());
    win.w.action(QStringLiteral("compareModels"))->trigger();
    HI_WAIT_IDLE(win.w.jobs(), 240000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    const auto& run = win.w.session()->adjustment();
    const auto cylinder = std::find_if(run->overlays->landmarks.begin(), run->overlays->landmarks.end(),
                                       [](const AdjustedLandmark& l) { return l.object == "cyl-1"; });
    QVERIFY(cylinder != run->overlays->landmarks.end());
    CrossSectionView* section = win.w.crossSectionView();
    SlabSpec slab = section->slab();
    slab.width = 0.2;
    section->SetSlab(slab);
    section->CentreOn(cylinder->position);
    section->canvas()->FitView();
    // Zoom to the cylinder's 1.5 m around its middle, the vertical stretched.
    const QRectF panel(0, 0, section->canvas()->width() / 3.0, section->canvas()->height());
    section->canvas()->ZoomAt(QPointF(panel.center().x(), section->canvas()->height() / 2.0), 2.0);
    section->canvas()->SetExaggeration(3.0);

    // The whole window: the heatmap and detected objects, the cross-section.
    SceneOptions o = win.w.layersPanel()->options();
    o.visible[SceneLayer::kAdjustedDvlHits] = false;
    o.visible[SceneLayer::kAdjustedLandmarks] = false;
    win.w.layersPanel()->SetOptions(o);
    win.w.sceneView()->SetOptions(o);
    win.w.sceneView()->ResetCamera();
    win.Raise(section);
    win.w.statusBar()->clearMessage();
    QTest::qWait(400);
    QVERIFY(win.w.grab().toImage().save(OutputDir() + QStringLiteral("/user_guide_inspection.png")));

    // Each result view on its own, floated to a readable size.
    auto shoot = [&](QWidget* view, const QSize& size, const QString& name) {
      auto* dock = qobject_cast<QDockWidget*>(view->parentWidget());
      QVERIFY(dock);
      dock->setFloating(true);
      dock->resize(size);
      dock->show();
      dock->raise();
      QTest::qWait(400);
      QVERIFY(win.w.GrabView(view).save(OutputDir() + QStringLiteral("/user_guide_") + name + QStringLiteral(".png")));
      dock->setFloating(false);
    };
    shoot(win.w.solverPlotsView(), QSize(1280, 600), QStringLiteral("solver_plots"));
    shoot(section, QSize(1280, 420), QStringLiteral("cross_section"));
    QTableView* table = win.w.objectsPanel()->objectsTable();
    table->setCurrentIndex(table->model()->index(0, 0));
    shoot(win.w.objectsPanel(), QSize(1100, 320), QStringLiteral("objects"));
    shoot(win.w.keyframeView(), QSize(760, 560), QStringLiteral("keyframe"));
    // The scene close to the first object (the table's selection flew there).
    QVERIFY(win.w.sceneView()->Grab().save(OutputDir() + QStringLiteral("/user_guide_object.png")));
    // Measure anywhere: the remeshed model clicked at the first object's top.
    const auto& mapping = win.w.session()->mapping();
    const hull::TriangleMesh& model = mapping->result->model;
    const hull::DetectedObject& first = mapping->result->objects.front();
    QVERIFY(!first.vertices.empty());
    int top = first.vertices.front();
    for (const int v : first.vertices) {
      if ((*model.FindScalar("deviation"))[static_cast<std::size_t>(v)] >
          (*model.FindScalar("deviation"))[static_cast<std::size_t>(top)]) {
        top = v;
      }
    }
    // Outlines and points are picked before surfaces.
    for (SceneLayer layer : {SceneLayer::kDetectedObjects, SceneLayer::kTruthObjects, SceneLayer::kLandmarks}) {
      o.visible[layer] = false;
    }
    win.w.layersPanel()->SetOptions(o);
    win.w.sceneView()->SetOptions(o);
    win.w.sceneView()->Grab();
    const auto at = win.w.sceneView()->WidgetPosition(mapping->x_gM() * model.vertices[static_cast<std::size_t>(top)]);
    QVERIFY(at);
    const PickInfo picked = win.w.sceneView()->PickAt(*at);
    QVERIFY2(picked.kind == PickKind::kSurface, qPrintable(picked.title + QStringLiteral(" at %1,%2 of %3x%4")
                                                                              .arg(at->x())
                                                                              .arg(at->y())
                                                                              .arg(win.w.sceneView()->width())
                                                                              .arg(win.w.sceneView()->height())));
    QTest::qWait(400);
    QVERIFY(win.w.grab().toImage().save(OutputDir() + QStringLiteral("/user_guide_surface_pick.png")));
    win.w.action(QStringLiteral("openSonarDemoPrism"))->trigger();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    win.w.sonarPanel()->SetStep(12);
    shoot(win.w.sonarPanel(), QSize(1280, 440), QStringLiteral("sonar"));
    QVERIFY(win.errors.isEmpty());
  }

  // A rendered stereo survey without features.csv: the features extracted
  // on opening, the inspection run, one keyframe in the images view.
  void theImagesViewAsTheUserGuideShowsIt() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenPaths({hull::ui::testing::ImagesSurveyDir()});
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->frontEnd() && !win.w.jobs()->IsBusy(), 180000);
    win.w.action(QStringLiteral("runInspection"))->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->adjustment() && !win.w.jobs()->IsBusy(), 300000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    ImagesView* view = win.w.imagesView();
    view->ShowKeyframe(4);
    auto* dock = qobject_cast<QDockWidget*>(view->parentWidget());
    QVERIFY(dock);
    dock->setFloating(true);
    dock->resize(1000, 820);
    dock->show();
    dock->raise();
    QTest::qWait(400);
    QVERIFY(win.w.GrabView(view).save(OutputDir() + QStringLiteral("/user_guide_images.png")));
  }
};

HI_GUI_TEST_MAIN(UserGuideShots)
#include "user_guide_shots_test.moc"
