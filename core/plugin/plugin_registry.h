// The plugins a program has loaded, and the choice among their importers and
// exporters (F3D's reader factory with scores; CloudCompare's I/O plugins).
// The mesh loading of core/geometry (LoadMesh), the survey opening of
// core/survey (OpenSurveyBundle) and the result exports ask Global(), so a
// format a plugin reads works in the CLI, the GUI and the pipeline alike.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plugin/plugin_api.h"

namespace hull::plugin {

// A plugin file found in a plugin folder (or a plugin added in code), and
// what became of it.
struct PluginRecord {
  std::string path;     // the file, or where a plugin added in code came from
  std::string name;     // from its tag; the file name when it has none
  int abi = 0;          // from its tag; 0 when it has none
  bool loaded = false;  // false: refused, see `refused`
  std::string refused;  // why it was not loaded
};

// A loaded plugin: the object its file made and what it provides.
struct LoadedPlugin {
  std::string name;
  std::string path;
  std::unique_ptr<Plugin> plugin;  // destroyed last
  std::vector<OptionSpec> options;
  Settings settings;  // the option values in force (defaults until set)
  std::vector<std::unique_ptr<MeshImporter>> mesh_importers;
  std::vector<std::unique_ptr<SurveyImporter>> survey_importers;
  std::vector<std::unique_ptr<ResultExporter>> result_exporters;
};

class Registry {
 public:
  Registry();
  ~Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  // The programs' registry (LoadDefaultPlugins fills it). Load plugins
  // before other threads use it: the lookups are const and thread-safe,
  // loading and SetOption are not. Never destroyed, so plugin code stays
  // valid until the process ends.
  static Registry& Global();

  // Loads every regular file named *.so in `folder`, in name order; a folder
  // that does not exist adds nothing.
  void LoadFolder(const std::string& folder);
  // Loads one plugin file. Its tag is read from the file first: a file that
  // is no plugin, one built for another ABI version, or a second plugin of
  // a name already loaded is refused without being loaded (dlopen).
  const PluginRecord& LoadFile(const std::string& path);
  // Adds a plugin made in code (tests, plugins linked into a program).
  const PluginRecord& Add(const std::string& name, std::unique_ptr<Plugin> plugin, const std::string& origin);

  const std::vector<PluginRecord>& Records() const { return records_; }
  const std::vector<std::unique_ptr<LoadedPlugin>>& Plugins() const { return plugins_; }

  // "<plugin>.<key>=<value>" as given on the command line. Throws
  // OptionError naming the option when the plugin or key is unknown or a
  // numeric value is not a number in its range.
  void SetOption(const std::string& assignment);
  void SetOption(const std::string& plugin, const std::string& key, const std::string& value);

  // Reads `path` with the mesh importer bidding the highest score above
  // `floor`; std::nullopt when none bids more. Errors of the importer come
  // back as InputError naming the file, the importer and its plugin.
  std::optional<ImportedMesh> ImportMesh(const std::string& path, int floor) const;
  // The highest score a mesh importer bids for `path` (kCannotRead: none).
  int BestMeshScore(const std::string& path) const;
  // The extensions the mesh importers name (lower case, with the dot).
  std::vector<std::string> MeshExtensions() const;

  // Converts `path` into a survey bundle in `bundle_dir` (existing, empty)
  // with the survey importer bidding the highest score; std::nullopt when
  // none can read it. Errors come back as InputError naming the file.
  std::optional<Report> ImportSurvey(const std::string& path, const std::string& bundle_dir) const;
  int BestSurveyScore(const std::string& path) const;

  // The exporter for `target`'s extension (nullptr when none), and its plugin.
  const ResultExporter* FindExporter(const std::string& target, const LoadedPlugin** owner = nullptr) const;
  // Writes `target` with FindExporter's exporter; throws std::invalid_argument
  // when there is none, std::runtime_error naming the exporter when it fails.
  Report ExportResults(const Results& results, const std::string& target) const;
  // The extensions the exporters name.
  std::vector<std::string> ExportExtensions() const;

 private:
  PluginRecord& Refuse(PluginRecord record, const std::string& why);
  const LoadedPlugin* FindPlugin(const std::string& name) const;

  std::vector<PluginRecord> records_;
  std::vector<std::unique_ptr<LoadedPlugin>> plugins_;
};

// The folders plugins load from, in this order (a name found twice loads
// from the first): each entry of $HULLINSPECT_PLUGIN_PATH (':'-separated),
// the user's $XDG_DATA_HOME/hullinspect/plugins (by default
// ~/.local/share/hullinspect/plugins), and the installation's
// <program folder>/../lib/hullinspect/plugins (/usr/lib/hullinspect/plugins
// for /usr/bin/hullinspect-cli; build/lib/hullinspect/plugins in a build).
std::vector<std::string> DefaultPluginFolders();

// Loads DefaultPluginFolders() into Registry::Global() (the first call only).
void LoadDefaultPlugins();

// Applies every "--plugin-option <plugin>.<key>=<value>" (or
// "--plugin-option=...") in `args` to `registry` and returns the other
// arguments, so both programs take the option anywhere on their command
// line. Throws OptionError for a bad option.
std::vector<std::string> TakePluginOptions(const std::vector<std::string>& args, Registry& registry);

}  // namespace hull::plugin
