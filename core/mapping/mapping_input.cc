#include "mapping/mapping_input.h"

#include <algorithm>
#include <unordered_map>

#include "base/error.h"
#include "survey/survey_origin.h"

namespace hull {
namespace {

// Attaches the bundle's observations to the keyframes (by id); observations
// of unknown keyframes or landmarks are skipped.
void AttachObservations(const SurveyBundle& bundle, const std::unordered_map<std::int64_t, int>& keyframe_index,
                        const std::unordered_map<std::int64_t, int>& landmark_index, MappingInput& in) {
  for (const auto& f : bundle.features) {
    const auto k = keyframe_index.find(f.keyframe);
    const auto l = landmark_index.find(f.landmark);
    if (k == keyframe_index.end() || l == landmark_index.end()) continue;
    in.keyframes[static_cast<std::size_t>(k->second)].landmarks.push_back(l->second);
  }
  for (auto& k : in.keyframes) {
    std::sort(k.landmarks.begin(), k.landmarks.end());
    k.landmarks.erase(std::unique(k.landmarks.begin(), k.landmarks.end()), k.landmarks.end());
  }
}

}  // namespace

MappingInput MappingInputFromAdjustment(const AdjustmentResult& r, const SurveyBundle& bundle) {
  MappingInput in;
  in.source = "adjustment";
  const Eigen::Vector3d to_local = -LocalOrigin(bundle);
  in.x_gM = Pose::FromVector(ShiftedFrame(r.x_gM, to_local));
  in.camera = bundle.manifest.camera;
  in.model_axes = bundle.manifest.model_axes;
  const Pose x_s_cT = Pose::FromVector(r.x_s_cT);
  if (r.poses.size() != r.keyframes.size() || r.servo.size() != r.keyframes.size()) {
    throw InputError({r.bundle_path, 0, 0, "poses"},
                     "the adjustment's poses and servo angles do not match its keyframes");
  }
  const auto nav = bundle.KeyframeIndex();
  std::unordered_map<std::int64_t, int> keyframe_index;
  for (std::size_t i = 0; i < r.keyframes.size(); ++i) {
    if (!nav.count(r.keyframes[i])) {
      throw InputError({bundle.directory + "/nav.csv", 0, 0, "keyframe"},
                       "keyframe " + std::to_string(r.keyframes[i]) +
                           " of the adjustment is not in the bundle: they do not belong together");
    }
    MappingKeyframe k;
    k.id = r.keyframes[i];
    k.x_g_cT =
        Pose::FromVector(ShiftedFrame(r.poses[i], to_local)) * bundle.manifest.VehicleToServo(r.servo[i]) * x_s_cT;
    keyframe_index.emplace(k.id, static_cast<int>(in.keyframes.size()));
    in.keyframes.push_back(std::move(k));
  }
  std::unordered_map<std::int64_t, int> landmark_index;
  for (const auto& l : r.landmarks) {
    landmark_index.emplace(l.id, static_cast<int>(in.landmarks.size()));
    in.landmarks.push_back({l.id, l.p + to_local, l.deviation, l.sigma_h});
  }
  AttachObservations(bundle, keyframe_index, landmark_index, in);
  return in;
}

MappingInput MappingInputFromTruth(const SurveyBundle& bundle) {
  if (!bundle.truth) {
    throw InputError({bundle.directory + "/truth", 0, 0, ""}, "the bundle has no truth/ to map from");
  }
  const SurveyTruth& t = *bundle.truth;
  MappingInput in;
  in.source = "truth";
  const Eigen::Vector3d to_local = -LocalOrigin(bundle);
  in.x_gM = Pose::FromVector(ShiftedFrame(t.x_gM, to_local));
  in.camera = bundle.manifest.camera;
  in.model_axes = bundle.manifest.model_axes;
  const Pose x_s_cT = Pose::FromVector(t.x_s_cT);
  std::unordered_map<std::int64_t, int> keyframe_index;
  for (const auto& p : t.poses) {
    MappingKeyframe k;
    k.id = p.keyframe;
    k.x_g_cT = Pose::FromVector(ShiftedFrame(p.x_gv, to_local)) * bundle.manifest.VehicleToServo(p.servo) * x_s_cT;
    keyframe_index.emplace(k.id, static_cast<int>(in.keyframes.size()));
    in.keyframes.push_back(std::move(k));
  }
  std::unordered_map<std::int64_t, int> landmark_index;
  for (const auto& l : t.landmarks) {
    landmark_index.emplace(l.landmark, static_cast<int>(in.landmarks.size()));
    in.landmarks.push_back({l.landmark, l.p + to_local, l.deviation});
  }
  AttachObservations(bundle, keyframe_index, landmark_index, in);
  return in;
}

}  // namespace hull
