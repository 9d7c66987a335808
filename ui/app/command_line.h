// hullinspect's command line: hullinspect [--demo] [MESH] [BUNDLE] [PROJECT.hiproj]
#pragma once

#include <QString>
#include <QStringList>

namespace hull::ui {

struct LaunchOptions {
  bool demo = false;
  bool help = false;
  bool version = false;
  QStringList paths;  // meshes, bundle folders, project files, in order
  QString error;      // non-empty: the command line is wrong (exit code 2)
};

LaunchOptions ParseCommandLine(const QStringList& arguments);  // without argv[0]
QString UsageText();
// What hullinspect prints when there is no display.
QString HeadlessText();

}  // namespace hull::ui
