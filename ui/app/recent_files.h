// The File ▸ Recent files list, kept in QSettings (most recent first).
#pragma once

#include <QObject>
#include <QStringList>

namespace hull::ui {

class RecentFiles : public QObject {
  Q_OBJECT

 public:
  static constexpr int kMaximum = 10;
  explicit RecentFiles(QObject* parent = nullptr);

  QStringList paths() const;
  // Moves (or adds) the path to the top.
  void Add(const QString& path);
  void Clear();

 signals:
  void changed();
};

}  // namespace hull::ui
