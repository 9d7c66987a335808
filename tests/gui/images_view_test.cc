// The images view and the feature extraction in the main window, on a small
// rendered version 2 survey without features.csv: opening it extracts the
// features in a job and fills the view, whose counts are the core's (the
// front end run here directly on the same bundle); a front-end parameter
// change re-extracts and undo brings the first features back (cached);
// cancel stops an extraction and keeps the last features; Run waits for the
// features and the view then shows the adjusted landmarks' reprojections.
// The canvas is compared with tests/gui/baselines/images_view.png.
#include <QAction>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QUndoStack>

#include "gui_test_support.h"
#include "images_survey.h"
#include "inspection_window.h"
#include "survey/survey_io.h"
#include "synthetic_survey.h"
#include "ui/controllers/front_end_controller.h"
#include "ui/session/inspection_parameters.h"
#include "ui/session/project_file.h"
#include "ui/views/images_view.h"
#include "vision/front_end.h"

using namespace hull::ui;
using hull::ui::testing::ImagesSurveyDir;
using hull::ui::testing::OutputDir;
using hull::ui::testing::Window;

namespace {

// Opens the survey and waits for the extraction.
bool OpenAndExtract(Window& win) {
  if (!QTest::qWaitForWindowExposed(&win.w)) return false;
  win.w.OpenPaths({ImagesSurveyDir()});
  return QTest::qWaitFor([&win] { return !win.w.jobs()->IsBusy() && win.w.session()->frontEnd(); }, 180000);
}

}  // namespace

class ImagesViewTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QVERIFY(!ImagesSurveyDir().isEmpty()); }

  void aSurveyOfTracksSaysItHasNoImages() {
    // A version 1 bundle (feature tracks, no images): not "a dropped frame".
    const auto& survey = hull::ui::testing::MakeSyntheticSurvey();
    ImagesView view;
    view.resize(800, 600);
    view.SetSurvey(survey.bundle, nullptr);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QVERIFY(view.keyframe() >= 0);
    QVERIFY(view.image().isNull());
    QVERIFY2(view.missingImageText().contains(QStringLiteral("no camera images")), qPrintable(view.missingImageText()));
  }

  void openingAVersion2SurveyExtractsAndFillsTheView() {
    Window win;
    QSignalSpy started(win.w.jobs(), &JobRunner::jobStarted);
    QVERIFY(OpenAndExtract(win));
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    bool extracted = false;
    for (const auto& s : started) extracted |= s.at(1).toString() == FrontEndController::kFeaturesJob;
    QVERIFY(extracted);
    const auto fe = win.w.session()->frontEnd();
    const hull::SurveyBundle* bundle = win.w.session()->bundle();
    QVERIFY(fe && bundle);
    QCOMPARE(bundle->features.size(), fe->features.size());
    QVERIFY(fe->landmarks > 100);
    QVERIFY(!win.w.session()->NeedsFeatureExtraction());

    // The core's own run on the bundle as read from disk, with the panel's options.
    const hull::SurveyBundle fresh = hull::ReadSurveyBundle(QFile::encodeName(ImagesSurveyDir()).toStdString());
    QVERIFY(fresh.features.empty());
    hull::NullProgress progress;
    const hull::FrontEndResult core =
        hull::RunFrontEnd(fresh, FrontEndOptionsFrom(win.w.parameterPanel()->values()), progress);
    QCOMPARE(core.landmarks, fe->landmarks);
    QCOMPARE(core.features.size(), fe->features.size());

    ImagesView* view = win.w.imagesView();
    win.Raise(view);
    for (int index : {1, 4, static_cast<int>(core.keyframes.size()) - 1}) {
      view->keyframeSlider()->setValue(index);
      QCOMPARE(view->keyframe(), index);
      QCOMPARE(view->keyframeBox()->value(), index);
      const ImageOverlay& o = view->overlay();
      const hull::FrontEndKeyframe& k = core.keyframes[static_cast<std::size_t>(index)];
      QCOMPARE(o.keyframe, k.keyframe);
      QCOMPARE(static_cast<int>(o.features.size()), k.top_features);
      QCOMPARE(o.tracked, k.tracked);
      QCOMPARE(static_cast<int>(o.stereo.size()), k.stereo_matches);
      QCOMPARE(o.stereo_inliers + o.stereo_outliers + o.stereo_unverified, k.stereo_matches);
      // The pair with the previous keyframe.
      const hull::FrontEndPair* pair = nullptr;
      for (const auto& p : core.pairs) {
        if (p.to == k.keyframe && p.from == core.keyframes[static_cast<std::size_t>(index - 1)].keyframe) pair = &p;
      }
      QVERIFY(pair);
      QCOMPARE(o.previous_keyframe, pair->from);
      QCOMPARE(static_cast<int>(o.temporal.size()), pair->putative);
      QCOMPARE(o.temporal_inliers, pair->inliers);
      QCOMPARE(o.temporal_outliers, pair->putative - pair->inliers);
      qInfo("keyframe %d: %d features, %d tracked, stereo %d, temporal %d (%d inliers, pair %s)", index, k.top_features,
            k.tracked, k.stereo_matches, pair->putative, pair->inliers,
            pair->accepted ? "accepted" : pair->note.c_str());
      QCOMPARE(o.previous_pair_accepted, pair->accepted);
      if (index < 10) QVERIFY(pair->accepted && o.temporal_inliers > 20);  // the last may be after a turn
      // The legend says the same.
      const QString legend = view->findChild<QLabel*>(QStringLiteral("imagesLegend"))->text();
      QVERIFY2(legend.contains(QStringLiteral("%1 features, %2 tracked").arg(k.top_features).arg(k.tracked)),
               qPrintable(legend));
      QVERIFY2(legend.contains(QStringLiteral("temporal matches with keyframe %1: %2 (inliers %3")
                                   .arg(pair->from)
                                   .arg(pair->putative)
                                   .arg(pair->inliers)),
               qPrintable(legend));
      // The real image, of the camera's size.
      QCOMPARE(view->image().size(), QSize(bundle->manifest.camera.width, bundle->manifest.camera.height));
    }
    // The bottom camera: its features and the same stereo matches, no temporal ones.
    view->cameraBox()->setCurrentIndex(1);
    QCOMPARE(static_cast<int>(view->overlay().features.size()),
             core.keyframes[static_cast<std::size_t>(view->keyframe())].bottom_features);
    QCOMPARE(static_cast<int>(view->overlay().stereo.size()),
             core.keyframes[static_cast<std::size_t>(view->keyframe())].stereo_matches);
    QVERIFY(view->overlay().temporal.empty());
    QVERIFY(!view->image().isNull());
    view->cameraBox()->setCurrentIndex(0);

    // The view as the user sees it (looked at; the baseline).
    auto* dock = qobject_cast<QDockWidget*>(view->parentWidget());
    dock->setFloating(true);
    dock->resize(1000, 820);
    dock->show();
    view->ShowKeyframe(4);
    hull::ui::testing::Settle(view);
    QTest::qWait(200);
    const QImage shot = view->findChild<QWidget*>(QStringLiteral("imagesCanvas"))->grab().toImage();
    QVERIFY(win.w.GrabView(view).save(OutputDir() + QStringLiteral("/images_view_dock.png")));
    QString message;
    QVERIFY2(hull::ui::testing::MatchesBaseline(shot, QStringLiteral("images_view"), &message), qPrintable(message));
    dock->setFloating(false);
  }

  void aParameterChangeReExtractsAndUndoRestores() {
    Window win;
    QVERIFY(OpenAndExtract(win));
    const auto first = win.w.session()->frontEnd();
    win.w.imagesView()->ShowKeyframe(3);
    const int inliers = win.w.imagesView()->overlay().temporal_inliers;
    auto* threshold = win.Real("fe_ransac_threshold");
    QVERIFY(threshold);
    threshold->setValue(0.4);
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->frontEnd() != first && !win.w.jobs()->IsBusy(), 720000);
    const auto second = win.w.session()->frontEnd();
    QCOMPARE(FrontEndOptionsFrom(win.w.parameterPanel()->values()).temporal.ransac_threshold, 0.4);
    QVERIFY(win.w.imagesView()->overlay().temporal_inliers < inliers);
    QVERIFY(win.w.imagesView()->overlay().temporal_outliers > 0);
    // Saved with the project.
    QTemporaryDir tmp;
    const QString project = tmp.filePath(QStringLiteral("images.hiproj"));
    QVERIFY(win.w.SaveProject(project));
    const ProjectData saved = ReadProject(project, DefaultParameterTable(), CheckDefaultParameters);
    QCOMPARE(saved.parameters.value(QStringLiteral("fe_ransac_threshold")).toDouble(), 0.4);
    win.w.parameterPanel()->undoStack()->undo();
    QCOMPARE(threshold->value(), hull::TemporalOptions().ransac_threshold);
    QVERIFY(win.w.session()->frontEnd() == first);  // from the cache, at once
    QVERIFY(!win.w.jobs()->IsBusy());
    QCOMPARE(win.w.imagesView()->overlay().temporal_inliers, inliers);
    win.w.parameterPanel()->undoStack()->redo();
    QVERIFY(win.w.session()->frontEnd() == second);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
  }

  void cancelStopsTheExtraction() {
    Window win;
    QVERIFY(OpenAndExtract(win));
    const auto first = win.w.session()->frontEnd();
    QSignalSpy cancelled(win.w.jobs(), &JobRunner::jobCancelled);
    win.Real("fe_stereo_ratio")->setValue(0.7);  // not cached: a new extraction
    QVERIFY(win.w.jobs()->IsBusy(FrontEndController::kFeaturesJob));
    QTest::qWait(100);
    QElapsedTimer timer;
    timer.start();
    win.w.action(QStringLiteral("cancelJobs"))->trigger();
    HI_WAIT_IDLE(win.w.jobs(), 30000);
    QVERIFY2(timer.elapsed() < 10000, qPrintable(QString::number(timer.elapsed())));
    QCOMPARE(cancelled.size(), 1);
    QCOMPARE(cancelled.first().at(1).toString(), FrontEndController::kFeaturesJob);
    QVERIFY(win.w.session()->frontEnd() == first);  // the last features stay
    QVERIFY(win.errors.isEmpty());
    // On request, with the parameters in force, it runs to the end.
    QVERIFY(win.w.action(QStringLiteral("extractFeatures"))->isEnabled());
    win.w.action(QStringLiteral("extractFeatures"))->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->frontEnd() != first && !win.w.jobs()->IsBusy(), 720000);
    QCOMPARE(win.w.session()->frontEnd()->keyframes.size(), first->keyframes.size());
  }

  void runWaitsForTheFeaturesAndShowsReprojections() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenPaths({ImagesSurveyDir()});
    // Run as soon as the survey is open, while the features are extracted.
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->survey().has_value() && win.w.session()->mesh().has_value(), 60000);
    win.w.action(QStringLiteral("runInspection"))->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->adjustment() && !win.w.jobs()->IsBusy(),
                             1200000);  // a whole adjustment: 60-370 s, by the load
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    QVERIFY(win.w.session()->frontEnd());
    ImagesView* view = win.w.imagesView();
    view->ShowKeyframe(4);
    const ImageOverlay& o = view->overlay();
    QVERIFY(o.reprojections.size() > 20);
    QVERIFY2(o.rms_residual < 1.5, qPrintable(QString::number(o.rms_residual)));
    QVERIFY(view->findChild<QLabel*>(QStringLiteral("imagesLegend"))->text().contains(QStringLiteral("reprojections")));
    auto* dock = qobject_cast<QDockWidget*>(view->parentWidget());
    dock->setFloating(true);
    dock->resize(1000, 820);
    dock->show();
    hull::ui::testing::Settle(view);
    QTest::qWait(200);
    QVERIFY(win.w.GrabView(view).save(OutputDir() + QStringLiteral("/images_view_adjusted.png")));
  }
};

HI_GUI_TEST_MAIN(ImagesViewTest)
#include "images_view_test.moc"
