// Reads a plugin's tag (HULLINSPECT_PLUGIN in plugin_api.h) from the shared
// object file without loading it: the ELF section ".hullinspect_plugin"
// holds "HULLINSPECT_PLUGIN abi=<n> name=<name>". Qt reads its plugins'
// metadata the same way, so that a plugin built for another interface
// version never runs.
#pragma once

#include <string>

namespace hull::plugin {

struct PluginTag {
  int abi = 0;
  std::string name;
};

// Returns false and says why in *why when the file is not a 64-bit
// little-endian ELF shared object with a well-formed tag.
bool ReadPluginTag(const std::string& path, PluginTag* tag, std::string* why);

// Parses the tag's text ("HULLINSPECT_PLUGIN abi=1 name=step-iges").
bool ParsePluginTag(const std::string& text, PluginTag* tag, std::string* why);

}  // namespace hull::plugin
