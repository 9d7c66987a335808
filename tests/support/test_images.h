// Images made in code for the image, survey and simulator tests: textured
// test patterns of any OpenCV type, and hand-made PNG files for layouts
// OpenCV does not write (palette, 1-bit, transparency).
#pragma once

#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

namespace hull::testing {

// A deterministic pattern (gradients and a checkerboard of varying contrast)
// of the given size and OpenCV type (CV_8UC1, CV_16UC1, CV_8UC3, ...); 16-bit
// images use the whole range, so they differ from any 8-bit image.
cv::Mat PatternImage(int width, int height, int type, int seed = 0);

// A PNG file written chunk by chunk: IHDR(width, height, bit_depth,
// colour_type), the extra chunks (type, data) in order, one IDAT holding
// `rows` (each row: filter byte 0 then its packed samples, as the PNG
// specification lays them out) compressed with zlib, IEND.
std::string HandMadePng(int width, int height, int bit_depth, int colour_type, const std::string& rows,
                        const std::vector<std::pair<std::string, std::string>>& extra_chunks = {});

}  // namespace hull::testing
