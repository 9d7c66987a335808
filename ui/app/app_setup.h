// Process-wide set-up of the GUI: the OpenGL surface format VTK needs, the
// application's name (which fixes its cache and settings folders), icon and
// resources, and whether there is a display to open windows on.
#pragma once

#include <QIcon>
#include <QString>

namespace hull::ui {

// Call before the QApplication is constructed: sets the default
// QSurfaceFormat to QVTKOpenGLNativeWidget's (OpenGL 3.2 core, depth and
// stencil buffers, no multisampling) and the application's name and version.
void PrepareApplication();

// Call once the QApplication exists: registers the compiled-in resources and
// sets the window icon.
void InitApplication();

// True when a window system is reachable: DISPLAY or WAYLAND_DISPLAY is set.
bool HasDisplay();

QIcon ApplicationIcon();
QString ApplicationVersion();

}  // namespace hull::ui
