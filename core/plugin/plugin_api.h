// The interface between HullInspect and its run-time plugins: shared objects
// (dlopen) that add mesh importers, survey importers and result exporters.
// A plugin includes this header only (standard C++, no HullInspect library
// to link) and ends with one HULLINSPECT_PLUGIN(Class, "name") line; see
// docs/plugins.md for a complete example.
//
// Versioning (CloudCompare's interface ids, Qt's plugin metadata): the macro
// writes the ABI version into an ELF section of the plugin file, which
// HullInspect reads *before* loading the file; a plugin built for another
// ABI version is refused with a message and never loaded (none of its code
// runs). Any change to this header that alters a type's layout, a virtual
// function or a meaning bumps HULLINSPECT_PLUGIN_ABI_VERSION. Plugins must be
// built with the same C++ standard library (GCC's libstdc++, C++11 ABI) as
// HullInspect: the interface passes std::string and std::vector.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// A test defines it first to build a plugin for another ABI version.
#ifndef HULLINSPECT_PLUGIN_ABI_VERSION
#define HULLINSPECT_PLUGIN_ABI_VERSION 1
#endif

namespace hull::plugin {

inline constexpr int kAbiVersion = HULLINSPECT_PLUGIN_ABI_VERSION;

// CanRead scores: the reader with the highest score wins (F3D's reader
// scores). HullInspect's own STL/PLY/OBJ/OFF readers bid kByExtension for
// their extensions, its assimp reader kFallback for the formats assimp knows;
// a plugin outbids them only with a higher score.
inline constexpr int kCannotRead = 0;
inline constexpr int kFallback = 10;
inline constexpr int kByExtension = 50;
inline constexpr int kByContent = 90;  // the file's signature was recognised

// A setting of a plugin, given by the user as
// `--plugin-option <plugin>.<key>=<value>` (hullinspect-cli and hullinspect).
struct OptionSpec {
  std::string key;            // "chord-tolerance"
  std::string default_value;  // "0.005"
  std::string description;    // one line, with the unit
  bool numeric = false;       // the value must be a number in [min, max]
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};
// The values of a plugin's options: every key of Plugin::Options(), the
// defaults filled in, numeric values already checked against their range.
using Settings = std::map<std::string, std::string>;

// What an importer or exporter found or did, one fact per entry
// ({"unit", "millimetre"}, {"surfaces", "12"}); shown to the user.
using Report = std::vector<std::pair<std::string, std::string>>;

// A triangle mesh as plain arrays, in metres.
struct MeshData {
  std::vector<double> positions;        // x, y, z per vertex
  std::vector<std::int32_t> triangles;  // three vertex indices per triangle
  // Named per-vertex values ("deviation"), one value per vertex each.
  std::vector<std::pair<std::string, std::vector<double>>> vertex_scalars;
  // Vertices repeated per triangle (a soup): the host merges coincident ones.
  bool soup = false;

  std::size_t num_vertices() const { return positions.size() / 3; }
  std::size_t num_triangles() const { return triangles.size() / 3; }
};

struct ImportedMesh {
  MeshData mesh;
  Report report;
};

// Reads a mesh format (a CAD hull: STEP, IGES, ...). Read is called from
// worker threads, possibly concurrently: it must be thread-safe.
class MeshImporter {
 public:
  virtual ~MeshImporter() = default;
  virtual std::string Name() const = 0;                     // "STEP (OpenCASCADE)"
  virtual std::vector<std::string> Extensions() const = 0;  // lower case, with the dot: ".step"
  // How well this importer reads `path` (a score above); `head` holds the
  // file's first bytes (up to 4 KiB).
  virtual int CanRead(const std::string& path, std::string_view head) const = 0;
  // Throws a std::exception whose message says what is wrong (the host adds
  // the file and the plugin's name).
  virtual ImportedMesh Read(const std::string& path, const Settings& settings) const = 0;
};

// Turns a foreign survey log (a file or a folder) into a survey bundle.
class SurveyImporter {
 public:
  virtual ~SurveyImporter() = default;
  virtual std::string Name() const = 0;
  virtual std::vector<std::string> Extensions() const = 0;  // empty for folders
  // `head`: the file's first bytes; empty for a folder.
  virtual int CanRead(const std::string& path, std::string_view head) const = 0;
  // Writes a survey bundle (survey.json, nav.csv, ... as the survey bundle
  // contract says) into `bundle_dir`, an existing empty folder. Throws a
  // std::exception on bad input.
  virtual Report Convert(const std::string& path, const std::string& bundle_dir, const Settings& settings) const = 0;
};

// What an exporter is given.
struct Results {
  // The fused, remeshed model in the CAD frame (metres) with its per-vertex
  // "deviation" (m, positive outside the hull) and "fusions".
  MeshData model;
  // The pipeline's output folder (mapping/, and mosaic/ when the
  // photomosaic was made); empty when the results were never written.
  std::string results_dir;
};

class ResultExporter {
 public:
  virtual ~ResultExporter() = default;
  virtual std::string Name() const = 0;
  virtual std::vector<std::string> Extensions() const = 0;  // ".gltf", ".glb"
  // Writes `target` (its extension is one of Extensions()); returns what it
  // wrote. Throws a std::exception on failure.
  virtual Report Export(const Results& results, const std::string& target, const Settings& settings) const = 0;
};

// The object a plugin file makes (HULLINSPECT_PLUGIN). Its importers and
// exporters are asked for once, after loading.
class Plugin {
 public:
  virtual ~Plugin() = default;
  virtual std::string Version() const = 0;
  virtual std::string Description() const = 0;  // one line
  virtual std::vector<OptionSpec> Options() const { return {}; }
  virtual std::vector<std::unique_ptr<MeshImporter>> MeshImporters() const { return {}; }
  virtual std::vector<std::unique_ptr<SurveyImporter>> SurveyImporters() const { return {}; }
  virtual std::vector<std::unique_ptr<ResultExporter>> ResultExporters() const { return {}; }
};

}  // namespace hull::plugin

#define HULLINSPECT_PLUGIN_STR2(x) #x
#define HULLINSPECT_PLUGIN_STR(x) HULLINSPECT_PLUGIN_STR2(x)

// Declares the plugin: `name` is short and unique (letters, digits, '-'),
// the prefix of its options. Expands to the tag HullInspect reads from the
// file before loading it, and the two entry points it calls after.
#define HULLINSPECT_PLUGIN(PluginClass, name)                                                             \
  extern "C" __attribute__((visibility("default"), used, section(".hullinspect_plugin")))                 \
  const char hullinspect_plugin_tag[] =                                                                   \
      "HULLINSPECT_PLUGIN abi=" HULLINSPECT_PLUGIN_STR(HULLINSPECT_PLUGIN_ABI_VERSION) " name=" name;     \
  extern "C" __attribute__((visibility("default"))) int hullinspect_plugin_abi() {                        \
    return HULLINSPECT_PLUGIN_ABI_VERSION;                                                                \
  }                                                                                                       \
  extern "C" __attribute__((visibility("default"))) ::hull::plugin::Plugin* hullinspect_plugin_create() { \
    return new PluginClass;                                                                               \
  }
