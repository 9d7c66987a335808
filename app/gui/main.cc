// hullinspect: the desktop application. hullinspect [--demo] [MESH] [BUNDLE] [PROJECT.hiproj]
#include <QApplication>
#include <cstdio>

#include "ui/app_setup.h"
#include "ui/command_line.h"
#include "ui/main_window.h"

namespace {
constexpr int kExitUsage = 2;  // as hullinspect-cli: bad command line, or no display to run on
}

int main(int argc, char** argv) {
  QStringList arguments;
  for (int i = 1; i < argc; ++i) arguments << QString::fromLocal8Bit(argv[i]);
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
    return kExitUsage;
  }

  hull::ui::PrepareApplication();
  QApplication app(argc, argv);
  hull::ui::InitApplication();
  hull::ui::MainWindow window;
  window.show();
  window.Launch(options);
  return app.exec();
}
