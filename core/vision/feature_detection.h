// SIFT features of one camera image, after contrast normalisation (CLAHE)
// for the uneven strobe lighting of underwater images (Ozog et al., 3.1).
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "vision/vision_options.h"

namespace hull {

struct ImageFeatures {
  std::vector<Eigen::Vector2d> points;  // pixel positions (origin at the centre of the top-left pixel)
  std::vector<float> sizes;             // SIFT scale (diameter, px)
  cv::Mat descriptors;                  // one CV_32F row of 128 per point
  std::size_t size() const { return points.size(); }
  const float* Descriptor(std::size_t i) const { return descriptors.ptr<float>(static_cast<int>(i)); }
};

// 8-bit grey version of any 8/16-bit grey or colour image (16-bit: scaled by
// 1/257, colour: luminance), then CLAHE when enabled.
cv::Mat NormaliseImage(const cv::Mat& image, const DetectionOptions& options);

// SIFT on NormaliseImage(image). Checks the options (OptionError).
ImageFeatures DetectFeatures(const cv::Mat& image, const DetectionOptions& options);

// Squared L2 distance of two 128-float SIFT descriptors.
float DescriptorDistance2(const float* a, const float* b);

}  // namespace hull
