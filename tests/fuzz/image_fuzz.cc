// PNG and JPEG files read by InspectImageFile (container walk and header)
// and ReadImageFile (decode and check), as survey bundles' and acoustic
// sequences' images are read.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "image/image_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = hull::fuzz::ScratchDir() + "/input.img";
  hull::fuzz::WriteInput(path, data, size);
  hull::fuzz::ExpectOnlyInputError([&] { hull::InspectImageFile(path); });
  hull::fuzz::ExpectOnlyInputError([&] { hull::ReadImageFile(path); });
  return 0;
}
