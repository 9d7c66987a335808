#include "ui/models/image_overlay.h"

#include <cmath>
#include <unordered_map>

#include "vision/camera_geometry.h"

namespace hull::ui {

namespace {

void Count(MatchVerdict v, int& inliers, int& outliers, int* unverified) {
  if (v == MatchVerdict::kInlier) {
    ++inliers;
  } else if (v == MatchVerdict::kOutlier || !unverified) {
    ++outliers;
  } else {
    ++*unverified;
  }
}

// Features and matches from the front end's record of the keyframe.
void FromFrontEnd(const FrontEndResult& fe, ImageOverlay& o) {
  const FrontEndKeyframe& k = fe.keyframes[static_cast<std::size_t>(o.index)];
  o.from_images = true;
  std::vector<char> bottom_tracked(k.bottom_points.size(), 0);
  for (const FrontEndStereoLink& l : k.stereo) {
    if (k.landmark[static_cast<std::size_t>(l.top)] >= 0) bottom_tracked[static_cast<std::size_t>(l.bottom)] = 1;
  }
  const auto& points = o.bottom ? k.bottom_points : k.top_points;
  const auto& sizes = o.bottom ? k.bottom_sizes : k.top_sizes;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool tracked = o.bottom ? bottom_tracked[i] != 0 : k.landmark[i] >= 0;
    o.features.push_back({points[i], sizes[i], tracked});
    o.tracked += tracked;
  }
  for (const FrontEndStereoLink& l : k.stereo) {
    const Eigen::Vector2d& top = k.top_points[static_cast<std::size_t>(l.top)];
    const Eigen::Vector2d& bottom = k.bottom_points[static_cast<std::size_t>(l.bottom)];
    o.stereo.push_back({o.bottom ? bottom : top, o.bottom ? top : bottom, l.verdict});
    Count(l.verdict, o.stereo_inliers, o.stereo_outliers, &o.stereo_unverified);
  }
  if (o.bottom) return;
  // The temporal pair with the nearest earlier keyframe.
  const FrontEndPair* best = nullptr;
  int best_from = -1;
  for (const FrontEndPair& p : fe.pairs) {
    if (p.to != o.keyframe) continue;
    const int from = fe.KeyframeIndex(p.from);
    if (from >= 0 && from < o.index && from > best_from) {
      best = &p;
      best_from = from;
    }
  }
  if (!best) return;
  o.previous_keyframe = best->from;
  o.previous_pair_accepted = best->accepted;
  const FrontEndKeyframe& prev = fe.keyframes[static_cast<std::size_t>(best_from)];
  for (const FrontEndMatch& m : best->matches) {
    const MatchVerdict v = m.inlier ? MatchVerdict::kInlier : MatchVerdict::kOutlier;
    o.temporal.push_back(
        {k.top_points[static_cast<std::size_t>(m.b)], prev.top_points[static_cast<std::size_t>(m.a)], v});
    Count(v, o.temporal_inliers, o.temporal_outliers, nullptr);
  }
}

}  // namespace

ImageOverlay ComputeImageOverlay(const SurveyBundle& bundle, const FrontEndResult* fe, const AdjustmentResult* adj,
                                 int index, bool bottom) {
  ImageOverlay o;
  if (index < 0 || index >= static_cast<int>(bundle.nav.size())) return o;
  o.index = index;
  o.keyframe = bundle.nav[static_cast<std::size_t>(index)].keyframe;
  o.bottom = bottom && bundle.manifest.camera.stereo();
  if (bundle.images && static_cast<std::size_t>(index) < bundle.images->frames.size()) {
    const KeyframeImages& f = bundle.images->frames[static_cast<std::size_t>(index)];
    o.has_image = !(o.bottom ? f.bottom : f.top).empty();
  }
  const bool use_front_end = fe && static_cast<std::size_t>(index) < fe->keyframes.size() &&
                             fe->keyframes[static_cast<std::size_t>(index)].keyframe == o.keyframe;
  // The observations of this keyframe (what the adjustment used).
  std::vector<const FeatureObservation*> observations;
  for (const FeatureObservation& f : bundle.features) {
    if (f.keyframe == o.keyframe && (!o.bottom || f.has_bottom)) observations.push_back(&f);
  }
  if (use_front_end) {
    FromFrontEnd(*fe, o);
  } else {
    for (const FeatureObservation* f : observations) o.features.push_back({o.bottom ? f->bottom : f->top, 0, true});
    o.tracked = static_cast<int>(o.features.size());
  }
  if (!adj) return o;

  // Reprojections: the adjusted landmark through the adjusted camera.
  int pose = -1;
  for (std::size_t j = 0; j < adj->keyframes.size(); ++j) {
    if (adj->keyframes[j] == o.keyframe) pose = static_cast<int>(j);
  }
  if (pose < 0) return o;
  std::unordered_map<std::int64_t, const LandmarkEstimate*> landmarks;
  for (const LandmarkEstimate& l : adj->landmarks) landmarks[l.id] = &l;
  const CameraRig& rig = bundle.manifest.camera;
  Pose x_g_c = Pose::FromVector(adj->poses[static_cast<std::size_t>(pose)]) *
               bundle.manifest.VehicleToServo(adj->servo[static_cast<std::size_t>(pose)]) *
               Pose::FromVector(adj->x_s_cT);
  if (o.bottom) x_g_c = x_g_c * Pose::FromVector(rig.top_to_bottom);
  const Pose x_c_g = x_g_c.Inverse();
  const Eigen::Matrix3d K = CameraMatrix(o.bottom ? rig.bottom : rig.top);
  double sum = 0;
  for (const FeatureObservation* f : observations) {
    const auto it = landmarks.find(f->landmark);
    if (it == landmarks.end()) continue;  // skipped or rejected by the adjustment
    const Eigen::Vector3d pc = x_c_g * it->second->p;
    if (pc.z() <= 1e-6) continue;
    const Eigen::Vector3d h = K * pc;
    OverlayReprojection r;
    r.landmark = f->landmark;
    r.observed = o.bottom ? f->bottom : f->top;
    r.projected = h.head<2>() / h.z();
    r.label = it->second->label;
    sum += (r.projected - r.observed).squaredNorm();
    o.reprojections.push_back(r);
  }
  if (!o.reprojections.empty()) o.rms_residual = std::sqrt(sum / static_cast<double>(o.reprojections.size()));
  return o;
}

}  // namespace hull::ui
