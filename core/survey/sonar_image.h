// Reading and writing the acoustic images of an acoustic sequence, version 2
// (../shared/survey-format.md, "Acoustic images"; the geometry of a polar
// image is SonarImageFormat's, in acoustic_sequence.h).
#pragma once

#include <opencv2/core/mat.hpp>
#include <string>

#include "survey/acoustic_sequence.h"

namespace hull {

// images/<step>.png inside an acoustic sequence folder.
std::string SonarImagePath(const std::string& sequence_dir, long long step);

// Reads one acoustic image (validated by core/image: complete, uncorrupted)
// as CV_8UC1 or CV_16UC1 of exactly range_bins x beams.
// Throws InputError naming the file when it is missing, unreadable,
// truncated, not grey, not 8/16-bit or of another size.
cv::Mat ReadSonarImage(const std::string& path, const SonarImageFormat& format);

// The same checks from the file's container and header alone (no decoding).
void InspectSonarImage(const std::string& path, const SonarImageFormat& format);

// Writes an 8- or 16-bit single-channel image as PNG, atomically (core/image).
void WriteSonarImage(const std::string& path, const cv::Mat& image);

}  // namespace hull
