#include "plugin/plugin_registry.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "base/error.h"
#include "base/file_io.h"
#include "plugin/plugin_tag.h"

namespace hull::plugin {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kHeadBytes = 4096;

// The first bytes of a file (empty for a folder or an unreadable file).
std::string ReadHead(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return {};
  std::ifstream in(path, std::ios::binary);
  std::string head(kHeadBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

// Collects the extensions of every T of every plugin, sorted and unique.
template <typename T>
std::vector<std::string> ExtensionsOf(const std::vector<std::unique_ptr<LoadedPlugin>>& plugins,
                                      std::vector<std::unique_ptr<T>> LoadedPlugin::*member) {
  std::set<std::string> all;
  for (const auto& p : plugins) {
    for (const auto& item : (*p).*member) {
      for (const std::string& e : item->Extensions()) all.insert(AsciiLower(e));
    }
  }
  return {all.begin(), all.end()};
}

// The T bidding the highest score for `path` (ties: the first loaded).
template <typename T>
std::pair<const T*, const LoadedPlugin*> Best(const std::vector<std::unique_ptr<LoadedPlugin>>& plugins,
                                              std::vector<std::unique_ptr<T>> LoadedPlugin::*member,
                                              const std::string& path, int* score) {
  const std::string head = ReadHead(path);
  std::pair<const T*, const LoadedPlugin*> best{nullptr, nullptr};
  *score = kCannotRead;
  for (const auto& p : plugins) {
    for (const auto& item : (*p).*member) {
      const int s = item->CanRead(path, head);
      if (s > *score) {
        *score = s;
        best = {item.get(), p.get()};
      }
    }
  }
  return best;
}

}  // namespace

Registry::Registry() = default;
Registry::~Registry() = default;

Registry& Registry::Global() {
  static Registry* const global = new Registry;  // never destroyed: see the header
  return *global;
}

PluginRecord& Registry::Refuse(PluginRecord record, const std::string& why) {
  record.loaded = false;
  record.refused = why;
  records_.push_back(std::move(record));
  return records_.back();
}

const LoadedPlugin* Registry::FindPlugin(const std::string& name) const {
  for (const auto& p : plugins_) {
    if (p->name == name) return p.get();
  }
  return nullptr;
}

void Registry::LoadFolder(const std::string& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return;
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file(ec) && entry.path().extension() == ".so") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) LoadFile(f);
}

const PluginRecord& Registry::LoadFile(const std::string& path) {
  PluginRecord record;
  record.path = path;
  record.name = fs::path(path).filename().string();
  PluginTag tag;
  std::string why;
  if (!ReadPluginTag(path, &tag, &why)) return Refuse(record, why);
  record.name = tag.name;
  record.abi = tag.abi;
  if (tag.abi != kAbiVersion) {
    return Refuse(record, "built for plugin ABI version " + std::to_string(tag.abi) + ", but this HullInspect loads " +
                              "version " + std::to_string(kAbiVersion) +
                              " only: rebuild the plugin against this version's plugin_api.h");
  }
  if (const LoadedPlugin* other = FindPlugin(tag.name)) {
    return Refuse(record, "a plugin named '" + tag.name + "' is already loaded from " + other->path);
  }
  // RTLD_NOW: a missing library or symbol refuses the plugin here, with the
  // loader's message, instead of ending the program later.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) return Refuse(record, std::string("cannot be loaded: ") + dlerror());
  // The handle is never closed: the plugin's code must outlive its objects.
  using AbiFn = int (*)();
  using CreateFn = Plugin* (*)();
  auto abi_fn = reinterpret_cast<AbiFn>(dlsym(handle, "hullinspect_plugin_abi"));
  auto create_fn = reinterpret_cast<CreateFn>(dlsym(handle, "hullinspect_plugin_create"));
  if (!abi_fn || !create_fn) return Refuse(record, "has a tag but no hullinspect_plugin_abi/_create entry points");
  if (abi_fn() != kAbiVersion) {
    return Refuse(record, "its tag says ABI " + std::to_string(tag.abi) + " but its code says " +
                              std::to_string(abi_fn()) + " (a damaged build)");
  }
  std::unique_ptr<Plugin> plugin;
  try {
    plugin.reset(create_fn());
  } catch (const std::exception& e) {
    return Refuse(record, std::string("failed to start: ") + e.what());
  }
  if (!plugin) return Refuse(record, "failed to start (its create function returned nothing)");
  return Add(tag.name, std::move(plugin), path);
}

