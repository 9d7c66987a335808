// Screenshots of the result views compared with baselines: the solver
// plots, the cross-section through the cylinder with the three models, the
// objects and zones tables, a keyframe with its alpha shapes, the heatmap
// in the 3-D scene and the sonar dock on the prism demo. The data are made
// in code (synthetic_results.h: the synthetic survey's truth, its mapping
// by the core, the sonar simulator's seeded prism), the widgets have fixed
// sizes, so the renders are reproducible under Xvfb.
#include <QTabWidget>
#include <QTableView>
#include <cmath>
#include <numeric>

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
    SceneView scene;
    SceneOptions o = ShowTheHeatmap(scene);
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

  // Judging against a tolerance (issue 25.2): within +-3 cm one green, the
  // cylinder's 15 cm above it in the deviation colours; a manual range marks
  // what lies beyond it; zero stays white over an asymmetric range.
  void heatmapWithAToleranceBand() {
    SceneView scene;
    SceneOptions o = ShowTheHeatmap(scene);
    scene.show();
    QVERIFY(QTest::qWaitForWindowExposed(&scene));
    LookAtTheCylinder(scene);
    const QImage continuous = scene.Grab();
    const std::array<double, 3> white = scene.DeviationColour(0.0);
    QVERIFY(white[0] > 0.9 && white[1] > 0.9 && white[2] > 0.9);
    o.tolerance = 0.03;
    scene.SetOptions(o);
    for (double h : {-0.029, 0.0, 0.02, 0.029}) {
      const std::array<double, 3> c = scene.DeviationColour(h);
      for (int k = 0; k < 3; ++k) QVERIFY2(std::abs(c[k] - kWithinTolerance[k]) < 0.01, qPrintable(QString::number(h)));
    }
    const std::array<double, 3> over = scene.DeviationColour(0.10), under = scene.DeviationColour(-0.10);
    QVERIFY(over[0] > 0.6 && over[2] < 0.4);    // red
    QVERIFY(under[2] > 0.6 && under[0] < 0.4);  // blue
    const QImage banded = scene.Grab();
    Settle(&scene);
    Check(scene.Grab(), QStringLiteral("scene_heatmap_tolerance"));
    // The histogram beside the legend counts the remeshed model's vertices,
    // the share within the band among them.
    const std::vector<double>& deviation = *SyntheticMapping()->result->model.FindScalar("deviation");
    int finite = 0, within = 0;
    for (const double h : deviation) {
      finite += std::isfinite(h);
      within += std::isfinite(h) && std::abs(h) <= 0.03;
    }
    const DeviationHistogram& histogram = scene.LegendHistogram();
    QCOMPARE(histogram.total, finite);
    QCOMPARE(histogram.within, within);
    QVERIFY(within > 0 && within < finite);
    QCOMPARE(std::accumulate(histogram.counts.begin(), histogram.counts.end(), 0) + histogram.below + histogram.above,
             finite);
    // The scale bar: a round length, its pixels what the camera spans.
    const ScaleBar& bar = scene.CurrentScaleBar();
    QVERIFY2(bar.pixels >= 90 && bar.pixels <= 240, qPrintable(QString::number(bar.pixels)));
    const CameraState camera = scene.Camera();
    const double distance = std::sqrt(std::pow(camera.position[0] - camera.focal_point[0], 2) +
                                      std::pow(camera.position[1] - camera.focal_point[1], 2) +
                                      std::pow(camera.position[2] - camera.focal_point[2], 2));
    const double metres_per_pixel = 2 * distance * std::tan(camera.view_angle * M_PI / 360.0) / scene.height();
    QVERIFY(std::abs(bar.metres - bar.pixels * metres_per_pixel) < 1e-6 * bar.metres);
    // The band recoloured the hull around the cylinder: many pixels changed.
    int changed = 0;
    for (int y = 0; y < banded.height(); ++y) {
      for (int x = 0; x < banded.width(); ++x) changed += banded.pixel(x, y) != continuous.pixel(x, y);
    }
    QVERIFY2(changed > banded.width() * banded.height() / 20, qPrintable(QString::number(changed)));

    // A manual, asymmetric range: zero still white, beyond the ends marked.
    o.tolerance = 0;
    o.auto_range = false;
    o.range_min = -0.05;
    o.range_max = 0.10;
    scene.SetOptions(o);
    const std::array<double, 3> zero = scene.DeviationColour(0.0);
    QVERIFY(zero[0] > 0.9 && zero[1] > 0.9 && zero[2] > 0.9);
    const std::array<double, 3> above = scene.DeviationColour(0.15), below = scene.DeviationColour(-0.08);
    for (int k = 0; k < 3; ++k) {
      QVERIFY(std::abs(above[k] - kAboveRange[k]) < 0.01);
      QVERIFY(std::abs(below[k] - kBelowRange[k]) < 0.01);
    }
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
  // The synthetic survey's mapping in a 640 x 480 scene, the heatmap and
  // the detected objects on.
  static SceneOptions ShowTheHeatmap(SceneView& scene) {
    const auto& survey = MakeSyntheticSurvey();
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
    scene.SetOptions(o);
    return o;
  }

  void Check(const QImage& image, const QString& name, double max_fraction = 0.01) {
    QString message;
    if (!MatchesBaseline(image, name, &message, 40, max_fraction)) QFAIL(qPrintable(message));
  }
};

HI_GUI_TEST_MAIN(ResultViewsBaselineTest)
#include "result_views_baseline_test.moc"
