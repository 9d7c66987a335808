#include "gui_test_support.h"

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QStandardPaths>
#include <QTest>
#include <cstdlib>

#include "base/progress.h"
#include "geometry/mesh_io.h"
#include "survey/survey_io.h"
#include "ui/session/demo_cache.h"

namespace hull::ui::testing {

void PrepareTestProcess() {
  // CTest sets XDG_* to folders of the build tree; create them (the runtime
  // folder must be private) so Qt does not complain.
  for (const char* var : {"XDG_CACHE_HOME", "XDG_CONFIG_HOME", "XDG_RUNTIME_DIR"}) {
    const QString dir = qEnvironmentVariable(var);
    if (dir.isEmpty()) continue;
    QDir().mkpath(dir);
    if (QByteArray(var) == "XDG_RUNTIME_DIR") {
      QFile::setPermissions(dir, QFileDevice::ReadOwner | QFileDevice::WriteOwner | QFileDevice::ExeOwner);
    }
  }
  QDir().mkpath(OutputDir());
  PrepareApplication();
}

QString OutputDir() { return QStringLiteral(HI_GUI_TEST_DIR "/output"); }

QString DemoCacheRoot() { return QStandardPaths::writableLocation(QStandardPaths::CacheLocation); }

const Demo& LoadDemo() {
  static const Demo demo = [] {
    NullProgress progress;
    const DemoFiles files = PrepareDemo(QFile::encodeName(DemoCacheRoot()).toStdString(), progress);
    Demo d;
    d.directory = QFile::decodeName(files.directory.c_str());
    d.mesh_path = QFile::decodeName(files.mesh.c_str());
    d.mesh = std::make_shared<TriangleMesh>(LoadMesh(files.mesh));
    auto bundle = std::make_shared<SurveyBundle>(ReadSurveyBundle(files.directory));
    d.overlays = std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*bundle));
    d.bundle = bundle;
    return d;
  }();
  return demo;
}

bool MatchesBaseline(const QImage& image, const QString& name, QString* message, int channel_tolerance,
                     double max_fraction) {
  const QString actual_path = OutputDir() + QLatin1Char('/') + name + QStringLiteral(".png");
  const QString baseline_path = QStringLiteral(HI_SOURCE_DIR "/tests/gui/baselines/") + name + QStringLiteral(".png");
  if (image.isNull()) {
    *message = QStringLiteral("%1: the view produced no image").arg(name);
    return false;
  }
  const QImage actual = image.convertToFormat(QImage::Format_RGB32);
  actual.save(actual_path, "PNG");
  QImage baseline;
  if (!QFile::exists(baseline_path) || !baseline.load(baseline_path)) {
    *message = QStringLiteral(
                   "no baseline %1; the new image is %2 — look at it and, if it is right, accept it with\n"
                   "  cp %2 %1")
                   .arg(baseline_path, actual_path);
    return false;
  }
  baseline = baseline.convertToFormat(QImage::Format_RGB32);
  if (baseline.size() != actual.size()) {
    *message = QStringLiteral("%1: size %2x%3, baseline %4x%5 (new image: %6)")
                   .arg(name)
                   .arg(actual.width())
                   .arg(actual.height())
                   .arg(baseline.width())
                   .arg(baseline.height())
                   .arg(actual_path);
    return false;
  }
  QImage diff(actual.size(), QImage::Format_RGB32);
  diff.fill(Qt::black);
  long long differing = 0;
  for (int y = 0; y < actual.height(); ++y) {
    const auto* a = reinterpret_cast<const QRgb*>(actual.constScanLine(y));
    const auto* b = reinterpret_cast<const QRgb*>(baseline.constScanLine(y));
    auto* d = reinterpret_cast<QRgb*>(diff.scanLine(y));
    for (int x = 0; x < actual.width(); ++x) {
      const int dr = std::abs(qRed(a[x]) - qRed(b[x]));
      const int dg = std::abs(qGreen(a[x]) - qGreen(b[x]));
      const int db = std::abs(qBlue(a[x]) - qBlue(b[x]));
      const int m = std::max({dr, dg, db});
      if (m > channel_tolerance) {
        ++differing;
        d[x] = qRgb(255, 0, 0);
      } else {
        d[x] = qRgb(m, m, m);
      }
    }
  }
  const double fraction = static_cast<double>(differing) / (static_cast<double>(actual.width()) * actual.height());
  if (fraction > max_fraction) {
    const QString diff_path = OutputDir() + QLatin1Char('/') + name + QStringLiteral(".diff.png");
    diff.save(diff_path, "PNG");
    *message = QStringLiteral(
                   "%1: %2 % of the pixels differ from the baseline (at most %3 % allowed); new image %4, "
                   "difference %5")
                   .arg(name)
                   .arg(100.0 * fraction, 0, 'f', 2)
                   .arg(100.0 * max_fraction, 0, 'f', 2)
                   .arg(actual_path, diff_path);
    return false;
  }
  return true;
}

void Settle(QWidget* w) {
  QApplication::processEvents();
  QTest::qWait(50);
  w->repaint();
  QApplication::processEvents();
}

}  // namespace hull::ui::testing
