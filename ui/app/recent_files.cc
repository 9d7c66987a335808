#include "ui/app/recent_files.h"

#include <QDir>
#include <QFileInfo>
#include <QSettings>

namespace hull::ui {

namespace {
const char* kKey = "recentFiles";
}

RecentFiles::RecentFiles(QObject* parent) : QObject(parent) {}

QStringList RecentFiles::paths() const { return QSettings().value(QLatin1String(kKey)).toStringList(); }

void RecentFiles::Add(const QString& path) {
  const QString absolute = QDir::cleanPath(QFileInfo(path).absoluteFilePath());
  QStringList list = paths();
  list.removeAll(absolute);
  list.prepend(absolute);
  while (list.size() > kMaximum) list.removeLast();
  QSettings().setValue(QLatin1String(kKey), list);
  emit changed();
}

void RecentFiles::Clear() {
  QSettings().remove(QLatin1String(kKey));
  emit changed();
}

}  // namespace hull::ui
