// Acoustic sequences through the whole sonar chain (issue 23, part 6): one
// file of the small valid sequence in tests/fuzz/base/sonar replaced by the
// fuzzer's bytes, read, and when the reader accepts it, run through
// RunSonarPipeline (the EKF from the given measurements and the batch
// smoother with its covariances, a few iterations). The reader may refuse
// with an InputError and the chain may stop with an InputError (a numeric
// breakdown naming sonar.json) or InsufficientData; a crash, a sanitizer
// report or any other exception is a finding. The EKF's crash on
// initial_pose_sigma 1e19 was found this way before the reader bounded it.
#include <string>

#include "base/progress.h"
#include "fuzz_support.h"
#include "fuzz_targets.h"
#include "sonar/sonar_pipeline.h"
#include "survey/acoustic_sequence.h"

namespace hull::fuzz {

void SonarChainFile(const char* base, const char* file, const std::uint8_t* data, std::size_t size) {
  static const std::string dir = [base] {
    const std::string d = ScratchDir() + "/sequence";
    CopyTree(base, d);
    return d;
  }();
  WriteInput(dir + "/" + file, data, size);
  ExpectOnlyInputError([&] { ValidateAcousticSequence(dir); });
  ExpectOnlyInputError([&] {
    const AcousticSequence seq = ReadAcousticSequence(dir);
    SonarPipelineOptions o;
    o.smoother = true;
    o.smoother_options.max_iterations = 5;
    NullProgress progress;
    try {
      RunSonarPipeline(seq, dir, o, progress);
    } catch (const InsufficientData&) {
    }
  });
}

}  // namespace hull::fuzz
