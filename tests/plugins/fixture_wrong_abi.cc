// A plugin built against another plugin ABI version (as an old HullInspect's
// plugin_api.h would make it). HullInspect must refuse it without loading
// it: if the file were ever loaded, its constructor would leave a marker
// file that the registry test looks for.
#define HULLINSPECT_PLUGIN_ABI_VERSION 999
#include <cstdio>
#include <cstdlib>

#include "plugin/plugin_api.h"

namespace {

__attribute__((constructor)) void LeaveMarker() {
  if (const char* marker = std::getenv("HI_WRONG_ABI_MARKER")) {
    if (std::FILE* f = std::fopen(marker, "w")) std::fclose(f);
  }
}

class OldPlugin final : public hull::plugin::Plugin {
 public:
  std::string Version() const override { return "0.0.1"; }
  std::string Description() const override { return "built for ABI 999"; }
};

}  // namespace

HULLINSPECT_PLUGIN(OldPlugin, "old-abi")
