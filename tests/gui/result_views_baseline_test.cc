// Screenshots of the result views compared with baselines: the solver
// plots, the cross-section through the cylinder with the three models, the
// objects and zones tables, a keyframe with its alpha shapes, the heatmap
// in the 3-D scene and the sonar dock on the prism demo. The data are made
// in code (synthetic_results.h: the synthetic survey's truth, its mapping
// by the core, the sonar simulator's seeded prism), the widgets have fixed
// sizes, so the renders are reproducible under Xvfb.
#include <QTabWidget>
#include <QTableView>

#include "gui_test_support.h"
#include "synthetic_results.h"
#include "synthetic_survey.h"
#include "ui/panels/objects_panel.h"
#include "ui/panels/sonar_panel.h"
#include "ui/views/cross_section_view.h"
#include "ui/views/keyframe_view.h"
#include "ui/views/profile_canvas.h"
#include "ui/views/scene_view.h"
#include "ui/views/solver_plots_view.h"

using namespace hull::ui;
using namespace hull::ui::testing;

class ResultViewsBaselineTest : public QObject {
  Q_OBJECT

 private slots:
  void solverPlots() {
    SolverPlotsView view;
    view.setFixedSize(1280, 560);
    view.SetRuns(SyntheticRuns().at(hull::SurfaceModel::kMaxMixture), SyntheticRuns());
    view.SetSigmas(1.0, 0.02);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QVERIFY(view.timePlot()->HasPoints() && view.mixturePlot()->HasPoints());
    Settle(&view);
    Check(view.grab().toImage(), QStringLiteral("view_solver_plots"));
  }

  void crossSectionThroughTheCylinder() {
    const auto& survey = MakeSyntheticSurvey();
    CrossSectionView view;
    view.setFixedSize(1100, 360);
    view.SetMesh(survey.mesh, survey.bundle->manifest.model_axes);
    view.SetRuns(SyntheticRuns().at(hull::SurfaceModel::kMaxMixture), SyntheticRuns());
    SlabSpec slab;
    slab.direction = SlabDirection::kTransverse;
    slab.position = 2.0;  // the cylinder's centre along the hull (M)
    slab.width = 0.5;
    view.SetSlab(slab);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.canvas()->FitView();
    view.canvas()->SetExaggeration(4.0);
    const auto& panels = view.canvas()->panels();
    QCOMPARE(panels.size(), std::size_t(3));
    for (const ProfilePanel& p : panels) QVERIFY(p.present && !p.profile.features.empty());
    // The cylinder's features stand 15 cm off the section under max-mixture,
    // squashed to a third by all-on-surface.
    auto highest = [](const ProfilePanel& p) {
      double v = -1e9;
      for (const ProfilePoint& q : p.profile.features) v = std::max(v, q.deviation);
      return v;
    };
    QVERIFY(std::abs(highest(panels[2]) - 0.15) < 1e-6);
    QVERIFY(std::abs(highest(panels[1]) - 0.045) < 1e-6);
    Settle(&view);
    Check(view.grab().toImage(), QStringLiteral("view_cross_section"));
  }

  void objectsAndZones() {
    ObjectsPanel panel;
    panel.setFixedSize(1000, 260);
    panel.SetMapping(SyntheticMapping());
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QVERIFY(panel.objectsTable()->model()->rowCount() >= 2);
    Settle(&panel);
    Check(panel.grab().toImage(), QStringLiteral("view_objects"));
    panel.tabs()->setCurrentIndex(1);
    Settle(&panel);
    Check(panel.grab().toImage(), QStringLiteral("view_zones"));
  }

  void keyframeWithItsAlphaShapes() {
    KeyframeView view;
    view.setFixedSize(640, 420);
    view.SetMapping(SyntheticMapping());
    view.ShowObject(0);
    QVERIFY(view.keyframe() >= 0);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    Settle(&view);
    Check(view.grab().toImage(), QStringLiteral("view_keyframe"));
  }

  void heatmapAndDetectedObjects() {
    const auto& survey = MakeSyntheticSurvey();
    SceneView scene;
    scene.setFixedSize(640, 480);
    scene.SetMesh(survey.mesh);
    scene.SetSurvey(survey.bundle, std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*survey.bundle)));
    scene.SetModelPose(PlacementPose(survey.bundle.get(), ModelPlacement::kTruth));
    scene.SetAdjusted(SyntheticRuns().at(hull::SurfaceModel::kMaxMixture)->overlays);
    scene.SetMapping(SyntheticMapping());
    SceneOptions o;
    for (SceneLayer layer :
         {SceneLayer::kHull, SceneLayer::kLandmarks, SceneLayer::kDvlHits, SceneLayer::kAdjustedDvlHits,
          SceneLayer::kAdjustedLandmarks, SceneLayer::kTrueTrajectory, SceneLayer::kTruthObjects}) {
      o.visible[layer] = false;
    }
    o.auto_range = false;
    o.range_min = -0.15;
    o.range_max = 0.15;
    scene.SetOptions(o);
    scene.show();
    QVERIFY(QTest::qWaitForWindowExposed(&scene));
    LookAtTheCylinder(scene);
    QVERIFY(scene.Stats(SceneLayer::kHeatmap).visible && scene.Stats(SceneLayer::kDetectedObjects).visible);
    QVERIFY(scene.LegendVisible());
    Check(scene.Grab(), QStringLiteral("scene_heatmap"));
  }

  void sonarDockOnThePrism() {
    JobRunner jobs;
    SonarPanel panel(&jobs);
    panel.setFixedSize(1280, 330);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    panel.OpenDemo(QStringLiteral("prism"));
    HI_WAIT_IDLE(&jobs, 60000);
    QVERIFY(panel.run());
    panel.SetStep(10);
    Settle(&panel);
    QTest::qWait(200);
    Check(panel.grab().toImage(), QStringLiteral("view_sonar"), 0.02);
  }

 private:
  void Check(const QImage& image, const QString& name, double max_fraction = 0.01) {
    QString message;
    if (!MatchesBaseline(image, name, &message, 40, max_fraction)) QFAIL(qPrintable(message));
  }
};

HI_GUI_TEST_MAIN(ResultViewsBaselineTest)
#include "result_views_baseline_test.moc"
