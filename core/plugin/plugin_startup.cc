// Where plugins load from, and the programs' --plugin-option (plugin_registry.h).
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "base/error.h"
#include "plugin/plugin_registry.h"

namespace hull::plugin {
namespace fs = std::filesystem;
namespace {

// The folder of the running program (from /proc/self/exe); empty if unknown.
fs::path ProgramFolder() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  buf[n] = '\0';
  return fs::path(buf).parent_path();
}

}  // namespace

std::vector<std::string> DefaultPluginFolders() {
  std::vector<std::string> folders;
  if (const char* env = std::getenv("HULLINSPECT_PLUGIN_PATH")) {
    std::string list = env;
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) folders.push_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  const char* xdg = std::getenv("XDG_DATA_HOME");
  const char* home = std::getenv("HOME");
  if (xdg && *xdg) {
    folders.push_back((fs::path(xdg) / "hullinspect" / "plugins").string());
  } else if (home && *home) {
    folders.push_back((fs::path(home) / ".local" / "share" / "hullinspect" / "plugins").string());
  }
  const fs::path program = ProgramFolder();
  if (!program.empty()) {
    folders.push_back((program.parent_path() / "lib" / "hullinspect" / "plugins").lexically_normal().string());
  }
  return folders;
}

void LoadDefaultPlugins() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const std::string& folder : DefaultPluginFolders()) Registry::Global().LoadFolder(folder);
  });
}

std::vector<std::string> TakePluginOptions(const std::vector<std::string>& args, Registry& registry) {
  static const std::string kFlag = "--plugin-option";
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == kFlag) {
      if (i + 1 == args.size()) throw OptionError("plugin-option", "expected <plugin>.<key>=<value> after it");
      registry.SetOption(args[++i]);
    } else if (args[i].rfind(kFlag + "=", 0) == 0) {
      registry.SetOption(args[i].substr(kFlag.size() + 1));
    } else {
      rest.push_back(args[i]);
    }
  }
  return rest;
}

}  // namespace hull::plugin
