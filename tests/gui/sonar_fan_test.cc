// The sonar fan view (issue 11): the polar-to-fan mapping checked with
// numbers worked out by hand and on the drawn image (a lit bin lands on the
// pixel the mapping gives); playback and stepping move the fan and the 3-D
// view together and playing stops at the end; the smoother's estimates and
// the scene in the 3-D view; a screenshot of the fan on a small simulated
// image sequence compared with its baseline.
#include <QCheckBox>
#include <QComboBox>
#include <QPushButton>
#include <QSlider>
#include <QTemporaryDir>

#include "gui_test_support.h"
#include "simulate/sonar_image_simulator.h"
#include "ui/jobs/job_runner.h"
#include "ui/panels/sonar_panel.h"
#include "ui/views/sonar_fan_view.h"
#include "ui/views/sonar_view.h"

using namespace hull::ui;
using hull::ui::testing::MatchesBaseline;
using hull::ui::testing::OutputDir;
using hull::ui::testing::Settle;

namespace {

// The prism layout, 8 steps, rendered at 256 range bins x 64 beams.
std::shared_ptr<const SonarJobInput> SmallSequence() {
  static const std::shared_ptr<const SonarJobInput> input = [] {
    hull::SonarImageSimulationOptions o = hull::SonarImagePreset("prism", 5);
    o.sequence.num_steps = 8;
    o.format.range_bins = 256;
    o.format.beams = 64;
    hull::SonarImageSimulation sim = hull::SimulateSonarImages(o);
    auto in = std::make_shared<SonarJobInput>();
    in->sequence = std::make_shared<const hull::AcousticSequence>(std::move(sim.sequence));
    in->name = "small prism";
    in->images = std::make_shared<const std::vector<cv::Mat>>(std::move(sim.images));
    in->scene = std::make_shared<const hull::TriangleMesh>(std::move(sim.scene.mesh));
    return in;
  }();
  return input;
}

}  // namespace

class SonarFanTest : public QObject {
  Q_OBJECT

 private slots:
  void aBinLandsWhereTheGeometrySays() {
    // The contract's default sensor (0.7..5 m, 32 deg) and image (512 x 128)
    // in a 400 x 600 rectangle: the fan is 2 * 5 sin(16 deg) = 2.7564 m wide
    // and 5 - 0.7 cos(16 deg) = 4.3271 m tall, so the height binds:
    // 600 / 4.3271 = 138.660 px/m, the apex at (200, 5 * 138.660 = 693.30).
    // Row 383 is at 0.7 + 383.5 * 4.3 / 512 = 3.92080 m, column 112 at
    // -0.27925 + 112.5 * 0.5585 / 128 = 0.211619 rad: x = 200 + r sin(az) s,
    // y = 693.30 - r cos(az) s.
    const hull::SonarSensor sensor;
    const hull::SonarImageFormat format;
    const SonarFanGeometry g(sensor, format, sensor.range_min, sensor.range_max, QRectF(0, 0, 400, 600));
    QCOMPARE(qRound(g.pixels_per_metre() * 1000), 138660);
    QVERIFY(std::abs(g.apex().x() - 200.0) < 1e-9 && std::abs(g.apex().y() - 693.302) < 1e-3);
    const QPointF p = g.BinToPixel(383, 112);
    QVERIFY2(std::abs(p.x() - 314.192) < 1e-3 && std::abs(p.y() - 161.770) < 1e-3,
             qPrintable(QStringLiteral("(%1, %2)").arg(p.x()).arg(p.y())));
    const Eigen::Vector2d back = g.PixelToBin(p);
    QVERIFY(std::abs(back[0] - 383) < 1e-9 && std::abs(back[1] - 112) < 1e-9);
    // The near corners and the far centre touch the rectangle.
    QVERIFY(std::abs(g.ToPixel(sensor.range_max, 0).y() - 0.0) < 1e-9);
    QVERIFY(std::abs(g.ToPixel(sensor.range_max, sensor.azimuth_fov / 2).x() - (200 + 1.37822 * 138.660)) < 0.01);
    // A range window [2, 3] m: the far arc at the top of the rectangle.
    const SonarFanGeometry z(sensor, format, 2.0, 3.0, QRectF(10, 20, 400, 300));
    QVERIFY(std::abs(z.ToPixel(3.0, 0).y() - z.bounds().top()) < 1e-9);
    QVERIFY(z.bounds().top() >= 20 - 1e-9 && z.bounds().bottom() <= 320 + 1e-9);
  }

