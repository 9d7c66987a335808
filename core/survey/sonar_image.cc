#include "survey/sonar_image.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <vector>

#include "base/error.h"
#include "base/file_io.h"

namespace hull {

std::string SonarImagePath(const std::string& sequence_dir, long long step) {
  return (std::filesystem::path(sequence_dir) / "images" / (std::to_string(step) + ".png")).string();
}

cv::Mat ReadSonarImage(const std::string& path, const SonarImageFormat& format) {
  if (!std::filesystem::exists(path)) {
    throw InputError({path, 0, 0, ""}, "the acoustic image is missing; every step needs images/<step>.png");
  }
  const std::string bytes = ReadFileToString(path);
  static const char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
  if (bytes.size() < 8 || bytes.compare(0, 8, std::string(kSignature, 8)) != 0) {
    throw InputError({path, 0, 0, ""}, "not a PNG file (the acoustic images must be 8- or 16-bit grey PNG)");
  }
  const std::vector<uchar> buffer(bytes.begin(), bytes.end());
  cv::Mat image;
  try {
    image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    image.release();
  }
  if (image.empty()) {
    throw InputError({path, 0, 0, ""}, "cannot decode the PNG (truncated or corrupt file)");
  }
  if (image.channels() != 1) {
    throw InputError({path, 0, 0, ""}, "the acoustic image has " + std::to_string(image.channels()) +
                                           " channels; expected a single grey channel");
  }
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw InputError({path, 0, 0, ""}, "the acoustic image must be 8- or 16-bit");
  }
  if (image.rows != format.range_bins || image.cols != format.beams) {
    throw InputError({path, 0, 0, ""}, "the acoustic image is " + std::to_string(image.cols) + " x " +
                                           std::to_string(image.rows) +
                                           " (beams x range bins); sonar.json's image "
                                           "block says " +
                                           std::to_string(format.beams) + " beams x " +
                                           std::to_string(format.range_bins) + " range bins");
  }
  return image;
}

void WriteSonarImage(const std::string& path, const cv::Mat& image) {
  if (image.empty() || image.channels() != 1 || (image.depth() != CV_8U && image.depth() != CV_16U)) {
    throw std::invalid_argument("WriteSonarImage: expected a non-empty 8- or 16-bit single-channel image");
  }
  std::vector<uchar> png;
  if (!cv::imencode(".png", image, png)) throw std::runtime_error("WriteSonarImage: PNG encoding failed for " + path);
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteFileAtomic(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace hull
