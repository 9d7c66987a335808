// The sonar dock: Help ▸ Open sonar demo simulates the paper's prism with
// its acoustic images and runs the image chain and the EKF in a worker; the view shows the true, first and estimated
// feature points and the trajectory with its ellipsoids; playing steps
// through the sequence and moves the error plots' marker; switching the
// initialisation runs the filter again; File ▸ Open sonar sequence reads a
// folder, and a broken one is reported naming the file; a run saved with
// File ▸ Export ▸ Sonar results reopens (File ▸ Open sonar results) as it
// was, its controls set to how it ran, and runs again from there; the
// parameter table's Sonar rows run the dock again, are saved in the project
// and come back with undo.
#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QScrollArea>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QUndoStack>

#include "gui_test_support.h"
#include "simulate/sonar_image_simulator.h"
#include "simulate/sonar_simulator.h"
#include "ui/app/main_window.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/sonar_panel.h"
#include "ui/session/inspection_parameters.h"
#include "ui/session/project_file.h"
#include "ui/views/plot_widget.h"
#include "ui/views/sonar_fan_view.h"
#include "ui/views/sonar_view.h"

using namespace hull::ui;
using hull::ui::testing::OutputDir;

class SonarTest : public QObject {
  Q_OBJECT

 private slots:
  void theDemoPlaysStepByStep() {
    MainWindow w;
    QStringList errors;
    w.SetErrorSink([&](const QString& t, const QString& m) { errors << t + ": " + m; });
    w.setFixedSize(1280, 900);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    SonarPanel* panel = w.sonarPanel();
    QSignalSpy changed(panel, &SonarPanel::runChanged);
    w.action(QStringLiteral("openSonarDemoPrism"))->trigger();
    QVERIFY(w.jobs()->IsBusy(SonarPanel::kSonarJob));
    HI_WAIT_IDLE(w.jobs(), 60000);
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    QCOMPARE(changed.count(), 1);
    const auto run = panel->run();
    QVERIFY(run && run->result.has_truth);
    QVERIFY(run->from_images);
    QCOMPARE(run->steps(), 21);  // the paper's T = 21
    QCOMPARE(static_cast<int>(run->frames.size()), 21);
    QVERIFY(run->scene && run->scene->num_faces() > 0);
    QCOMPARE(panel->step(), 20);  // opens on the last step
    // The paper's simulation from the images: the features end within a
    // few centimetres, the EKF's pose beats dead reckoning.
    const auto& last = *run->result.steps.back().errors;
    QVERIFY2(last.mean_feature_error < 0.03, qPrintable(QString::number(last.mean_feature_error)));
    QVERIFY(last.position < last.dr_position);
    SonarView::Counts c = panel->view()->counts();
    QCOMPARE(c.true_features, 8);
    const int shown = static_cast<int>(run->result.steps.back().features.size());
    QVERIFY2(shown >= 8, qPrintable(QString::number(shown)));  // every vertex (and tentative clutter)
    QCOMPARE(c.estimated, shown);
    QCOMPARE(c.feature_ellipsoids, shown);
    QCOMPARE(c.pose_ellipsoids, 21);
    QVERIFY(panel->featurePlot()->HasPoints() && panel->positionPlot()->HasPoints());

    // Playing from the start: the step advances on its own, the view and the
    // plots' marker follow.
    panel->SetStep(0);
    QCOMPARE(panel->view()->counts().pose_ellipsoids, 1);
    panel->Play();
    QVERIFY(panel->playing());
    QTRY_VERIFY_WITH_TIMEOUT(panel->step() >= 3, 5000);
    panel->Pause();
    const int step = panel->step();
    QTest::qWait(700);
    QCOMPARE(panel->step(), step);
    QCOMPARE(panel->view()->counts().pose_ellipsoids, step + 1);
    QCOMPARE(panel->fanView()->step(), step);
    QCOMPARE(panel->featurePlot()->data().markers.front().x, static_cast<double>(step));

    // The paper's initialisation: the filter runs again.
    panel->SetStep(20);
    QVERIFY(panel->grab().toImage().save(OutputDir() + QStringLiteral("/sonar_panel.png")));
    panel->initBox()->setCurrentIndex(panel->initBox()->findData(static_cast<int>(hull::SonarInit::kPaper)));
    HI_WAIT_IDLE(w.jobs(), 60000);
    QVERIFY(panel->run() != run);
    QCOMPARE(panel->run()->result.options.init, hull::SonarInit::kPaper);
    QVERIFY(errors.isEmpty());
  }

