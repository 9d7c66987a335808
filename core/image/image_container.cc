#include "image/image_container.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>

#include "base/error.h"

namespace hull {
namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
// Larger images are refused before decoding (a corrupt header must not make
// the decoder allocate gigabytes).
constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 28;

[[noreturn]] void Fail(const std::string& name, const std::string& message) {
  throw InputError({name, 0, 0, ""}, message);
}

std::uint32_t Be32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
std::uint32_t Be16(const unsigned char* p) { return (std::uint32_t{p[0]} << 8) | p[1]; }

void CheckSize(const std::string& name, std::uint64_t w, std::uint64_t h) {
  if (w == 0 || h == 0) Fail(name, "the header gives a zero image size");
  if (w * h > kMaxPixels) {
    Fail(name, "the header gives " + std::to_string(w) + "x" + std::to_string(h) +
                   " pixels; this reader refuses images over 268 megapixels");
  }
}

// ---- PNG: signature, then chunks (length, type, data, CRC) up to IEND ------

ImageInfo WalkPng(std::string_view bytes, const std::string& name) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t n = bytes.size();
  ImageInfo info;
  info.codec = ImageCodec::kPng;
  std::size_t pos = 8;
  bool have_header = false, have_data = false;
  while (true) {
    if (pos == n)
      Fail(name, "truncated PNG: the file ends after " + std::to_string(n) + " bytes without an IEND chunk");
    if (n - pos < 12) {
      Fail(name, "truncated PNG: the file ends inside a chunk header at byte " + std::to_string(pos) + " of " +
                     std::to_string(n));
    }
    const std::uint32_t length = Be32(data + pos);
    const std::string type(reinterpret_cast<const char*>(data + pos + 4), 4);
    for (char c : type) {
      if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) {
        Fail(name, "corrupt PNG: no chunk type at byte " + std::to_string(pos + 4));
      }
    }
    if (length > 0x7FFFFFFFu || length > n - pos - 12) {
      Fail(name, "truncated PNG: chunk " + type + " at byte " + std::to_string(pos) + " declares " +
                     std::to_string(length) + " bytes of data, but the file ends after " + std::to_string(n) +
                     " bytes");
    }
    const unsigned char* body = data + pos + 8;
    const std::uint32_t stored_crc = Be32(body + length);
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), data + pos + 4, length + 4);
    if (crc != stored_crc) Fail(name, "corrupt PNG: CRC mismatch in chunk " + type + " at byte " + std::to_string(pos));
    if (!have_header) {
      if (type != "IHDR" || length != 13) Fail(name, "corrupt PNG: the first chunk is not a 13-byte IHDR");
      const std::uint32_t w = Be32(body), h = Be32(body + 4);
      const int depth = body[8], colour = body[9];
      CheckSize(name, w, h);
      info.width = static_cast<int>(w);
      info.height = static_cast<int>(h);
      info.bit_depth = depth;
      switch (colour) {
        case 0:  // grey
          info.channels = 1;
          break;
        case 2:  // RGB
          info.channels = 3;
          break;
        case 3:  // palette: decoded to 8-bit colour
          info.channels = 3;
          info.bit_depth = 8;
          if (depth != 8) {
            Fail(name, "a " + std::to_string(depth) + "-bit palette PNG; expected 8 or 16 bits per channel");
          }
          break;
        case 4:
        case 6:
          Fail(name, std::string("a ") + (colour == 4 ? "grey" : "colour") +
                         " PNG with an alpha channel; expected an opaque grey or RGB image");
        default:
          Fail(name, "corrupt PNG: unknown colour type " + std::to_string(colour));
      }
      if (depth != 8 && depth != 16) {
        Fail(name, "a " + std::to_string(depth) + "-bit PNG; expected 8 or 16 bits per channel");
      }
      have_header = true;
    } else if (type == "tRNS") {
      Fail(name, "a PNG with transparency (tRNS chunk); expected an opaque grey or RGB image");
    } else if (type == "IDAT") {
      have_data = true;
    } else if (type == "IEND") {
      if (!have_data) Fail(name, "corrupt PNG: no image data (IDAT) before IEND");
      return info;  // bytes after IEND are ignored, as decoders do
    }
    pos += 12 + static_cast<std::size_t>(length);
  }
}