  void theDrawnImageHasTheBinWhereTheGeometrySays() {
    // One lit 3 x 3 block of bins in an otherwise dark image.
    auto seq = std::make_shared<hull::AcousticSequence>();
    seq->image = hull::SonarImageFormat();
    seq->image->range_bins = 128;
    seq->image->beams = 32;
    auto run = std::make_shared<SonarRun>();
    run->sequence = seq;
    run->from_images = true;
    run->result.steps.resize(1);
    run->frames.resize(1);
    cv::Mat image(128, 32, CV_8U, cv::Scalar(0));
    const int row = 90, col = 24;
    image(cv::Rect(col - 1, row - 1, 3, 3)).setTo(255);
    run->frames[0].image = image;
    SonarFanView view;
    view.setFixedSize(420, 520);
    view.SetRun(run);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    const QImage shot = view.grab().toImage();
    const QPointF p = view.FanGeometry().BinToPixel(row, col);
    const QRgb lit = shot.pixel(static_cast<int>(p.x()), static_cast<int>(p.y()));
    QVERIFY2(qRed(lit) > 200, qPrintable(QStringLiteral("red %1 at the lit bin").arg(qRed(lit))));
    // Three bins further in range (beyond the block): dark.
    const QPointF q = view.FanGeometry().BinToPixel(row + 4, col);
    QVERIFY(qRed(shot.pixel(static_cast<int>(q.x()), static_cast<int>(q.y()))) < 40);
  }

  void playAndStepMoveBothViews() {
    JobRunner jobs;
    SonarPanel panel(&jobs);
    panel.setFixedSize(1280, 480);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    panel.OpenInput(SmallSequence());
    HI_WAIT_IDLE(&jobs, 60000);
    const auto run = panel.run();
    QVERIFY(run && run->from_images);
    QCOMPARE(run->steps(), 8);
    QCOMPARE(static_cast<int>(run->frames.size()), 8);
    QCOMPARE(panel.step(), 7);
    QCOMPARE(panel.fanView()->step(), 7);
    QCOMPARE(panel.view()->step(), 7);
    // What the fan shows is the run's frame.
    Settle(&panel);
    const SonarFanView::Counts c = panel.fanView()->counts();
    const SonarFrame& last = run->frames.back();
    QCOMPARE(c.detections, static_cast<int>(last.detections.size()));
    QCOMPARE(c.predictions, static_cast<int>(last.predictions.size()));
    QVERIFY2(c.in_state_pairs > 0, "the prism's features are associated at the last step");
    QVERIFY(c.rings >= 3 && c.azimuth_lines >= 5);

    panel.findChild<QPushButton*>(QStringLiteral("sonarStepBack"))->click();
    QCOMPARE(panel.step(), 6);
    QCOMPARE(panel.fanView()->step(), 6);
    QCOMPARE(panel.view()->step(), 6);
    QCOMPARE(panel.view()->counts().pose_ellipsoids, 7);
    panel.findChild<QPushButton*>(QStringLiteral("sonarStepForward"))->click();
    QCOMPARE(panel.fanView()->step(), 7);
    QVERIFY(!panel.findChild<QPushButton*>(QStringLiteral("sonarStepForward"))->isEnabled());
    panel.findChild<QSlider*>(QStringLiteral("sonarStep"))->setValue(2);
    QCOMPARE(panel.fanView()->step(), 2);
    QCOMPARE(panel.view()->step(), 2);

    // Playing from step 2 advances both views and stops at the last step.
    panel.Play();
    QVERIFY(panel.playing());
    QTRY_VERIFY_WITH_TIMEOUT(panel.step() >= 4, 5000);
    QCOMPARE(panel.fanView()->step(), panel.step());
    QCOMPARE(panel.view()->step(), panel.step());
    QTRY_VERIFY_WITH_TIMEOUT(!panel.playing(), 10000);
    QCOMPARE(panel.step(), 7);
    QCOMPARE(panel.fanView()->step(), 7);
    QCOMPARE(panel.view()->step(), 7);
  }

