#include "image/image_file.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "base/error.h"
#include "base/file_io.h"
#include "image/image_container.h"

namespace hull {
namespace {

[[noreturn]] void Fail(const std::string& name, const std::string& message) {
  throw InputError({name, 0, 0, ""}, message);
}

std::string SizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

void CheckImageRequirements(const ImageInfo& info, const std::string& name, const ImageRequirements& r) {
  if ((r.width > 0 || r.height > 0) && (info.width != r.width || info.height != r.height)) {
    Fail(name, "the image is " + SizeText(info.width, info.height) + "; expected " + SizeText(r.width, r.height) +
                   (r.size_source.empty() ? std::string() : " (" + r.size_source + ")"));
  }
  if (r.same_layout_as && !info.SameLayout(*r.same_layout_as)) {
    ImageInfo ref = *r.same_layout_as;
    ref.width = info.width;  // compare the layouts only
    ref.height = info.height;
    Fail(name, "the image is " + std::to_string(info.bit_depth) + "-bit " + (info.channels == 1 ? "grey" : "colour") +
                   "; expected " + std::to_string(ref.bit_depth) + "-bit " + (ref.channels == 1 ? "grey" : "colour") +
                   (r.layout_source.empty() ? std::string() : " like " + r.layout_source) +
                   " (all images of a set must share bit depth and channels)");
  }
}

namespace {

// The file, refused from its size alone when it is larger than an image of
// the required size can be (every pixel 16-bit RGBA, uncompressed, and
// 16 MiB of metadata): a huge or sparse file named as an image costs no
// memory.
std::string ReadBytes(const std::string& path, const ImageRequirements& required) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) == 0 && !ec) {
    Fail(path, "empty file; expected a PNG or JPEG image");
  }
  if (required.width > 0 && required.height > 0) {
    const std::uint64_t cap = std::uint64_t(required.width) * std::uint64_t(required.height) * 8 + (16u << 20);
    return ReadFileToString(path, std::min(cap, kMaxFileBytes),
                            "an image of " + SizeText(required.width, required.height) + " pixels can hold");
  }
  return ReadFileToString(path);  // InputError naming the file when unreadable
}

std::string LowerExtension(const std::string& path) {
  return AsciiLower(std::filesystem::path(path).extension().string());
}

}  // namespace

std::string ImageInfo::Describe() const {
  return SizeText(width, height) + " " + std::to_string(bit_depth) + "-bit " + (channels == 1 ? "grey" : "colour") +
         (codec == ImageCodec::kPng ? " PNG" : " JPEG");
}

int ImageInfo::CvType() const { return CV_MAKETYPE(bit_depth == 16 ? CV_16U : CV_8U, channels); }

ImageInfo InspectImageBytes(std::string_view bytes, const std::string& name, const ImageRequirements& required) {
  const ImageInfo info = WalkImageContainer(bytes, name);
  CheckImageRequirements(info, name, required);
  return info;
}

cv::Mat DecodeImageBytes(std::string_view bytes, const std::string& name, const ImageRequirements& required,
                         ImageInfo* info_out) {
  const ImageInfo info = InspectImageBytes(bytes, name, required);
  const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8UC1,
                       const_cast<char*>(bytes.data()));  // imdecode only reads
  cv::Mat image;
  try {
    image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    Fail(name, std::string("cannot decode the image: ") + e.what());
  }
  if (image.empty()) Fail(name, "cannot decode the image data (corrupt compressed data)");
  if (image.cols != info.width || image.rows != info.height || image.type() != info.CvType()) {
    Fail(name, "the decoded image (" + SizeText(image.cols, image.rows) + ", " + std::to_string(image.channels()) +
                   " channels) does not match its header (" + info.Describe() + ")");
  }
  if (info_out) *info_out = info;
  return image;
}

ImageInfo InspectImageFile(const std::string& path, const ImageRequirements& required) {
  return InspectImageBytes(ReadBytes(path, required), path, required);
}

cv::Mat ReadImageFile(const std::string& path, const ImageRequirements& required, ImageInfo* info) {
  return DecodeImageBytes(ReadBytes(path, required), path, required, info);
}

std::string EncodeImage(const cv::Mat& image, const std::string& extension, const ImageWriteOptions& options) {
  const std::string ext = LowerExtension("x" + extension);
  const bool png = ext == ".png", jpeg = ext == ".jpg" || ext == ".jpeg";
  if (!png && !jpeg) throw std::invalid_argument("EncodeImage: unsupported extension '" + extension + "'");
  if (image.empty()) throw std::invalid_argument("EncodeImage: empty image");
  if (image.depth() != CV_8U && !(png && image.depth() == CV_16U)) {
    throw std::invalid_argument(std::string("EncodeImage: expected 8-bit") + (png ? " or 16-bit" : "") +
                                " pixels for " + ext);
  }
  if (image.channels() != 1 && image.channels() != 3) {
    throw std::invalid_argument("EncodeImage: expected 1 or 3 channels, got " + std::to_string(image.channels()));
  }
  std::vector<int> params;
  if (png) {
    params = {cv::IMWRITE_PNG_COMPRESSION, std::clamp(options.png_compression, 0, 9)};
    if (options.png_huffman_only) {
      params.insert(params.end(), {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY});
    }
  } else {
    params = {cv::IMWRITE_JPEG_QUALITY, std::clamp(options.jpeg_quality, 1, 100)};
  }
  std::vector<unsigned char> buffer;
  if (!cv::imencode(png ? ".png" : ".jpg", image, buffer, params)) {
    throw std::runtime_error("EncodeImage: OpenCV could not encode the image as " + ext);
  }
  return std::string(buffer.begin(), buffer.end());
}

void WriteImageFile(const std::string& path, const cv::Mat& image, const ImageWriteOptions& options) {
  WriteFileAtomic(path, EncodeImage(image, LowerExtension(path), options));
}

}  // namespace hull
