#include "support/test_images.h"

#include <zlib.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

namespace hull::testing {
namespace {

void PutBe32(std::string& s, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s.push_back(static_cast<char>((v >> shift) & 0xFF));
}

void AppendChunk(std::string& png, const std::string& type, const std::string& data) {
  PutBe32(png, static_cast<std::uint32_t>(data.size()));
  const std::string body = type + data;
  png += body;
  PutBe32(png, static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(body.data()),
                                                static_cast<uInt>(body.size()))));
}

}  // namespace

cv::Mat PatternImage(int width, int height, int type, int seed) {
  cv::Mat image(height, width, type);
  const int channels = image.channels();
  const double full = CV_MAT_DEPTH(type) == CV_16U ? 65535.0 : 255.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        const double check = (((x + seed) / 8 + y / 8 + c) % 2) ? 0.25 : -0.25;
        const double v = 0.5 + 0.2 * std::sin(0.05 * x + 0.3 * c + seed) + check * (0.3 + 0.7 * y / double(height));
        const double value = std::round(std::min(1.0, std::max(0.0, v)) * full);
        if (CV_MAT_DEPTH(type) == CV_16U) {
          image.ptr<std::uint16_t>(y)[x * channels + c] = static_cast<std::uint16_t>(value);
        } else if (CV_MAT_DEPTH(type) == CV_8U) {
          image.ptr<std::uint8_t>(y)[x * channels + c] = static_cast<std::uint8_t>(value);
        } else {
          throw std::invalid_argument("PatternImage: 8- or 16-bit unsigned types only");
        }
      }
    }
  }
  return image;
}

std::string HandMadePng(int width, int height, int bit_depth, int colour_type, const std::string& rows,
                        const std::vector<std::pair<std::string, std::string>>& extra_chunks) {
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  PutBe32(ihdr, static_cast<std::uint32_t>(width));
  PutBe32(ihdr, static_cast<std::uint32_t>(height));
  ihdr += {static_cast<char>(bit_depth), static_cast<char>(colour_type), 0, 0, 0};
  AppendChunk(png, "IHDR", ihdr);
  for (const auto& [type, data] : extra_chunks) AppendChunk(png, type, data);
  uLongf size = compressBound(static_cast<uLong>(rows.size()));
  std::string compressed(size, '\0');
  if (compress(reinterpret_cast<Bytef*>(compressed.data()), &size, reinterpret_cast<const Bytef*>(rows.data()),
               static_cast<uLong>(rows.size())) != Z_OK) {
    throw std::runtime_error("HandMadePng: zlib failed");
  }
  compressed.resize(size);
  AppendChunk(png, "IDAT", compressed);
  AppendChunk(png, "IEND", "");
  return png;
}

}  // namespace hull::testing
