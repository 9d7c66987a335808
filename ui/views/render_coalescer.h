// One render per event-loop turn for a VTK view in a Qt widget.
//
// QVTKOpenGLNativeWidget's paintGL only shows VTK's last frame: a change of
// the scene needs a vtkRenderWindow::Render(). Views ask for a frame after
// every change; the coalescer renders once, on a 1 ms timer rather than a
// posted event, so that the event loop gets a turn (input, timers) between
// the change that asked for the frame and the frame itself. Nothing is
// rendered while the widget is hidden.
#pragma once

#include <QWidget>
#include <functional>

namespace hull::ui {

class RenderCoalescer {
 public:
  RenderCoalescer(QWidget* widget, std::function<void()> render) : widget_(widget), render_(std::move(render)) {}

  void Schedule();

 private:
  QWidget* widget_;
  std::function<void()> render_;
  bool pending_ = false;
};

}  // namespace hull::ui