  void aSequenceFolderOpensAndABrokenOneIsReported() {
    QTemporaryDir dir;
    const QString tank = dir.filePath(QStringLiteral("tank"));
    hull::WriteAcousticSequence(hull::SimulateSonarPreset("tank", 3), QFile::encodeName(tank).toStdString());
    MainWindow w;
    QStringList errors;
    w.SetErrorSink([&](const QString& t, const QString& m) { errors << t + ": " + m; });
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.sonarPanel()->OpenSequence(tank);
    HI_WAIT_IDLE(w.jobs(), 60000);
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    QCOMPARE(w.sonarPanel()->run()->steps(), 8);
    QVERIFY(!w.sonarPanel()->run()->from_images);  // version 1: measurements only
    const auto good = w.sonarPanel()->run();

    QFile measurements(tank + QStringLiteral("/measurements.csv"));
    QVERIFY(measurements.open(QIODevice::WriteOnly | QIODevice::Truncate));
    measurements.write("step,feature,range,azimuth\n0,0,far,0.1\n");
    measurements.close();
    w.sonarPanel()->OpenSequence(tank);
    HI_WAIT_IDLE(w.jobs(), 60000);
    QCOMPARE(errors.size(), 1);
    QVERIFY2(errors[0].contains(QStringLiteral("measurements.csv")), qPrintable(errors[0]));
    QCOMPARE(w.sonarPanel()->run(), good);  // the last good run stays
  }

  void sonarRowsOfTheParameterTableRunTheDockAndAreSaved() {
    MainWindow w;
    QStringList errors;
    w.SetErrorSink([&](const QString& t, const QString& m) { errors << t + ": " + m; });
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.sonarPanel()->OpenDemo(QStringLiteral("prism"));
    HI_WAIT_IDLE(w.jobs(), 60000);
    const auto first = w.sonarPanel()->run();
    QVERIFY(first);
    QCOMPARE(first->result.options.hypotheses, 9);
    auto* hypotheses = qobject_cast<QSpinBox*>(w.parameterPanel()->editor(QStringLiteral("sonar_hypotheses")));
    QVERIFY(hypotheses);
    const int undo_before = w.parameterPanel()->undoStack()->count();
    hypotheses->setValue(15);
    HI_WAIT_IDLE(w.jobs(), 60000);
    QVERIFY(w.sonarPanel()->run() != first);
    QCOMPARE(w.sonarPanel()->run()->result.options.hypotheses, 15);
    QCOMPARE(w.parameterPanel()->undoStack()->count(), undo_before + 1);
    QTemporaryDir tmp;
    const QString project = tmp.filePath(QStringLiteral("sonar.hiproj"));
    QVERIFY(w.SaveProject(project));
    const ProjectData saved = ReadProject(project, DefaultParameterTable(), CheckDefaultParameters);
    QCOMPARE(saved.parameters.value(QStringLiteral("sonar_hypotheses")).toInt(), 15);
    w.parameterPanel()->undoStack()->undo();
    HI_WAIT_IDLE(w.jobs(), 60000);
    QCOMPARE(hypotheses->value(), 9);
    QCOMPARE(w.sonarPanel()->run()->result.options.hypotheses, 9);
    // A value its options refuse is named on its row (collapse 1 is out of (0.5, 1)).
    const std::vector<ParameterError> bad = [&] {
      ParameterValues v = w.parameterPanel()->values();
      v[QStringLiteral("sonar_collapse")] = 1.0;
      return CheckDefaultParameters(v);
    }();
    QVERIFY(!bad.empty());
    QCOMPARE(bad.front().key, QStringLiteral("sonar_collapse"));
    {  // The group as the user sees it (looked at).
      ParameterPanel* panel = w.parameterPanel();
      auto* dock = qobject_cast<QDockWidget*>(panel->parentWidget());
      QVERIFY(dock);
      dock->setFloating(true);
      dock->resize(420, 700);
      dock->show();
      if (auto* scroll = panel->findChild<QScrollArea*>()) {
        scroll->ensureWidgetVisible(panel->editor(QStringLiteral("sonar_smoother_covariances")));
      }
      hull::ui::testing::Settle(dock);
      QVERIFY(panel->grab().save(OutputDir() + QStringLiteral("/sonar_parameters.png")));
    }
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
  }

