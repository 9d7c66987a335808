#include "ui/app/window_layout.h"

#include <QByteArray>
#include <QMainWindow>
#include <QSettings>

namespace hull::ui {

namespace {

const char kGeometryKey[] = "window/geometry";
const char kStateKey[] = "window/state";

}  // namespace

bool RestoreWindowLayout(QMainWindow* window, QSettings* settings) {
  const QByteArray geometry = settings->value(QLatin1String(kGeometryKey)).toByteArray();
  if (geometry.isEmpty() || !window->restoreGeometry(geometry)) return false;
  window->restoreState(settings->value(QLatin1String(kStateKey)).toByteArray(), kWindowLayoutVersion);
  return true;
}

void SaveWindowLayout(const QMainWindow& window, QSettings* settings) {
  settings->setValue(QLatin1String(kGeometryKey), window.saveGeometry());
  settings->setValue(QLatin1String(kStateKey), window.saveState(kWindowLayoutVersion));
  settings->sync();
}

}  // namespace hull::ui
