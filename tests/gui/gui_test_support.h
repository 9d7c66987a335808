// Shared by the GUI tests: the test main (surface format before
// QApplication), the demo loaded directly from the core, and F3D-style
// image comparison with baselines in tests/gui/baselines.
#pragma once

#include <QApplication>
#include <QImage>
#include <QString>
#include <QWidget>
#include <QtTest>
#include <memory>

#include "geometry/triangle_mesh.h"
#include "survey/survey.h"
#include "ui/app/app_setup.h"
#include "ui/jobs/job_runner.h"
#include "ui/session/survey_overlays.h"

namespace hull::ui::testing {

// Prepares the process (folders, surface format); call before QApplication.
void PrepareTestProcess();

// Scratch folder for the test's outputs: <build>/gui-tests/output.
QString OutputDir();
// Where tests cache the demo (XDG_CACHE_HOME/hullinspect, as the app).
QString DemoCacheRoot();

// The demo survey from the cache (simulated on first use), read directly.
struct Demo {
  QString directory, mesh_path;
  std::shared_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const SurveyBundle> bundle;
  std::shared_ptr<const SurveyOverlays> overlays;
};
const Demo& LoadDemo();

// Compares `image` with tests/gui/baselines/<name>.png: a pixel differs when
// a channel differs by more than `channel_tolerance`; the images match when
// at most `max_fraction` of the pixels differ. Always writes the image to
// OutputDir()/<name>.png (and <name>.diff.png on a mismatch). Without a
// baseline it fails, saying how to accept the new image.
bool MatchesBaseline(const QImage& image, const QString& name, QString* message, int channel_tolerance = 40,
                     double max_fraction = 0.01);

// Renders pending paints (and the views' coalesced frames) so that a grab
// shows the current state of `w`.
void Settle(QWidget* w);

}  // namespace hull::ui::testing

// main() for a QTest class that needs a QApplication with VTK's format.
#define HI_GUI_TEST_MAIN(TestClass)          \
  int main(int argc, char** argv) {          \
    hull::ui::testing::PrepareTestProcess(); \
    QApplication app(argc, argv);            \
    hull::ui::InitApplication();             \
    TestClass test;                          \
    return QTest::qExec(&test, argc, argv);  \
  }

// Waits (turning the event loop) until the runner is idle: up to 4 x ms,
// since a job's time is not what these tests check and a loaded 2-core CI
// machine took 167 s for a job that takes 60 s alone (ctest's TIMEOUT still
// bounds the whole test).
#define HI_WAIT_IDLE(runner, ms) QTRY_VERIFY_WITH_TIMEOUT(!(runner)->IsBusy(), 4 * (ms))
