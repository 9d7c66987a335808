// The sonar results folder's file names and CSV columns, shared by its
// writer (sonar_files.cc) and reader (sonar_reader.cc). Private to results/.
#pragma once

#include <string>
#include <vector>

#include "sonar/sonar_tracker.h"

namespace hull {

inline constexpr const char* kSonarPosesCsv = "poses.csv";
inline constexpr const char* kSonarFeaturesCsv = "features.csv";
inline constexpr const char* kSonarSummaryJson = "summary.json";
inline constexpr const char* kSonarDetectionsCsv = "detections.csv";
inline constexpr const char* kSonarSmootherPosesCsv = "smoother_poses.csv";
inline constexpr const char* kSonarSmootherFeaturesCsv = "smoother_features.csv";

inline constexpr const char* kSonarPoseNames[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
inline constexpr const char* kSonarXyz[3] = {"x", "y", "z"};

// step, pose, sigma_<pose>, cov_<i>_<j> (upper triangle), dr_<pose>, the
// update's statistics and, with truth, errors and NEES.
std::vector<std::string> SonarPoseColumns(bool truth);
// step, feature, in_state, x, y, z, cov_<i>_<j>, observations, first_step[, error].
std::vector<std::string> SonarFeatureColumns(bool truth);
// step, detection, row, col, range, azimuth, strength, contrast, sigmas,
// feature, pairing[, truth_feature].
std::vector<std::string> SonarDetectionColumns(bool truth);
// step, pose, sigma_<pose>, cov_<i>_<j>[, position_error, rotation_error, pose_nees].
std::vector<std::string> SonarSmootherPoseColumns(bool truth);
// step, feature, smoothed, x, y, z, cov_<i>_<j>, views, weak_sigma[, error].
std::vector<std::string> SonarSmootherFeatureColumns(bool truth);

const char* SonarPairingName(SonarPairing p);  // "in_state", "waiting", "new"
// Throws std::invalid_argument on another name.
SonarPairing ParseSonarPairing(const std::string& name);

}  // namespace hull
