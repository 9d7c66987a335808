// Screenshots of every view compared with baselines (F3D style): the 3-D
// scene in several states, each panel, and the whole window. The data are
// the synthetic survey made in code (not the simulator's demo, whose tuning
// may change); widgets get fixed sizes and the scene a camera fixed by the
// data, so that renders under Xvfb/Mesa are reproducible.
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QStatusBar>
#include <QUndoStack>

#include <QTemporaryDir>

#include "gui_test_support.h"
#include "synthetic_survey.h"
#include "ui/app/main_window.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/pick_info_panel.h"
#include "ui/panels/survey_summary_panel.h"
#include "ui/session/session.h"
#include "ui/views/scene_view.h"

using namespace hull::ui;
using hull::ui::testing::MakeSyntheticSurvey;
using hull::ui::testing::MatchesBaseline;
using hull::ui::testing::Settle;

class ViewBaselineTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    const auto& survey = MakeSyntheticSurvey();
    overlays_ = std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*survey.bundle));
    scene_ = std::make_unique<SceneView>();
    scene_->setFixedSize(640, 480);
    scene_->SetMesh(survey.mesh);
    scene_->SetSurvey(survey.bundle, overlays_);
    scene_->SetModelPose(PlacementPose(survey.bundle.get(), ModelPlacement::kTruth));
    scene_->show();
    QVERIFY(QTest::qWaitForWindowExposed(scene_.get()));
    scene_->ResetCamera();
  }

  void cleanupTestCase() { scene_.reset(); }

  void sceneOverview() {
    scene_->SetOptions(SceneOptions());
    scene_->ResetCamera();
    Check(scene_->Grab(), QStringLiteral("scene_overview"));
  }

  void sceneDeviationLegend() {
    SceneOptions o;
    o.colouring = LandmarkColouring::kDeviation;
    o.visible[SceneLayer::kHull] = false;  // the dent's landmarks lie inside it
    o.visible[SceneLayer::kDvlHits] = false;
    o.visible[SceneLayer::kTrajectory] = false;
    o.visible[SceneLayer::kTrueTrajectory] = false;
    scene_->SetOptions(o);
    scene_->ResetCamera();
    QVERIFY(scene_->LegendVisible());
    Check(scene_->Grab(), QStringLiteral("scene_deviation_legend"));
  }

  void sceneFrustaAndEdges() {
    SceneOptions o;
    o.visible[SceneLayer::kFrusta] = true;
    o.visible[SceneLayer::kLandmarks] = false;
    o.visible[SceneLayer::kDvlHits] = false;
    o.hull_edges = true;
    o.frustum_stride = 7;
    scene_->SetOptions(o);
    scene_->ResetCamera();
    Check(scene_->Grab(), QStringLiteral("scene_frusta_edges"));
  }

  void sceneCloseUpOfTheCylinder() {
    // Close to the known cylinder, from below, with its outline and the
    // landmarks on it in red.
    const auto& survey = MakeSyntheticSurvey();
    const hull::Pose x_gM = PlacementPose(survey.bundle.get(), ModelPlacement::kTruth);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& o : survey.bundle->truth->objects) {
      if (o.kind == hull::ObjectKind::kCylinder) centre = x_gM * o.center;
    }
    QVERIFY(!centre.isZero());
    scene_->SetOptions(SceneOptions());
    CameraState c;
    c.focal_point = {centre.x(), centre.y(), centre.z()};
    c.position = {centre.x() + 0.6, centre.y() - 0.9, centre.z() + 2.2};
    c.view_up = {1, 0, 0};
    c.view_angle = 30;
    scene_->SetCamera(c);
    Check(scene_->Grab(), QStringLiteral("scene_cylinder_closeup"));
  }

  void parameterPanelWithAnInlineError() {
    ParameterPanel panel(DefaultParameterTable(), CheckDefaultParameters);
    panel.setFixedSize(400, 520);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    static_cast<QDoubleSpinBox*>(panel.editor(QStringLiteral("sigma1")))->setValue(1.5);
    QVERIFY(!panel.errorText(QStringLiteral("sigma1")).isEmpty());
    Settle(&panel);
    Check(panel.grab().toImage(), QStringLiteral("panel_parameters_error"));
  }

  void layersPanel() {
    const auto& survey = MakeSyntheticSurvey();
    LayersPanel panel;
    panel.setFixedSize(320, 520);
    std::map<SceneLayer, bool> has;
    for (SceneLayer l : AllSceneLayers()) has[l] = true;
    panel.SetLayersWithData(has);
    panel.SetPlacements(AvailablePlacements(survey.bundle.get()), ModelPlacement::kTruth);
    panel.SetAutoRange(-0.15, 0.15);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    Settle(&panel);
    Check(panel.grab().toImage(), QStringLiteral("panel_layers"));
  }

  void pickInfoPanelShowsALandmark() {
    int foreign = -1;
    for (int i = 0; i < static_cast<int>(overlays_->landmarks.size()); ++i) {
      if (overlays_->landmarks[i].foreign()) {
        foreign = i;
        break;
      }
    }
    QVERIFY(foreign >= 0);
    PickInfoPanel panel;
    panel.setFixedSize(360, 260);
    panel.Show(DescribeLandmark(*overlays_, foreign));
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    Settle(&panel);
    Check(panel.grab().toImage(), QStringLiteral("panel_pick_landmark"));
  }

  void surveySummaryPanel() {
    const auto& survey = MakeSyntheticSurvey();
    Session session;
    session.SetMesh({QStringLiteral("/surveys/synthetic/hull.ply"), survey.mesh});
    session.SetSurvey({QStringLiteral("/surveys/synthetic"), survey.bundle, overlays_});
    SurveySummaryPanel panel;
    panel.setFixedSize(420, 460);
    panel.Update(session);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    Settle(&panel);
    Check(panel.grab().toImage(), QStringLiteral("panel_survey"));
  }

  void wholeWindow() {
    QTemporaryDir dir;
    const QString bundle = hull::ui::testing::WriteSyntheticSurvey(dir.filePath(QStringLiteral("synthetic")));
    MainWindow window;
    window.SetErrorSink([](const QString& title, const QString& message) {
      QFAIL(qPrintable(title + QStringLiteral(": ") + message));
    });
    window.setFixedSize(1280, 860);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.OpenPaths({bundle});  // brings its hull.ply (model_hint)
    HI_WAIT_IDLE(window.jobs(), 60000);
    QVERIFY(window.session()->survey().has_value() && window.session()->mesh().has_value());
    window.statusBar()->clearMessage();  // names the temporary folder
    Settle(&window);
    QTest::qWait(200);
    const QImage image = window.grab().toImage();
    Check(image, QStringLiteral("main_window"), /*max_fraction=*/0.03);
  }

 private:
  void Check(const QImage& image, const QString& name, double max_fraction = 0.01) {
    QString message;
    if (!MatchesBaseline(image, name, &message, 40, max_fraction)) QFAIL(qPrintable(message));
  }

  std::shared_ptr<const SurveyOverlays> overlays_;
  std::unique_ptr<SceneView> scene_;
};

HI_GUI_TEST_MAIN(ViewBaselineTest)
#include "view_baseline_test.moc"
