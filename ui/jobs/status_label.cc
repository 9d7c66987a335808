#include "ui/jobs/status_label.h"

#include <QFontMetrics>

namespace hull::ui {

StatusLabel::StatusLabel(int max_width, QWidget* parent) : QLabel(parent), max_width_(max_width) {
  setMaximumWidth(max_width_);
}

void StatusLabel::SetStatus(const QString& text) {
  full_ = text;
  setToolTip(text);
  const QFontMetrics metrics(font());
  const int room = max_width_ - 2 * margin() - 8;
  setText(metrics.horizontalAdvance(text) <= room ? text : metrics.elidedText(text, Qt::ElideMiddle, room));
}

}  // namespace hull::ui