  void savedResultsReopenAsTheyWere() {
    QTemporaryDir dir;
    const QString prism = dir.filePath(QStringLiteral("prism"));
    hull::WriteSonarImageSimulation(hull::SimulateSonarImages(hull::SonarImagePreset("prism", 2)),
                                    QFile::encodeName(prism).toStdString());
    MainWindow w;
    QStringList errors;
    w.SetErrorSink([&](const QString& t, const QString& m) { errors << t + ": " + m; });
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    SonarPanel* panel = w.sonarPanel();
    panel->initBox()->setCurrentIndex(panel->initBox()->findData(static_cast<int>(hull::SonarInit::kPaper)));
    panel->smootherBox()->setChecked(true);
    panel->OpenSequence(prism);
    HI_WAIT_IDLE(w.jobs(), 60000);
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    const auto ran = panel->run();
    QVERIFY(ran && ran->from_images && ran->smoother);
    const QString saved = dir.filePath(QStringLiteral("saved"));
    panel->SaveResults(saved);
    HI_WAIT_IDLE(w.jobs(), 60000);
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    QVERIFY(QFile::exists(saved + QStringLiteral("/detections.csv")));

    // Another window, controls at their defaults: the saved run as it was.
    MainWindow w2;
    w2.SetErrorSink([&](const QString& t, const QString& m) { errors << t + ": " + m; });
    w2.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w2));
    SonarPanel* p2 = w2.sonarPanel();
    QSignalSpy started(w2.jobs(), &JobRunner::jobStarted);
    p2->OpenResults(saved);
    HI_WAIT_IDLE(w2.jobs(), 60000);
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join('\n')));
    QCOMPARE(started.count(), 1);  // read, not run again
    const auto back = p2->run();
    QVERIFY(back);
    QCOMPARE(back->steps(), ran->steps());
    QCOMPARE(back->result.final_features.size(), ran->result.final_features.size());
    for (std::size_t i = 0; i < ran->result.final_features.size(); ++i) {
      QVERIFY((back->result.final_features[i].position - ran->result.final_features[i].position).norm() < 1e-12);
    }
    QVERIFY(back->smoother && back->from_images);
    QCOMPARE(back->frames.size(), ran->frames.size());
    QCOMPARE(back->frames.back().detections.size(), ran->frames.back().detections.size());
    QCOMPARE(back->frames.back().image.rows, ran->frames.back().image.rows);
    QCOMPARE(p2->initBox()->currentData().toInt(), static_cast<int>(hull::SonarInit::kPaper));
    QVERIFY(p2->smootherBox()->isChecked());
    p2->SetStep(3);
    QCOMPARE(p2->step(), 3);
    QVERIFY(p2->grab().toImage().save(OutputDir() + QStringLiteral("/sonar_panel_reopened.png")));
    // From there the EKF runs again with another option.
    p2->smootherBox()->setChecked(false);
    HI_WAIT_IDLE(w2.jobs(), 60000);
    QVERIFY(p2->run() != back && !p2->run()->smoother);

    // The sequence changed since: refused, naming it.
    QFile controls(prism + QStringLiteral("/controls.csv"));
    QVERIFY(controls.open(QIODevice::Append));
    controls.write("\n");
    controls.close();
    p2->OpenResults(saved);
    HI_WAIT_IDLE(w2.jobs(), 60000);
    QCOMPARE(errors.size(), 1);
    QVERIFY2(errors[0].contains(QStringLiteral("changed since these results were made")), qPrintable(errors[0]));
  }
};

HI_GUI_TEST_MAIN(SonarTest)
#include "sonar_test.moc"
