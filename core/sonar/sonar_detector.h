// Point features in a polar acoustic image (Mai et al.'s future work:
// "automatic extraction ... of features"): the vertices and corners of an
// object return strongly and compactly, so a feature is a local maximum of
// the denoised image that
//  1. stands out from its local background by min_contrast (ordered-
//     statistics CFAR: the background is the median of a training window
//     around the cell, a guard window left out so the target does not raise
//     its own threshold; a median, unlike a mean, is not raised by the
//     object's other vertices and faces). In a decibel image speckle is
//     additive with a spread fixed by the number of looks, so a fixed offset
//     above the background keeps the false alarm rate constant;
//  2. is the largest value in its neighbourhood (non-maximum suppression),
//  3. is point-like, not a ridge: both curvatures at the peak (at the coarser
//     scale shape_sigma, where the speckle along a ridge averages out) are
//     negative and the smaller is at least min_point_ratio of the larger (the
//     bright lines of walls and of faces seen head-on are curved across
//     them only);
// its position is refined to a fraction of a bin by a parabola through the
// peak and its neighbours in range and in azimuth, and its measurement
// covariance comes from the bin sizes (sigma_bins range bins, sigma_beams
// beams). Pixel values are taken as given (8-bit; 16-bit scaled to 8-bit
// levels): a decibel image (as ARIS and DIDSON store) makes the peak's
// parabola a Gaussian fit.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "survey/acoustic_sequence.h"

namespace hull {

struct SonarDetectorOptions {
  // Gaussian denoising (standard deviation in pixels; 0: none).
  double smooth_sigma = 0.8;
  // Half sizes (rows = range bins, columns = beams) of the guard window left
  // out of the background and of the training window around it.
  int guard_rows = 3, guard_cols = 3;
  int train_rows = 12, train_cols = 8;
  // CFAR: a cell is a target when it exceeds the background median by this
  // many grey levels (in an 8-bit image spanning 60 dB, 60 levels are 14 dB).
  double min_contrast = 60.0;
  // Non-maximum suppression: the peak is the largest value within this many
  // rows and columns.
  int nms_rows = 2, nms_cols = 2;
  // Point-likeness: smaller / larger curvature at the peak, measured after a
  // Gaussian of shape_sigma pixels (0 accepts ridges).
  double min_point_ratio = 0.15;
  double shape_sigma = 2.0;
  // Prominence: on each of 4 axes through the peak, the lower of the two
  // samples ring_radius pixels away on either side; the peak must exceed
  // the highest of those by this many grey levels (a ridge continues on both
  // sides along itself; a point falls off on at least one side of every axis).
  double min_prominence = 20.0;
  double ring_radius = 3.0;
  // Measurement standard deviations in bins (range) and beams (azimuth).
  double sigma_bins = 0.5;
  double sigma_beams = 0.5;
  // The strongest ones are kept when more are found.
  int max_detections = 200;

  bool Check(std::string* why = nullptr) const;
};

struct SonarDetection {
  double row = 0, col = 0;                                   // refined position (fractional range bin and beam)
  double range = 0;                                          // m
  double azimuth = 0;                                        // rad
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // of (range, azimuth)
  double strength = 0;                                       // denoised value at the peak (8-bit levels)
  double contrast = 0;                                       // above the background median (8-bit levels)
  double point_ratio = 0;                                    // smaller / larger curvature at the coarse scale
  double prominence = 0;                                     // above the highest sample of the ring
};

// The detections of one image (range_bins x beams, 8- or 16-bit, one
// channel), strongest first. Throws std::invalid_argument on another size
// or type and OptionError when options.Check() fails.
std::vector<SonarDetection> DetectSonarFeatures(const cv::Mat& image, const SonarSensor& sensor,
                                                const SonarImageFormat& format,
                                                const SonarDetectorOptions& options = {});

}  // namespace hull