const PluginRecord& Registry::Add(const std::string& name, std::unique_ptr<Plugin> plugin, const std::string& origin) {
  PluginRecord record;
  record.path = origin;
  record.name = name;
  record.abi = kAbiVersion;
  if (const LoadedPlugin* other = FindPlugin(name)) {
    return Refuse(record, "a plugin named '" + name + "' is already loaded from " + other->path);
  }
  auto loaded = std::make_unique<LoadedPlugin>();
  loaded->name = name;
  loaded->path = origin;
  try {
    loaded->options = plugin->Options();
    for (const OptionSpec& o : loaded->options) loaded->settings[o.key] = o.default_value;
    loaded->mesh_importers = plugin->MeshImporters();
    loaded->survey_importers = plugin->SurveyImporters();
    loaded->result_exporters = plugin->ResultExporters();
  } catch (const std::exception& e) {
    return Refuse(record, std::string("failed to start: ") + e.what());
  }
  loaded->plugin = std::move(plugin);
  plugins_.push_back(std::move(loaded));
  record.loaded = true;
  records_.push_back(record);
  return records_.back();
}

void Registry::SetOption(const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  const std::size_t dot = assignment.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq || dot == 0 || dot + 1 == eq) {
    throw OptionError("plugin-option", "expected <plugin>.<key>=<value>, got '" + assignment + "'");
  }
  SetOption(assignment.substr(0, dot), assignment.substr(dot + 1, eq - dot - 1), assignment.substr(eq + 1));
}

void Registry::SetOption(const std::string& plugin, const std::string& key, const std::string& value) {
  const std::string field = plugin + "." + key;
  LoadedPlugin* p = nullptr;
  for (auto& candidate : plugins_) {
    if (candidate->name == plugin) p = candidate.get();
  }
  if (!p) throw OptionError(field, "no plugin named '" + plugin + "' is loaded (see 'hullinspect-cli plugins')");
  const auto spec =
      std::find_if(p->options.begin(), p->options.end(), [&](const OptionSpec& o) { return o.key == key; });
  if (spec == p->options.end()) {
    std::string known;
    for (const OptionSpec& o : p->options) known += (known.empty() ? "" : ", ") + o.key;
    throw OptionError(field, "plugin '" + plugin + "' has no option '" + key + "'" +
                                 (known.empty() ? std::string(" (it has none)") : "; it has " + known));
  }
  if (spec->numeric) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v) || v < spec->min || v > spec->max) {
      throw OptionError(field, "expected a number from " + std::to_string(spec->min) + " to " +
                                   std::to_string(spec->max) + ", got '" + value + "'");
    }
  }
  p->settings[key] = value;
}

std::optional<ImportedMesh> Registry::ImportMesh(const std::string& path, int floor) const {
  int score = kCannotRead;
  const auto [importer, owner] = Best(plugins_, &LoadedPlugin::mesh_importers, path, &score);
  if (!importer || score <= floor) return std::nullopt;
  try {
    return importer->Read(path, owner->settings);
  } catch (const std::exception& e) {
    throw InputError({path, 0, 0, ""}, importer->Name() + " (plugin " + owner->name + "): " + e.what());
  }
}

int Registry::BestMeshScore(const std::string& path) const {
  int score = kCannotRead;
  Best(plugins_, &LoadedPlugin::mesh_importers, path, &score);
  return score;
}

std::vector<std::string> Registry::MeshExtensions() const {
  return ExtensionsOf(plugins_, &LoadedPlugin::mesh_importers);
}

std::optional<Report> Registry::ImportSurvey(const std::string& path, const std::string& bundle_dir) const {
  int score = kCannotRead;
  const auto [importer, owner] = Best(plugins_, &LoadedPlugin::survey_importers, path, &score);
  if (!importer) return std::nullopt;
  try {
    return importer->Convert(path, bundle_dir, owner->settings);
  } catch (const std::exception& e) {
    throw InputError({path, 0, 0, ""}, importer->Name() + " (plugin " + owner->name + "): " + e.what());
  }
}

int Registry::BestSurveyScore(const std::string& path) const {
  int score = kCannotRead;
  Best(plugins_, &LoadedPlugin::survey_importers, path, &score);
  return score;
}

const ResultExporter* Registry::FindExporter(const std::string& target, const LoadedPlugin** owner) const {
  const std::string ext = AsciiLower(fs::path(target).extension().string());
  for (const auto& p : plugins_) {
    for (const auto& e : p->result_exporters) {
      for (const std::string& x : e->Extensions()) {
        if (AsciiLower(x) != ext) continue;
        if (owner) *owner = p.get();
        return e.get();
      }
    }
  }
  return nullptr;
}

Report Registry::ExportResults(const Results& results, const std::string& target) const {
  const LoadedPlugin* owner = nullptr;
  const ResultExporter* exporter = FindExporter(target, &owner);
  if (!exporter) {
    throw std::invalid_argument("no exporter writes '" + fs::path(target).extension().string() + "' files (" + target +
                                ")");
  }
  try {
    return exporter->Export(results, target, owner->settings);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write " + target + ": " + exporter->Name() + " (plugin " + owner->name +
                             "): " + e.what());
  }
}

std::vector<std::string> Registry::ExportExtensions() const {
  return ExtensionsOf(plugins_, &LoadedPlugin::result_exporters);
}

}  // namespace hull::plugin
