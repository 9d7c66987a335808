// hullinspect: the desktop application. hullinspect [--demo] [MESH] [BUNDLE] [PROJECT.hiproj]
// Without a display, `hullinspect --demo [--out DIR]` runs the headless main
// job instead (as do --report RESULTS --out DIR and --demo --out DIR anywhere):
// see ui/report/headless_job.h.
#include <QApplication>
#include <QGuiApplication>
#include <QSettings>
#include <cstdio>
#include <string>
#include <vector>

#include "base/error.h"
#include "plugin/plugin_registry.h"
#include "ui/app/app_setup.h"
#include "ui/app/command_line.h"
#include "ui/app/main_window.h"
#include "ui/report/headless_job.h"

namespace {
constexpr int kExitUsage = 2;  // as hullinspect-cli: bad command line, or no display to run on
}

int main(int argc, char** argv) {
  // Plugins first: the mesh, survey and export formats they add work in the
  // window and the headless job alike; --plugin-option is taken out here.
  hull::plugin::LoadDefaultPlugins();
  std::vector<std::string> args;
  try {
    args = hull::plugin::TakePluginOptions({argv + 1, argv + argc}, hull::plugin::Registry::Global());
  } catch (const hull::OptionError& e) {
    std::fprintf(stderr, "hullinspect: %s\n", e.what());
    return kExitUsage;
  }
  QStringList arguments;
  for (const std::string& a : args) arguments << QString::fromLocal8Bit(a.c_str());
  // The headless main job: no window, the report's figures drawn offscreen
  // (QPainter, no VTK), so Qt needs no X server.
  if (hull::report::IsBatchCommand(arguments) ||
      (!hull::ui::HasDisplay() && arguments.contains(QStringLiteral("--demo")))) {
    const hull::report::HeadlessCommand command = hull::report::ParseHeadlessCommand(arguments);
    if (!command.error.isEmpty() || command.help) return hull::report::RunHeadlessJob(command);  // no Qt needed
    hull::report::PrepareHeadless();
    QGuiApplication app(argc, argv);
    return hull::report::RunHeadlessJob(command);
  }
  const hull::ui::LaunchOptions options = hull::ui::ParseCommandLine(arguments);
  if (!options.error.isEmpty()) {
    std::fprintf(stderr, "hullinspect: %s\n\n%s", qPrintable(options.error), qPrintable(hull::ui::UsageText()));
    return kExitUsage;
  }
  if (options.help) {
    std::fputs(qPrintable(hull::ui::UsageText()), stdout);
    return 0;
  }
  if (options.version) {
    std::printf("hullinspect %s\n", qPrintable(hull::ui::ApplicationVersion()));
    return 0;
  }
  // Without a window system QApplication would abort; say what to run instead.
  if (!hull::ui::HasDisplay()) {
    std::fputs(qPrintable(hull::ui::HeadlessText()), stderr);
    std::fputs(qPrintable(QStringLiteral("\n") + hull::report::HeadlessUsage()), stderr);
    return kExitUsage;
  }

  hull::ui::PrepareApplication();
  QApplication app(argc, argv);
  hull::ui::InitApplication();
  QSettings settings;  // the layout of the last session (before the window: it outlives it)
  hull::ui::MainWindow window;
  // The first start fills the screen.
  if (window.RestoreLayout(&settings)) {
    window.show();
  } else {
    window.showMaximized();
  }
  window.Launch(options);
  return app.exec();
}
