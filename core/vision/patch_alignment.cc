#include "vision/patch_alignment.h"

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace hull {

namespace {

// Bilinear sample of a CV_32F image; the caller checks the bounds.
inline float Bilinear(const cv::Mat& m, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const float* r0 = m.ptr<float>(y0) + x0;
  const float* r1 = m.ptr<float>(y0 + 1) + x0;
  return (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
}

inline bool Inside(const cv::Mat& m, double x, double y) {
  return x >= 0 && y >= 0 && x < m.cols - 1 && y < m.rows - 1;
}

}  // namespace

GradientImage MakeGradientImage(const cv::Mat& grey) {
  if (grey.empty() || grey.channels() != 1) throw std::invalid_argument("MakeGradientImage: expected a grey image");
  GradientImage g;
  grey.convertTo(g.image, CV_32F, grey.depth() == CV_16U ? 1.0 / 257.0 : 1.0);
  cv::Sobel(g.image, g.gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0, cv::BORDER_REPLICATE);
  cv::Sobel(g.image, g.gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0, cv::BORDER_REPLICATE);
  return g;
}

bool SamplePatch(const cv::Mat& image, const Eigen::Vector2d& c, int radius, std::vector<float>& out) {
  if (!Inside(image, c.x() - radius, c.y() - radius) || !Inside(image, c.x() + radius, c.y() + radius)) return false;
  out.resize(static_cast<std::size_t>((2 * radius + 1) * (2 * radius + 1)));
  std::size_t i = 0;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) out[i++] = Bilinear(image, c.x() + dx, c.y() + dy);
  }
  return true;
}

Eigen::Matrix2d InfiniteHomographyWarp(const Eigen::Matrix3d& K_a, const Eigen::Matrix3d& K_b,
                                       const Eigen::Matrix3d& R_b_a, const Eigen::Vector2d& x_a) {
  const Eigen::Matrix3d H = K_b * R_b_a * K_a.inverse();
  const Eigen::Vector3d X = H * x_a.homogeneous();
  const Eigen::Vector2d x_b = X.head<2>() / X.z();
  return (H.topLeftCorner<2, 2>() - x_b * H.block<1, 2>(2, 0)) / X.z();
}

PatchAlignment AlignPatch(const std::vector<float>& ref, int radius, const GradientImage& target,
                          const Eigen::Vector2d& guess, const Eigen::Matrix2d& warp0, bool affine, int max_iterations) {
  const int side = 2 * radius + 1;
  if (radius < 1 || ref.size() != static_cast<std::size_t>(side * side))
    throw std::invalid_argument("AlignPatch: the reference patch does not match the radius");
  PatchAlignment out;
  out.point = guess;
  out.warp = warp0;
  // Gaussian weights and offsets.
  const double s2 = 2 * std::pow(0.5 * radius, 2);
  std::vector<double> w(ref.size());
  std::vector<Eigen::Vector2d> d(ref.size());
  double wsum = 0, tmean = 0;
  for (int dy = -radius, i = 0; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx, ++i) {
      d[static_cast<std::size_t>(i)] = Eigen::Vector2d(dx, dy);
      w[static_cast<std::size_t>(i)] = std::exp(-(dx * dx + dy * dy) / s2);
      wsum += w[static_cast<std::size_t>(i)];
      tmean += w[static_cast<std::size_t>(i)] * ref[static_cast<std::size_t>(i)];
    }
  }
  tmean /= wsum;
  double tvar = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) tvar += w[i] * std::pow(ref[i] - tmean, 2);
  tvar /= wsum;
  if (tvar < 1e-6) return out;  // a flat reference: nothing to align

  const cv::Mat& I = target.image;
  std::vector<float> sampled(ref.size());
  // Samples the target under the current warp; false when outside.
  auto sample = [&](const Eigen::Vector2d& t, const Eigen::Matrix2d& A, bool gradients, std::vector<float>* gx,
                    std::vector<float>* gy) {
    for (std::size_t i = 0; i < ref.size(); ++i) {
      const Eigen::Vector2d p = t + A * d[i];
      if (!Inside(I, p.x(), p.y())) return false;
      sampled[i] = Bilinear(I, p.x(), p.y());
      if (gradients) {
        (*gx)[i] = Bilinear(target.gx, p.x(), p.y());
        (*gy)[i] = Bilinear(target.gy, p.x(), p.y());
      }
    }
    return true;
  };
  std::vector<float> gx(ref.size()), gy(ref.size());
  if (!sample(out.point, out.warp, false, nullptr, nullptr)) return out;
  // Gain and bias from the first samples' weighted moments.
  double smean = 0, svar = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) smean += w[i] * sampled[i];
  smean /= wsum;
  for (std::size_t i = 0; i < ref.size(); ++i) svar += w[i] * std::pow(sampled[i] - smean, 2);
  svar /= wsum;
  double gain = std::sqrt(std::max(svar, 1e-6) / tvar), bias = smean - gain * tmean;

  const int np = affine ? 8 : 4;
  Eigen::VectorXd J(np);
  for (int it = 0; it < max_iterations; ++it) {
    out.iterations = it + 1;
    if (!sample(out.point, out.warp, true, &gx, &gy)) return out;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(np, np);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(np);
    for (std::size_t i = 0; i < ref.size(); ++i) {
      const double r = sampled[i] - gain * ref[i] - bias;
      J(0) = gx[i];
      J(1) = gy[i];
      if (affine) {
        J(2) = gx[i] * d[i].x();
        J(3) = gx[i] * d[i].y();
        J(4) = gy[i] * d[i].x();
        J(5) = gy[i] * d[i].y();
      }
      J(np - 2) = -ref[i];
      J(np - 1) = -1;
      H.noalias() += w[i] * J * J.transpose();
      b.noalias() += w[i] * r * J;
    }
    H.diagonal() *= 1.0 + 1e-6;
    const Eigen::VectorXd step = -H.ldlt().solve(b);
    if (!step.allFinite()) return out;
    out.point += step.head<2>();
    if (affine) {
      out.warp(0, 0) += step(2);
      out.warp(0, 1) += step(3);
      out.warp(1, 0) += step(4);
      out.warp(1, 1) += step(5);
    }
    gain += step(np - 2);
    bias += step(np - 1);
    if (step.head<2>().norm() < 1e-3) {
      out.converged = true;
      break;
    }
  }
  if (!sample(out.point, out.warp, false, nullptr, nullptr)) {
    out.converged = false;
    return out;
  }
  double m = 0, v = 0, c = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) m += w[i] * sampled[i];
  m /= wsum;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    v += w[i] * std::pow(sampled[i] - m, 2);
    c += w[i] * (sampled[i] - m) * (ref[i] - tmean);
  }
  out.ncc = v > 0 ? c / std::sqrt(v * tvar * wsum) : -1;
  return out;
}

}  // namespace hull
