// A shown main window for the inspection tests: errors are collected
// instead of shown, and the demo can be opened and run to the end.
#pragma once

#include <QAction>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QStringList>
#include <QtTest>

#include "ui/app/main_window.h"
#include "ui/jobs/job_runner.h"
#include "ui/panels/parameter_panel.h"
#include "ui/session/session.h"

namespace hull::ui::testing {

class Window {
 public:
  Window() {
    w.SetErrorSink([this](const QString& title, const QString& message) { errors << title + ": " + message; });
    w.setFixedSize(1280, 900);
    w.show();
  }
  // Opens the demo and runs the inspection to the end.
  bool OpenAndRun() {
    if (!QTest::qWaitForWindowExposed(&w)) return false;
    w.OpenDemo();
    if (!QTest::qWaitFor([this] { return !w.jobs()->IsBusy(); }, 240000)) return false;
    w.action(QStringLiteral("runInspection"))->trigger();
    // The demo's adjustment with covariances: about 60 s alone, 170 s and
    // more on a loaded 2-core machine; the time is not what is tested.
    return QTest::qWaitFor([this] { return !w.jobs()->IsBusy(); }, 600000) && w.session()->adjustment() != nullptr;
  }
  QDoubleSpinBox* Real(const char* key) {
    return qobject_cast<QDoubleSpinBox*>(w.parameterPanel()->editor(QString::fromLatin1(key)));
  }
  void Raise(QWidget* view) {
    if (auto* dock = qobject_cast<QDockWidget*>(view->parentWidget())) dock->raise();
  }
  MainWindow w;
  QStringList errors;
};

}  // namespace hull::ui::testing
