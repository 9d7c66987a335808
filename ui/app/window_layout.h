// The main window's geometry and dock layout kept across sessions (issue
// 25.5): saved when the window closes, restored when it opens, in the
// user's settings (QSettings; tests pass a file of their own). A layout of
// another version of the docks is not applied.
#pragma once

class QMainWindow;
class QSettings;

namespace hull::ui {

// Bump when docks are added, removed or renamed: an older saved state is
// then ignored (QMainWindow::restoreState refuses another version).
constexpr int kWindowLayoutVersion = 1;

// False when `settings` holds no usable layout (the first start).
bool RestoreWindowLayout(QMainWindow* window, QSettings* settings);
void SaveWindowLayout(const QMainWindow& window, QSettings* settings);

}  // namespace hull::ui
