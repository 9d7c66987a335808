#include "results/sonar_columns.h"

#include <stdexcept>

namespace hull {
namespace {

void AddPose(std::vector<std::string>& head) {
  for (const char* n : kSonarPoseNames) head.push_back(n);
  for (const char* n : kSonarPoseNames) head.push_back(std::string("sigma_") + n);
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) head.push_back(std::string("cov_") + kSonarPoseNames[i] + "_" + kSonarPoseNames[j]);
  }
}

void AddPoint(std::vector<std::string>& head) {
  for (const char* n : kSonarXyz) head.push_back(n);
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) head.push_back(std::string("cov_") + kSonarXyz[i] + "_" + kSonarXyz[j]);
  }
}

}  // namespace

std::vector<std::string> SonarPoseColumns(bool truth) {
  std::vector<std::string> head = {"step"};
  AddPose(head);
  for (const char* n : kSonarPoseNames) head.push_back(std::string("dr_") + n);
  for (const char* n : {"measurements", "updated", "initialised", "pending", "nis", "nis_dof"}) head.push_back(n);
  if (truth) {
    for (const char* n :
         {"position_error", "rotation_error", "dr_position_error", "dr_rotation_error", "pose_nees",
          "features_in_state", "mean_feature_error", "max_feature_error", "joint_nees", "joint_nees_dof"}) {
      head.push_back(n);
    }
  }
  return head;
}

std::vector<std::string> SonarFeatureColumns(bool truth) {
  std::vector<std::string> head = {"step", "feature", "in_state"};
  AddPoint(head);
  for (const char* n : {"observations", "first_step"}) head.push_back(n);
  if (truth) head.push_back("error");
  return head;
}

std::vector<std::string> SonarDetectionColumns(bool truth) {
  std::vector<std::string> head = {"step",     "detection", "row",         "col",           "range",   "azimuth",
                                   "strength", "contrast",  "range_sigma", "azimuth_sigma", "feature", "pairing"};
  if (truth) head.push_back("truth_feature");
  return head;
}

std::vector<std::string> SonarSmootherPoseColumns(bool truth) {
  std::vector<std::string> head = {"step"};
  AddPose(head);
  if (truth) {
    for (const char* n : {"position_error", "rotation_error", "pose_nees"}) head.push_back(n);
  }
  return head;
}

std::vector<std::string> SonarSmootherFeatureColumns(bool truth) {
  std::vector<std::string> head = {"step", "feature", "smoothed"};
  AddPoint(head);
  for (const char* n : {"views", "weak_sigma"}) head.push_back(n);
  if (truth) head.push_back("error");
  return head;
}

const char* SonarPairingName(SonarPairing p) {
  switch (p) {
    case SonarPairing::kInState:
      return "in_state";
    case SonarPairing::kWaiting:
      return "waiting";
    case SonarPairing::kNew:
      return "new";
  }
  return "?";
}

SonarPairing ParseSonarPairing(const std::string& name) {
  for (SonarPairing p : {SonarPairing::kInState, SonarPairing::kWaiting, SonarPairing::kNew}) {
    if (name == SonarPairingName(p)) return p;
  }
  throw std::invalid_argument("expected in_state, waiting or new");
}

}  // namespace hull
