// The adjustment results folder (docs/results-format.md, "Adjustment
// results, version 1"):
//   adjustment.json   format "hull-adjustment", version, model, inputs,
//                     options, summary, x_gM, x_s_cT (initial and final),
//                     iteration log
//   timing.json       the wall times (apart, so that the rest is
//                     byte-identical from one run to the next)
//   poses.csv         keyframe,x,y,z,roll,pitch,yaw,servo           (x_gv in g)
//   landmarks.csv     landmark,x,y,z,label,deviation,observations,
//                     sigma_h,cov_*                                 (in g)
//   dvl_residuals.csv keyframe,beam,measured,initial,final          (m; empty = no hit)
#pragma once

#include <string>
#include <vector>

#include "adjust/adjust_result.h"
#include "results/results_folder.h"

namespace hull {

// The files, into the folder `dir` (created when needed; each file written
// atomically). Programs write a whole results folder instead
// (SaveAdjustmentResults, or within WriteResultsFolder).
void WriteAdjustmentResult(const AdjustmentResult& result, const std::string& dir);
// The file names WriteAdjustmentResult writes.
std::vector<std::string> AdjustmentFileNames();

// Reads the folder. Throws InputError naming file, line and field, and when
// the files are not those of one run (results_folder.h, CheckResultsFiles).
AdjustmentResult ReadAdjustmentResult(const std::string& dir);

// `hullinspect-cli adjust`: the folder out.path replaced as a whole by the
// result's files and a manifest naming `run` (its inputs: the survey bundle
// and mesh the result names).
void SaveAdjustmentResults(const AdjustmentResult& result, const OutputFolder& out, ResultsRun run);

}  // namespace hull
