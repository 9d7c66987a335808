#include "ui/app/app_setup.h"

#include <QApplication>
#include <QSurfaceFormat>

#include "ui/views/scene_view.h"

static void InitHullInspectResources() { Q_INIT_RESOURCE(hullinspect); }

namespace hull::ui {

void PrepareApplication() {
  QSurfaceFormat::setDefaultFormat(SceneView::SurfaceFormat());
  QCoreApplication::setApplicationName(QStringLiteral("hullinspect"));
  QCoreApplication::setApplicationVersion(ApplicationVersion());
}

void InitApplication() {
  InitHullInspectResources();
  QApplication::setWindowIcon(ApplicationIcon());
  QApplication::setApplicationDisplayName(QStringLiteral("HullInspect"));
}

bool HasDisplay() { return !qEnvironmentVariableIsEmpty("DISPLAY") || !qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY"); }

QIcon ApplicationIcon() {
  QIcon icon;
  icon.addFile(QStringLiteral(":/hullinspect/icon-64.png"), QSize(64, 64));
  icon.addFile(QStringLiteral(":/hullinspect/icon-256.png"), QSize(256, 256));
  return icon;
}

QString ApplicationVersion() { return QStringLiteral(HI_VERSION); }

}  // namespace hull::ui
