#include "ui/views/render_coalescer.h"

#include <QTimer>

namespace hull::ui {

void RenderCoalescer::Schedule() {
  if (pending_) return;
  pending_ = true;
  QTimer::singleShot(1, widget_, [this] {
    pending_ = false;
    if (widget_->isVisible()) render_();
  });
}

}  // namespace hull::ui
