#include "vision/feature_detection.h"

#include <algorithm>
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
  cv::Mat grey = NormaliseImage(image, o);
  // Above max_image_size: detected on the image shrunk by `scale` (area
  // averaging), the keypoints mapped back to full-resolution pixels.
  double scale = 1;
  if (const int side = std::max(grey.cols, grey.rows); o.max_image_size > 0 && side > o.max_image_size) {
    scale = static_cast<double>(o.max_image_size) / side;
    cv::Mat small;
    cv::resize(grey, small, cv::Size(), scale, scale, cv::INTER_AREA);
    grey = small;
  }
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create(o.max_features, 3, o.contrast_threshold, o.edge_threshold, 1.6);
  std::vector<cv::KeyPoint> keys;
  ImageFeatures f;
  sift->detectAndCompute(grey, cv::noArray(), keys, f.descriptors);
  f.points.reserve(keys.size());
  f.sizes.reserve(keys.size());
  // OpenCV's keypoints use the same origin (centre of the top-left pixel).
  for (const auto& k : keys) {
    if (scale == 1) {
      f.points.emplace_back(k.pt.x, k.pt.y);
      f.sizes.push_back(k.size);
    } else {
      f.points.emplace_back((k.pt.x + 0.5) / scale - 0.5, (k.pt.y + 0.5) / scale - 0.5);
      f.sizes.push_back(static_cast<float>(k.size / scale));
    }
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
