// One file of a survey bundle or acoustic sequence replaced by the fuzzer's
// bytes; the rest is a small valid base (tests/fuzz/base). Built once per
// file: HI_FUZZ_BASE names the base folder, HI_FUZZ_FILE the file replaced,
// HI_FUZZ_SONAR selects the acoustic sequence readers. Both the throwing
// reader and the collecting validator run on every input.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "survey/acoustic_sequence.h"
#include "survey/survey_io.h"

namespace {

const std::string& Bundle() {
  static const std::string dir = [] {
    const std::string d = hull::fuzz::ScratchDir() + "/bundle";
    hull::fuzz::CopyTree(HI_FUZZ_BASE, d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& dir = Bundle();
  hull::fuzz::WriteInput(dir + "/" HI_FUZZ_FILE, data, size);
#ifdef HI_FUZZ_SONAR
  hull::fuzz::ExpectOnlyInputError([&] { hull::ReadAcousticSequence(dir); });
  hull::fuzz::ExpectOnlyInputError([&] { hull::ValidateAcousticSequence(dir); });
#else
  hull::fuzz::ExpectOnlyInputError([&] { hull::ReadSurveyBundle(dir); });
  hull::fuzz::ExpectOnlyInputError([&] { hull::ValidateSurveyBundle(dir); });
#endif
  return 0;
}
