#include "survey/sonar_image.h"

#include <filesystem>

#include "base/error.h"
#include "image/image_file.h"

namespace hull {

std::string SonarImagePath(const std::string& sequence_dir, long long step) {
  return (std::filesystem::path(sequence_dir) / "images" / (std::to_string(step) + ".png")).string();
}

namespace {

ImageRequirements Required(const std::string& path, const SonarImageFormat& format) {
  if (!std::filesystem::exists(path)) {
    throw InputError({path, 0, 0, ""}, "the acoustic image is missing; every step needs images/<step>.png");
  }
  ImageRequirements required;
  required.width = format.beams;
  required.height = format.range_bins;
  required.size_source = "beams x range_bins of sonar.json's image block";
  return required;
}

void CheckGrey(const std::string& path, const ImageInfo& info) {
  if (info.channels != 1 || info.codec != ImageCodec::kPng) {
    throw InputError({path, 0, 0, ""},
                     "the acoustic image is " + info.Describe() + "; acoustic images are 8- or 16-bit grey PNG");
  }
}

}  // namespace

void InspectSonarImage(const std::string& path, const SonarImageFormat& format) {
  CheckGrey(path, InspectImageFile(path, Required(path, format)));
}

cv::Mat ReadSonarImage(const std::string& path, const SonarImageFormat& format) {
  const ImageRequirements required = Required(path, format);
  ImageInfo info;
  cv::Mat image = ReadImageFile(path, required, &info);
  CheckGrey(path, info);
  return image;
}

void WriteSonarImage(const std::string& path, const cv::Mat& image) {
  if (image.channels() != 1) throw std::invalid_argument("WriteSonarImage: acoustic images have one channel");
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteImageFile(path, image);
}

}  // namespace hull
