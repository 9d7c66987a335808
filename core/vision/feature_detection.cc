#include "vision/feature_detection.h"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace hull {

cv::Mat NormaliseImage(const cv::Mat& image, const DetectionOptions& o) {
  if (image.empty()) throw std::invalid_argument("NormaliseImage: empty image");
  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  } else if (image.channels() == 1) {
    grey = image;
  } else {
    throw std::invalid_argument("NormaliseImage: expected 1 or 3 channels");
  }
  cv::Mat g8;
  if (grey.depth() == CV_16U) {
    grey.convertTo(g8, CV_8U, 1.0 / 257.0);
  } else if (grey.depth() == CV_8U) {
    g8 = grey;
  } else {
    throw std::invalid_argument("NormaliseImage: expected 8- or 16-bit pixels");
  }
  if (!o.clahe) return g8;
  cv::Mat out;
  cv::createCLAHE(o.clahe_clip, cv::Size(o.clahe_tiles, o.clahe_tiles))->apply(g8, out);
  return out;
}

ImageFeatures DetectFeatures(const cv::Mat& image, const DetectionOptions& o) {
  o.Check();
  const cv::Mat grey = NormaliseImage(image, o);
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create(o.max_features, 3, o.contrast_threshold, o.edge_threshold, 1.6);
  std::vector<cv::KeyPoint> keys;
  ImageFeatures f;
  sift->detectAndCompute(grey, cv::noArray(), keys, f.descriptors);
  f.points.reserve(keys.size());
  f.sizes.reserve(keys.size());
  // OpenCV's keypoints use the same origin (centre of the top-left pixel).
  for (const auto& k : keys) {
    f.points.emplace_back(k.pt.x, k.pt.y);
    f.sizes.push_back(k.size);
  }
  if (f.descriptors.empty()) f.descriptors = cv::Mat(0, 128, CV_32F);
  return f;
}

float DescriptorDistance2(const float* a, const float* b) {
  float s = 0;
  for (int i = 0; i < 128; ++i) {
    const float d = a[i] - b[i];
    s += d * d;
  }
  return s;
}

}  // namespace hull
