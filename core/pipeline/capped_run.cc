#include "pipeline/capped_run.h"

#include <chrono>

#include "base/printable.h"
#include "pipeline/pipeline.h"
#include "survey/survey_io.h"

namespace hull {

void CappedRunOptions::Check() const {
  if (max_iterations < 1) throw OptionError("max_iterations", "must be >= 1");
  if (!(max_seconds > 0)) throw OptionError("max_seconds", "must be > 0");
  if (rejection_rounds < 0) throw OptionError("rejection_rounds", "must be >= 0");
  if (num_threads < 1) throw OptionError("num_threads", "must be >= 1");
}

CappedRunOptions CappedRunOptions::PerFuzzInput() {
  CappedRunOptions caps;
  caps.max_iterations = 5;
  caps.max_seconds = 2;
  caps.rejection_rounds = 1;
  caps.num_threads = 1;
  return caps;
}

const char* CappedRunStageName(CappedRunOutcome::Stage s) {
  switch (s) {
    case CappedRunOutcome::Stage::kValidate:
      return "validate";
    case CappedRunOutcome::Stage::kLoad:
      return "load";
    case CappedRunOutcome::Stage::kAlign:
      return "align";
    case CappedRunOutcome::Stage::kAdjust:
      return "adjust";
    case CappedRunOutcome::Stage::kDone:
      return "done";
  }
  return "?";
}

CappedRunOutcome RunCappedValidateAdjust(const std::string& bundle_dir, const CappedRunOptions& options) {
  options.Check();
  const auto t0 = std::chrono::steady_clock::now();
  CappedRunOutcome out;
  auto finish = [&]() -> CappedRunOutcome& {
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  };
  out.problems = ValidateSurveyBundle(bundle_dir);
  for (const Problem& p : out.problems) {
    if (p.severity != Severity::kError) continue;
    out.refused = true;
    out.message = p.ToString();
    return finish();
  }
  try {
    out.stage = CappedRunOutcome::Stage::kLoad;
    const PipelineInputs in = LoadPipelineInputs(bundle_dir);
    NullProgress progress;
    Pose x_gM;
    if (options.align || !in.bundle.manifest.model_pose_guess) {
      out.stage = CappedRunOutcome::Stage::kAlign;
      x_gM = RunAlignment(in, PipelineOptions(), progress).x_gM;
    } else {
      x_gM = Pose::FromVector(*in.bundle.manifest.model_pose_guess);
    }
    out.stage = CappedRunOutcome::Stage::kAdjust;
    AdjustmentOptions o;
    o.max_iterations = options.max_iterations;
    o.max_solver_seconds = options.max_seconds;
    o.rejection_rounds = options.rejection_rounds;
    o.num_threads = options.num_threads;
    const AdjustmentResult r = RunAdjustmentStep(in, x_gM, o, progress);
    out.iterations = r.iterations.empty() ? 0 : r.iterations.back().iteration;
    out.stage = CappedRunOutcome::Stage::kDone;
  } catch (const InputError& e) {
    out.refused = true;
    out.message = PrintableText(e.what(), kMaxPrintedMessage + kMaxPrintedPath);
  } catch (const OptionError& e) {
    out.refused = true;
    out.message = PrintableText(e.what(), kMaxPrintedMessage);
  }
  return finish();
}

}  // namespace hull
