// hullinspect-cli plugins: the plugin folders, what loaded (with its formats
// and options) and what was refused, and why.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/commands.h"
#include "plugin/plugin_registry.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli plugins

Lists the folders plugins load from (in search order), every plugin loaded
with its importers, exporters and options, and every file refused with the
reason (not a plugin, built for another plugin ABI version, a library it
needs is missing, a second plugin of the same name). Folders:
  $HULLINSPECT_PLUGIN_PATH (':'-separated), searched first
  $XDG_DATA_HOME/hullinspect/plugins (~/.local/share/hullinspect/plugins)
  <program folder>/../lib/hullinspect/plugins (the installation's)
Set an option on any command with --plugin-option <plugin>.<key>=<value>.
--quiet is accepted, as by every command (plugins prints no progress).
)";

std::string Join(const std::vector<std::string>& items) {
  std::string s;
  for (const std::string& i : items) s += (s.empty() ? "" : " ") + i;
  return s;
}

template <typename T>
void PrintItems(const char* kind, const std::vector<std::unique_ptr<T>>& items) {
  for (const auto& item : items) {
    std::printf("    %-15s %s  [%s]\n", kind, item->Name().c_str(), Join(item->Extensions()).c_str());
  }
}

}  // namespace

int RunPlugins(const CommandArgs& argv) {
  Args a(argv, {"quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"quiet"});
  if (!a.positionals().empty()) throw UsageError("takes no arguments");
  const plugin::Registry& registry = plugin::Registry::Global();
  std::printf("plugin ABI version %d; folders, in search order:\n", plugin::kAbiVersion);
  for (const std::string& folder : plugin::DefaultPluginFolders()) {
    std::error_code ec;
    std::printf("  %s%s\n", folder.c_str(), std::filesystem::is_directory(folder, ec) ? "" : "  (absent)");
  }
  std::printf("\nloaded (%zu):\n", registry.Plugins().size());
  for (const auto& p : registry.Plugins()) {
    std::printf("  %s %s  %s\n", p->name.c_str(), p->plugin->Version().c_str(), p->path.c_str());
    std::printf("    %s\n", p->plugin->Description().c_str());
    PrintItems("mesh importer", p->mesh_importers);
    PrintItems("survey importer", p->survey_importers);
    PrintItems("exporter", p->result_exporters);
    for (const plugin::OptionSpec& o : p->options) {
      std::printf("    option          %s.%s = %s  (%s)\n", p->name.c_str(), o.key.c_str(),
                  p->settings.at(o.key).c_str(), o.description.c_str());
    }
  }
  std::size_t refused = 0;
  for (const auto& r : registry.Records()) refused += !r.loaded;
  std::printf("\nrefused (%zu):\n", refused);
  for (const auto& r : registry.Records()) {
    if (!r.loaded) std::printf("  %s  %s\n    %s\n", r.name.c_str(), r.path.c_str(), r.refused.c_str());
  }
  return kExitOk;
}

}  // namespace hull::cli
