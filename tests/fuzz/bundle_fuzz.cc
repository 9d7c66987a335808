// Survey bundles and acoustic sequences: one file of a small valid base
// (tests/fuzz/base) replaced by the fuzzer's bytes. Both the throwing reader
// and the collecting validator run on every input (they take different paths
// through the same code).
#include <string>

#include "fuzz_support.h"
#include "fuzz_targets.h"
#include "survey/acoustic_sequence.h"
#include "survey/survey_io.h"

namespace hull::fuzz {

void BundleFile(const char* base, const char* file, bool sonar, const std::uint8_t* data, std::size_t size) {
  static const std::string dir = [base] {
    const std::string d = ScratchDir() + "/bundle";
    CopyTree(base, d);
    return d;
  }();
  WriteInput(dir + "/" + file, data, size);
  if (sonar) {
    ExpectOnlyInputError([&] { ReadAcousticSequence(dir); });
    ExpectOnlyInputError([&] { ValidateAcousticSequence(dir); });
  } else {
    ExpectOnlyInputError([&] { ReadSurveyBundle(dir); });
    ExpectOnlyInputError([&] { ValidateSurveyBundle(dir); });
  }
}

}  // namespace hull::fuzz
