// hullinspect-cli: simulate, validate and inspect survey bundles, and run the
// model-assisted pipeline without a display.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/printable.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "plugin/plugin_registry.h"

namespace {

struct Command {
  const char* name;
  int (*run)(const hull::cli::CommandArgs&);
  const char* summary;
};

const Command kCommands[] = {
    {"simulate", hull::cli::RunSimulate, "write a simulated survey bundle or acoustic sequence with truth"},
    {"validate", hull::cli::RunValidate, "check a survey bundle or acoustic sequence against the contract"},
    {"info", hull::cli::RunInfo, "summarise a survey bundle, acoustic sequence or mesh"},
    {"features", hull::cli::RunFeatures, "visual front end: features.csv from a version 2 bundle's images"},
    {"align", hull::cli::RunAlign, "initial model pose: align DVL returns to the mesh (GICP)"},
    {"run", hull::cli::RunPipeline, "the whole pipeline without a display (alignment, adjustment, mapping)"},
    {"adjust", hull::cli::RunAdjust, "model-assisted bundle adjustment (naive, all-on-surface, max-mixture)"},
    {"map", hull::cli::RunMap, "shapes of foreign structure, remeshed hull, fouling assessment"},
    {"mosaic", hull::cli::RunMosaic, "3-D photomosaic: the remeshed model textured from the survey's images"},
    {"compare", hull::cli::RunCompare, "change between two surveys of one hull (per vertex and per object)"},
    {"sonar", hull::cli::RunSonar, "reconstruct features from an acoustic sequence with the sonar EKF"},
#ifdef HI_HAVE_REPORT
    {"report", hull::cli::RunReport, "the inspection report (PDF, HTML) of pipeline, comparison or sonar results"},
#endif
    {"export", hull::cli::RunExport,
     "write the remeshed model of results as PLY, OBJ, STL or a plugin's format (glTF)"},
    {"plugins", hull::cli::RunPlugins, "list the plugins loaded and refused, their formats and options"},
};

void PrintUsage() {
  std::printf(
      "usage: hullinspect-cli <command> [options]\n\n"
      "HullInspect: model-assisted bundle adjustment and mapping of ship hulls.\n\n"
      "commands:\n");
  for (const auto& c : kCommands) std::printf("  %-10s %s\n", c.name, c.summary);
  std::printf(
      "\nRun 'hullinspect-cli <command> --help' for a command's options.\n"
      "Every command takes --plugin-option <plugin>.<key>=<value> (see 'hullinspect-cli plugins').\n\n"
      "exit codes: 0 success, 1 the work failed, 2 bad command line,\n"
      "            3 unreadable or malformed input, 4 insufficient data (the inputs\n"
      "            are well-formed but show too little for a result), 130 cancelled\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    PrintUsage();
    return argc < 2 ? hull::cli::kExitUsage : hull::cli::kExitOk;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::printf("hullinspect-cli %s (plugin ABI %d)\n", HI_VERSION, hull::plugin::kAbiVersion);
    return hull::cli::kExitOk;
  }
  for (const auto& c : kCommands) {
    if (std::strcmp(argv[1], c.name) != 0) continue;
    try {
      // Plugins load before every command, so a format a plugin reads works
      // everywhere; --plugin-option is taken out of the command's arguments.
      hull::plugin::LoadDefaultPlugins();
      const std::vector<std::string> args =
          hull::plugin::TakePluginOptions({argv + 2, argv + argc}, hull::plugin::Registry::Global());
      return c.run(args);
    } catch (const hull::cli::UsageError& e) {
      std::fprintf(stderr, "hullinspect-cli %s: %s\n(see 'hullinspect-cli %s --help')\n", c.name,
                   hull::PrintableText(e.what(), hull::kMaxPrintedMessage).c_str(), c.name);
      return hull::cli::kExitUsage;
    } catch (const hull::InputError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return hull::cli::kExitBadInput;
    } catch (const hull::InsufficientData& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return hull::cli::kExitInsufficientData;
    } catch (const hull::OptionError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return hull::cli::kExitUsage;
    } catch (const hull::Cancelled&) {
      std::fprintf(stderr, "cancelled\n");
      return hull::cli::kExitCancelled;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", hull::PrintableText(e.what(), hull::kMaxPrintedMessage).c_str());
      return hull::cli::kExitFailure;
    }
  }
  std::fprintf(stderr, "hullinspect-cli: unknown command '%s'\n\n", hull::PrintableText(argv[1], 100).c_str());
  PrintUsage();
  return hull::cli::kExitUsage;
}