// ---- JPEG: SOI, marker segments, entropy-coded scans, EOI ----------------

bool IsStartOfFrame(unsigned char m) { return m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC; }

ImageInfo WalkJpeg(std::string_view bytes, const std::string& name) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t n = bytes.size();
  ImageInfo info;
  info.codec = ImageCodec::kJpeg;
  bool have_frame = false, have_scan = false;
  std::size_t pos = 2;
  auto truncated = [&](const std::string& where) {
    Fail(name,
         "truncated JPEG: the file ends " + where + " after " + std::to_string(n) + " bytes, without an EOI marker");
  };
  while (true) {
    if (pos >= n) truncated("between segments");
    if (data[pos] != 0xFF) Fail(name, "corrupt JPEG: expected a marker at byte " + std::to_string(pos));
    while (pos < n && data[pos] == 0xFF) ++pos;  // fill bytes
    if (pos >= n) truncated("inside a marker");
    const unsigned char marker = data[pos++];
    if (marker == 0xD9) {  // EOI
      if (!have_frame || !have_scan) Fail(name, "corrupt JPEG: EOI before any frame or scan");
      return info;
    }
    if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) continue;  // no length
    if (marker == 0xD8 || marker == 0x00) {
      Fail(name, "corrupt JPEG: unexpected marker at byte " + std::to_string(pos - 1));
    }
    if (n - pos < 2) truncated("inside a segment length");
    const std::uint32_t length = Be16(data + pos);
    if (length < 2) Fail(name, "corrupt JPEG: segment length below 2 at byte " + std::to_string(pos));
    if (length > n - pos) truncated("inside a segment");
    const unsigned char* body = data + pos + 2;
    if (IsStartOfFrame(marker)) {
      if (length < 8) Fail(name, "corrupt JPEG: short frame header at byte " + std::to_string(pos));
      const int precision = body[0];
      const std::uint32_t h = Be16(body + 1), w = Be16(body + 3);
      const int components = body[5];
      if (h == 0)
        Fail(name, "a JPEG whose height is given later (DNL marker); this reader needs it in the frame header");
      CheckSize(name, w, h);
      if (precision != 8) {
        Fail(name, "a " + std::to_string(precision) + "-bit JPEG; expected 8-bit (use 16-bit PNG for deeper images)");
      }
      if (components != 1 && components != 3) {
        Fail(name, "a JPEG with " + std::to_string(components) + " components; expected grey (1) or colour (3)");
      }
      info.width = static_cast<int>(w);
      info.height = static_cast<int>(h);
      info.bit_depth = 8;
      info.channels = components;
      have_frame = true;
    }
    pos += length;
    if (marker == 0xDA) {  // SOS: entropy-coded data up to the next real marker
      if (!have_frame) Fail(name, "corrupt JPEG: a scan before the frame header");
      have_scan = true;
      while (true) {
        if (pos + 1 >= n) truncated("inside the image data");
        if (data[pos] == 0xFF && data[pos + 1] != 0x00 && !(data[pos + 1] >= 0xD0 && data[pos + 1] <= 0xD7) &&
            data[pos + 1] != 0xFF) {
          break;
        }
        ++pos;
      }
    }
  }
}

}  // namespace

ImageInfo WalkImageContainer(std::string_view bytes, const std::string& name) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.empty()) Fail(name, "empty file; expected a PNG or JPEG image");
  if (bytes.size() >= 8 && std::equal(kPngSignature, kPngSignature + 8, data)) return WalkPng(bytes, name);
  if (bytes.size() >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) return WalkJpeg(bytes, name);
  if (bytes.size() < 8 && std::equal(data, data + bytes.size(), kPngSignature)) {
    Fail(name, "truncated PNG: the file ends inside the signature");
  }
  constexpr unsigned char kJpegStart[3] = {0xFF, 0xD8, 0xFF};
  if (bytes.size() < 3 && std::equal(data, data + bytes.size(), kJpegStart)) {
    Fail(name, "truncated JPEG: the file ends inside the start-of-image marker");
  }
  Fail(name, "not a PNG or JPEG image (unknown signature)");
}

}  // namespace hull
