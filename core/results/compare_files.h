// The comparison of two surveys' results folders (docs/results-format.md,
// "Comparison results, version 2"): the run that reads both mapping folders
// and the CAD mesh and compares them (mapping/survey_compare.h), and its
// folder
//   model.ply     survey B's model with per-vertex change, change_sigma,
//                 change_significant
//   objects.csv   one row per pair of objects and kind of change
//   compare.json  format "hull-compare", version 2: counts, registration,
//                 peak reach, objects
#pragma once

#include <string>
#include <vector>

#include "base/progress.h"
#include "mapping/survey_compare.h"
#include "results/mapping_files.h"
#include "results/results_folder.h"

namespace hull {

// The whole comparison of two results folders (mapping or pipeline results):
// both read, the CAD mesh loaded (`mesh`, or the one A's mapping.json names,
// scaled by mesh_scale) and compared. The two must have been mapped against
// the same CAD mesh, and `mesh` must be that mesh, where their manifests
// record it. Throws InputError naming the file at fault (a folder without
// mapping results, no mesh named, a mixed folder, a mesh that is not the one
// the results were mapped against), hull::Cancelled when progress asks.
struct SurveyComparisonRun {
  std::string folder_a, folder_b;  // the mapping results folders read
  std::string mesh;                // the CAD mesh used
  std::vector<DetectedObject> objects_a, objects_b;
  SurveyComparison comparison;
};
SurveyComparisonRun RunSurveyComparison(const std::string& results_a, const std::string& results_b,
                                        const std::string& mesh, double mesh_scale, const SurveyCompareOptions& options,
                                        Progress& progress);

// The files into `dir` (created when needed).
void WriteSurveyComparison(const SurveyComparison& c, const std::string& dir);
// `hullinspect-cli compare`: the folder out.path replaced as a whole by the
// comparison's files and a manifest naming `run` (inputs: both mapping
// folders and the mesh).
void SaveComparisonResults(const SurveyComparisonRun& c, const OutputFolder& out, ResultsRun run);

// A comparison folder as the report shows it: B's model with the change
// scalars, the objects' changes, the registration and the counts; the two
// mapping folders it compared (from its manifest; "" when unknown). Throws
// InputError naming file and field, and when the files are not those of one run.
struct ComparisonOnDisk {
  SurveyComparison comparison;
  std::string folder_a, folder_b, mesh;
};
ComparisonOnDisk ReadComparisonResults(const std::string& dir);

}  // namespace hull
