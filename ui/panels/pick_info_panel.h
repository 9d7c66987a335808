// The info panel: details of what was last picked in the 3-D view (a
// landmark, keyframe or object), as label/value rows.
#pragma once

#include <QWidget>

#include "ui/models/pick_details.h"

class QLabel;
class QTreeWidget;

namespace hull::ui {

class PickInfoPanel : public QWidget {
  Q_OBJECT

 public:
  explicit PickInfoPanel(QWidget* parent = nullptr);

  void Show(const PickInfo& info);
  void Clear();
  // Clears, saying why in the title (e.g. the results changed).
  void Clear(const QString& why);
  const PickInfo& info() const { return info_; }
  QString title() const;
  // "label: value" per row, for tests and copying.
  QStringList rowsText() const;

 private:
  PickInfo info_;
  QLabel* title_ = nullptr;
  QTreeWidget* rows_ = nullptr;
};

}  // namespace hull::ui
