// validate -> load -> align -> adjust with a cap on iterations and time, for
// fuzz harnesses (the product-shape issue's corpus run through the whole
// path, not only the readers) and for checks of many mutated bundles
// (issue 14). Bad input ends in a refusal at the stage that caught it; the
// run never hangs (the solver's iterations and wall time are capped, and a
// runaway cost ends it: adjust/cost_watch.h). Any exception other than
// InputError or OptionError escapes: for a fuzzer, that is a finding.
#pragma once

#include <string>
#include <vector>

#include "base/error.h"

namespace hull {

struct CappedRunOptions {
  int max_iterations = 15;   // Levenberg-Marquardt iterations per solve
  double max_seconds = 10;   // solver wall time per solve (s)
  int rejection_rounds = 1;  // outlier-rejection re-solves
  int num_threads = 1;       // one thread: reproducible, and fair to a fuzzer's parallel jobs
  bool align = true;         // GICP of the DVL returns first (else the bundle's model_pose_guess)
  void Check() const;        // throws OptionError naming the field

  // The caps of one fuzz-corpus input (the corpus replay through the whole
  // path, tests/unit/pipeline/robust_input_test.cc): 5 iterations, 2 s per
  // solve, one rejection round, one thread.
  static CappedRunOptions PerFuzzInput();
};

struct CappedRunOutcome {
  enum class Stage { kValidate, kLoad, kAlign, kAdjust, kDone };
  Stage stage = Stage::kValidate;  // the stage reached (kDone: the adjustment finished)
  bool refused = false;            // an InputError or OptionError stopped the run at `stage`
  std::string message;             // the refusal, printable and bounded
  std::vector<Problem> problems;   // what validation found (errors and warnings)
  int iterations = 0;              // of the adjustment, when it ran
  double seconds = 0;              // wall time of the whole run
};
const char* CappedRunStageName(CappedRunOutcome::Stage s);

// Runs the whole path on a bundle folder; the mesh is the bundle's model_hint.
CappedRunOutcome RunCappedValidateAdjust(const std::string& bundle_dir, const CappedRunOptions& options = {});

}  // namespace hull
