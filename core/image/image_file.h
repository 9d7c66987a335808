// Image files of survey bundles (version 2) and of the simulators: reading
// with validation into cv::Mat, and atomic PNG/JPEG writing.
//
// Reading never accepts a damaged file silently: the container is walked
// before decoding (PNG: every chunk and its CRC up to IEND; JPEG: every
// marker segment and the entropy-coded data up to EOI), because libjpeg
// decodes a truncated JPEG into a grey-filled image with only a warning. The
// decoded pixels are then checked against the header. Every error is an
// InputError naming the file.
#pragma once

#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace hull {

enum class ImageCodec { kPng, kJpeg };

// What an image file holds, from its header.
struct ImageInfo {
  ImageCodec codec = ImageCodec::kPng;
  int width = 0, height = 0;
  int bit_depth = 8;  // bits per channel: 8 or 16
  int channels = 1;   // 1 grey, 3 colour (decoded in OpenCV's BGR order)

  // "1360x1024 8-bit grey PNG".
  std::string Describe() const;
  // Same bit depth and channels (the size is checked on its own).
  bool SameLayout(const ImageInfo& other) const { return bit_depth == other.bit_depth && channels == other.channels; }
  // The OpenCV type of the decoded pixels (CV_8UC1, CV_16UC3, ...).
  int CvType() const;
};

// What a caller requires of an image; zero or empty fields accept anything.
struct ImageRequirements {
  int width = 0, height = 0;  // exact size in pixels (both or neither)
  // Where the expected size comes from, for the message
  // (e.g. "camera.width x camera.height in survey.json").
  std::string size_source;
  // Bit depth and channels must equal this image's (e.g. the first image of
  // a bundle); layout_source names it for the message.
  std::optional<ImageInfo> same_layout_as;
  std::string layout_source;
};

// Throws InputError naming `name` when `info` breaks a requirement (the
// checks InspectImageFile applies after reading the header).
void CheckImageRequirements(const ImageInfo& info, const std::string& name, const ImageRequirements& required);

// Walks the file's container and reads its header without decoding pixels,
// then applies the requirements. Throws InputError naming `path` when the
// file cannot be read, is neither PNG nor JPEG, is truncated or corrupt, has
// an unsupported layout (not 8/16-bit grey or colour, transparency) or
// breaks a requirement.
ImageInfo InspectImageFile(const std::string& path, const ImageRequirements& required = {});

// As InspectImageFile, then decodes the pixels (CV_8U or CV_16U, 1 or 3
// channels, exactly as stored) and checks them against the header.
cv::Mat ReadImageFile(const std::string& path, const ImageRequirements& required = {}, ImageInfo* info = nullptr);

// The same for bytes already in memory; `name` is used in messages.
ImageInfo InspectImageBytes(std::string_view bytes, const std::string& name, const ImageRequirements& required = {});
cv::Mat DecodeImageBytes(std::string_view bytes, const std::string& name, const ImageRequirements& required = {},
                         ImageInfo* info = nullptr);

struct ImageWriteOptions {
  int png_compression = 1;  // zlib level 0..9 (1: fastest, files ~10 % larger than 9)
  // zlib's Huffman coding only (no string matching): for noisy images such
  // as the simulator's renderings, about 15 % faster and 15 % smaller than
  // the default strategy at level 1; much larger for smooth images.
  bool png_huffman_only = false;
  int jpeg_quality = 95;  // 1..100
};

// Writes an 8- or 16-bit, 1- or 3-channel (BGR) image atomically (a sibling
// temporary, then a rename). The codec follows the extension: ".png", or
// ".jpg"/".jpeg" (8-bit only). Throws std::invalid_argument for another
// image type or extension and std::runtime_error when encoding or writing
// fails.
void WriteImageFile(const std::string& path, const cv::Mat& image, const ImageWriteOptions& options = {});

// The encoded bytes, as WriteImageFile would write them (`extension` is
// ".png", ".jpg" or ".jpeg").
std::string EncodeImage(const cv::Mat& image, const std::string& extension, const ImageWriteOptions& options = {});

}  // namespace hull
