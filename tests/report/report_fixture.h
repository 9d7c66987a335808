// The report tests' data, made in code once per process: the demo survey
// simulated and written to disk, run through the pipeline with the three
// surface models and through mapping, and variants of the report's inputs
// (without mapping, with one model, without truth).
#pragma once

#include <string>

#include "results/pipeline_files.h"
#include "ui/report/report_inputs.h"

namespace hull::report::test_data {

struct DemoRun {
  std::string directory;  // the test's output folder
  std::string results;    // WritePipelineResult + mapping/ (for ReadReportInputs)
  ReportInputs full;      // three models, mapping, truth
  ReportInputs no_mapping;
  ReportInputs one_model;  // max-mixture only
  ReportInputs no_truth;
};

const DemoRun& Demo();

}  // namespace hull::report::test_data
