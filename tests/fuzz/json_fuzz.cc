// HullInspect's JSON layer (core/base/json) alone: the parser under
// survey.json, sonar.json and the truth files, fed text directly (much
// faster than through a bundle).
#include <cstddef>
#include <cstdint>

#include "base/json.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hull::fuzz::ExpectOnlyInputError([&] {
    const hull::Json doc = hull::Json::Parse(hull::fuzz::AsText(data, size), "input.json");
    (void)doc.Dump();
  });
  return 0;
}
