// The container structure of PNG and JPEG files, walked without decoding
// pixels: enough to prove a file complete and to read its layout. Used by
// image_file.cc before it hands the bytes to OpenCV.
#pragma once

#include <string>
#include <string_view>

#include "image/image_file.h"

namespace hull {

// Identifies the codec by its signature, walks the whole container and
// returns the header's layout. Throws InputError naming `name` (with the
// byte offset in the message) for a file that is neither PNG nor JPEG, is
// truncated, fails a chunk CRC, or holds a layout this reader refuses (bit
// depths other than 8 and 16, transparency, CMYK, interlaced-less oddities
// such as zero sizes).
ImageInfo WalkImageContainer(std::string_view bytes, const std::string& name);

}  // namespace hull