  void theSmootherAndTheSceneInThe3dView() {
    JobRunner jobs;
    SonarPanel panel(&jobs);
    panel.setFixedSize(1280, 480);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    panel.OpenInput(SmallSequence());
    HI_WAIT_IDLE(&jobs, 60000);
    QVERIFY(panel.run() && !panel.run()->smoother);
    QVERIFY(panel.view()->counts().scene_triangles > 0);
    QVERIFY(!panel.view()->counts().smoother);
    panel.smootherBox()->setChecked(true);  // runs again, with the smoother
    HI_WAIT_IDLE(&jobs, 120000);
    const auto run = panel.run();
    QVERIFY(run && run->smoother);
    QCOMPARE(static_cast<int>(run->smoother->result.poses.size()), 8);
    QCOMPARE(panel.estimatesBox()->currentIndex(), 1);
    const SonarView::Counts s = panel.view()->counts();
    QVERIFY(s.smoother);
    QCOMPARE(s.estimated, static_cast<int>(run->smoother->result.features.size()));
    QVERIFY(s.feature_ellipsoids > 0);
    QCOMPARE(s.pose_ellipsoids, 8);
    Settle(&panel);
    QTest::qWait(200);
    QVERIFY(panel.view()->Grab().save(OutputDir() + QStringLiteral("/sonar_smoother_3d.png")));
    panel.estimatesBox()->setCurrentIndex(0);
    QVERIFY(!panel.view()->counts().smoother);
    QCOMPARE(panel.view()->counts().estimated, static_cast<int>(run->result.steps.back().features.size()));

    // The given measurements instead of the images: runs again, no frames to draw.
    QVERIFY(panel.sourceBox()->isEnabled());
    panel.sourceBox()->setCurrentIndex(1);
    HI_WAIT_IDLE(&jobs, 120000);
    QVERIFY(panel.run() != run && !panel.run()->from_images && panel.run()->frames.empty());
    Settle(&panel);
    QCOMPARE(panel.fanView()->counts().detections, 0);
    QCOMPARE(panel.fanView()->counts().predictions, 0);
    QVERIFY(panel.fanView()->counts().rings > 0);  // the fan's grid still
    QVERIFY(panel.fanView()->grab().toImage().save(OutputDir() + QStringLiteral("/sonar_fan_no_images.png")));
  }

  void aFolderWithImagesAndASceneOpens() {
    hull::SonarImageSimulationOptions o = hull::SonarImagePreset("tank", 2);
    o.sequence.num_steps = 4;
    o.format.range_bins = 128;
    o.format.beams = 48;
    QTemporaryDir dir;
    const std::string path = QFile::encodeName(dir.filePath(QStringLiteral("tank"))).toStdString();
    hull::WriteSonarImageSimulation(hull::SimulateSonarImages(o), path);
    JobRunner jobs;
    SonarPanel panel(&jobs);
    panel.OpenSequence(dir.filePath(QStringLiteral("tank")));
    HI_WAIT_IDLE(&jobs, 60000);
    const auto run = panel.run();
    QVERIFY(run && run->from_images && run->scene && run->scene->num_faces() > 0);
    QCOMPARE(static_cast<int>(run->frames.size()), 4);
    for (const SonarFrame& f : run->frames) QVERIFY(f.image.rows == 128 && f.image.cols == 48);
    QCOMPARE(run->input->directory, path);
  }

  void fanScreenshot() {
    JobRunner jobs;
    SonarPanel panel(&jobs);
    panel.OpenInput(SmallSequence());
    HI_WAIT_IDLE(&jobs, 60000);
    QVERIFY(panel.run());
    panel.SetStep(5);
    SonarFanView view;
    view.setFixedSize(520, 460);
    view.SetRun(panel.run());
    view.SetStep(5);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    Settle(&view);
    QString message;
    QVERIFY2(MatchesBaseline(view.grab().toImage(), QStringLiteral("view_sonar_fan"), &message), qPrintable(message));
    view.SetZoom(SonarFanView::Zoom::kFeatures);
    view.SetEllipseScale(3);
    Settle(&view);
    QVERIFY2(MatchesBaseline(view.grab().toImage(), QStringLiteral("view_sonar_fan_zoom"), &message),
             qPrintable(message));
  }

  // The user guide's picture of the fan (docs/images/sonar-fan.png is a
  // copy of user_guide_sonar_fan.png): the demo prism at step 12, around the
  // features.
  void userGuideShotOfTheFan() {
    JobRunner jobs;
    SonarPanel panel(&jobs);
    panel.OpenDemo(QStringLiteral("prism"));
    HI_WAIT_IDLE(&jobs, 120000);
    QVERIFY(panel.run() && panel.run()->from_images);
    SonarFanView view;
    view.setFixedSize(640, 520);
    view.SetRun(panel.run());
    view.SetStep(12);
    view.SetZoom(SonarFanView::Zoom::kFeatures);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    Settle(&view);
    QVERIFY(view.counts().predictions > 0 && view.counts().detections > 0);
    QVERIFY(view.grab().toImage().save(OutputDir() + QStringLiteral("/user_guide_sonar_fan.png")));
  }
};

HI_GUI_TEST_MAIN(SonarFanTest)
#include "sonar_fan_test.moc"
