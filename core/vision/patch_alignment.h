// Sub-pixel alignment of one feature's image patch in another image: the
// pixel-level refinement of a track's observations (front_end.h, step 3b).
// SIFT places each keypoint on its own image's scale-space extremum; two
// views of one point are each off by the detector's sub-pixel noise
// (typically 0.2 px, but 1-2 px for 1 % of the pairs on the rendered mono
// survey), and a two-view track seen along a 10 degree baseline turns 1 px
// into centimetres of depth. Aligning every member's patch with one
// reference patch makes their rays meet at the reference pixel's point.
//
// The model: the target image around `point` equals the reference patch
// under a 2x2 warp (affine, or a translation only) and a gain and bias
// (strobe lighting and attenuation differ between views); Gauss-Newton on
// those parameters, each pixel weighted by a Gaussian of its distance from
// the patch centre (sigma = radius / 2).
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace hull {

// A grey image in float with its gradients (central differences).
struct GradientImage {
  cv::Mat image, gx, gy;  // CV_32F, same size
  bool empty() const { return image.empty(); }
};

// From an 8-bit (or 16-bit, scaled to 0..255) grey image.
GradientImage MakeGradientImage(const cv::Mat& grey);

// The (2 radius + 1)^2 values of the image around `centre`, row by row,
// bilinear. False (and out unchanged) when any sample lies outside.
bool SamplePatch(const cv::Mat& image, const Eigen::Vector2d& centre, int radius, std::vector<float>& out);

struct PatchAlignment {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();     // the reference centre's position in the target
  Eigen::Matrix2d warp = Eigen::Matrix2d::Identity();  // reference offsets -> target offsets
  double ncc = -1;                                     // weighted normalised cross-correlation after it
  int iterations = 0;
  bool converged = false;  // the step fell below 1e-3 px in time, inside the image
};

// The local warp (reference offsets -> target offsets) at reference pixel
// x_a of the homography at infinity between two cameras whose rotation
// takes directions of camera a into camera b (R_b_a): the image rotation
// and foreshortening of the views' relative rotation, without the
// depth-dependent scale. A starting warp for AlignPatch from a navigation
// prior (a lawnmower's legs flown the other way turn the image by 180 deg).
Eigen::Matrix2d InfiniteHomographyWarp(const Eigen::Matrix3d& K_a, const Eigen::Matrix3d& K_b,
                                       const Eigen::Matrix3d& R_b_a, const Eigen::Vector2d& x_a);

// Aligns the reference patch (SamplePatch with `radius`) in `target`,
// starting at `guess` with `warp0`. affine: the 2x2 warp is estimated too,
// else only the translation (and gain, bias).
PatchAlignment AlignPatch(const std::vector<float>& reference, int radius, const GradientImage& target,
                          const Eigen::Vector2d& guess, const Eigen::Matrix2d& warp0, bool affine,
                          int max_iterations = 30);

}  // namespace hull
