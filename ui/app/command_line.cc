#include "ui/app/command_line.h"

namespace hull::ui {

LaunchOptions ParseCommandLine(const QStringList& arguments) {
  LaunchOptions o;
  bool only_paths = false;
  for (const QString& a : arguments) {
    if (!only_paths && a == QLatin1String("--")) {
      only_paths = true;
    } else if (!only_paths && a == QLatin1String("--demo")) {
      o.demo = true;
    } else if (!only_paths && (a == QLatin1String("--help") || a == QLatin1String("-h"))) {
      o.help = true;
    } else if (!only_paths && a == QLatin1String("--version")) {
      o.version = true;
    } else if (!only_paths && a.startsWith(QLatin1Char('-')) && a.size() > 1) {
      o.error = QStringLiteral("unknown option '%1'").arg(a);
      return o;
    } else {
      o.paths << a;
    }
  }
  if (o.demo && !o.paths.isEmpty()) {
    o.error = QStringLiteral("--demo opens the demo survey and its hull; give it no files");
  }
  return o;
}

QString UsageText() {
  return QStringLiteral(
      "usage: hullinspect [--demo] [MESH] [BUNDLE] [PROJECT.hiproj]\n"
      "\n"
      "HullInspect: inspect ship hulls from underwater robot surveys.\n"
      "\n"
      "  MESH            a hull model (PLY, STL, OBJ, OFF, glTF, ...; also .gz;\n"
      "                  STEP and IGES through the step-iges plugin)\n"
      "  BUNDLE          a survey bundle folder (survey.json, nav.csv, ...)\n"
      "  PROJECT.hiproj  a saved project\n"
      "  --demo          simulate (once, then cached) and open the demo survey\n"
      "  --help          this text\n"
      "  --version       the version\n"
      "  --plugin-option PLUGIN.KEY=VALUE\n"
      "                  set a plugin's option, e.g. step-iges.chord-tolerance=0.002\n"
      "                  (hullinspect-cli plugins lists them)\n"
      "\n"
      "Without a display (no DISPLAY or WAYLAND_DISPLAY) use hullinspect-cli.\n");
}

QString HeadlessText() {
  return QStringLiteral(
      "hullinspect: no display (neither DISPLAY nor WAYLAND_DISPLAY is set), so the desktop application "
      "cannot start.\n"
      "The headless pipeline is:  hullinspect-cli run --demo --out DIR\n");
}

}  // namespace hull::ui
