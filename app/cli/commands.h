// The sub-commands of hullinspect-cli; each takes the arguments after its
// name and returns an ExitCode (see args.h). main.cc dispatches.
#pragma once

#include <string>
#include <vector>

namespace hull::cli {

using CommandArgs = std::vector<std::string>;

int RunSimulate(const CommandArgs& args);  // cmd_simulate.cc
int RunValidate(const CommandArgs& args);  // cmd_validate.cc
int RunInfo(const CommandArgs& args);      // cmd_info.cc
int RunAlign(const CommandArgs& args);     // cmd_align.cc    (GICP initial alignment)
int RunAdjust(const CommandArgs& args);    // cmd_adjust.cc   (model-assisted BA)
int RunMap(const CommandArgs& args);       // cmd_map.cc      (shapes, fusion, assessment)
int RunPipeline(const CommandArgs& args);  // cmd_run.cc      (align -> adjust -> map: the headless main job)
int RunCompare(const CommandArgs& args);   // cmd_compare.cc  (change between two surveys)
int RunSonar(const CommandArgs& args);     // cmd_sonar.cc    (imaging-sonar EKF)
int RunExport(const CommandArgs& args);    // cmd_export.cc   (the remeshed model in other formats)
int RunFeatures(const CommandArgs& args);  // cmd_features.cc (visual front end: images -> features.csv)
int RunPlugins(const CommandArgs& args);   // cmd_plugins.cc  (what loaded, what was refused)
int RunMosaic(const CommandArgs& args);    // cmd_mosaic.cc   (3-D photomosaic of the remeshed model)
int RunReport(const CommandArgs& args);    // cmd_report.cc   (the report of a results folder; needs hull_report)

}  // namespace hull::cli
