// A VTK render window's picture as a QImage (VTK side only).
#pragma once

#include <QImage>

class vtkRenderWindow;

namespace hull::ui {

// Renders the window again and reads its back buffer (RGB); a null image
// when the window is not ready or empty.
QImage GrabRenderWindow(vtkRenderWindow* window);

}  // namespace hull::ui
