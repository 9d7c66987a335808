#include "ui/session/survey_overlays.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace hull::ui {

namespace {

// A unit tangent frame at a surface normal: e1 along the model x axis
// projected onto the tangent plane (as the simulator orients a box), e2 = n x e1.
void TangentFrame(const Eigen::Vector3d& n, Eigen::Vector3d* e1, Eigen::Vector3d* e2) {
  Eigen::Vector3d a = Eigen::Vector3d::UnitX() - n.dot(Eigen::Vector3d::UnitX()) * n;
  if (a.norm() < 1e-6) a = Eigen::Vector3d::UnitY() - n.dot(Eigen::Vector3d::UnitY()) * n;
  *e1 = a.normalized();
  *e2 = n.cross(*e1);
}

std::vector<Eigen::Vector3d> Circle(const Eigen::Vector3d& c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                                    double r, int n) {
  std::vector<Eigen::Vector3d> loop;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * M_PI * i / n;
    loop.push_back(c + r * (std::cos(phi) * e1 + std::sin(phi) * e2));
  }
  return loop;
}

std::vector<Eigen::Vector3d> Rectangle(const Eigen::Vector3d& c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                                       double a, double b) {
  return {c - a * e1 - b * e2, c + a * e1 - b * e2, c + a * e1 + b * e2, c - a * e1 + b * e2};
}

}  // namespace

Pose CameraPose(const SurveyManifest& manifest, const Vector6d& x_gv, double servo) {
  return Pose::FromVector(x_gv) * manifest.VehicleToServo(servo) * Pose::FromVector(manifest.camera.servo_to_top);
}

Pose DvlPose(const SurveyManifest& manifest, const Vector6d& x_gv, double servo) {
  return Pose::FromVector(x_gv) * manifest.VehicleToServo(servo) * Pose::FromVector(manifest.servo_to_dvl);
}

std::vector<DvlHit> ComputeDvlHits(const SurveyBundle& bundle, PoseSource source) {
  const auto nav_index = bundle.KeyframeIndex();
  std::unordered_map<std::int64_t, const TruePose*> truth;
  if (source == PoseSource::kTruth) {
    if (!bundle.truth) return {};
    for (const TruePose& p : bundle.truth->poses) truth[p.keyframe] = &p;
  }
  std::vector<DvlHit> hits;
  hits.reserve(bundle.dvl.size() * 4);
  for (const DvlRecord& d : bundle.dvl) {
    auto it = nav_index.find(d.keyframe);
    if (it == nav_index.end()) continue;
    Pose x_gd;
    if (source == PoseSource::kInitial) {
      const NavRecord& nav = bundle.nav[it->second];
      x_gd = DvlPose(bundle.manifest, nav.x_gv, nav.servo);
    } else {
      auto t = truth.find(d.keyframe);
      if (t == truth.end()) continue;
      x_gd = DvlPose(bundle.manifest, t->second->x_gv, t->second->servo);
    }
    for (int beam = 0; beam < 4; ++beam) {
      if (!DvlRecord::HasReturn(d.range[beam])) continue;
      DvlHit hit;
      hit.point = x_gd * (d.range[beam] * bundle.manifest.BeamDirection(beam));
      hit.nav_index = it->second;
      hit.beam = beam;
      hits.push_back(hit);
    }
  }
  return hits;
}

const char* LandmarkSourceName(LandmarkSource source) {
  switch (source) {
    case LandmarkSource::kNone:
      return "none";
    case LandmarkSource::kTruth:
      return "ground truth";
    case LandmarkSource::kInitial:
      return "initial (landmarks.csv)";
  }
  return "";
}

ObjectOutline OutlineOf(const TrueObject& o) {
  ObjectOutline out;
  out.id = o.id;
  out.kind = o.kind;
  out.center = o.center;
  const Eigen::Vector3d n = o.normal.normalized();
  Eigen::Vector3d e1, e2;
  TangentFrame(n, &e1, &e2);
  // The footprint is lifted 1 cm off the CAD surface so the hull does not hide it.
  const Eigen::Vector3d base = o.center + 0.01 * n;
  const Eigen::Vector3d top = o.center + o.Height() * n;
  switch (o.kind) {
    case ObjectKind::kCylinder: {
      out.loops.push_back(Circle(base, e1, e2, o.radius, 48));
      out.loops.push_back(Circle(top, e1, e2, o.radius, 48));
      for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d d = o.radius * (std::cos(i * M_PI / 2) * e1 + std::sin(i * M_PI / 2) * e2);
        out.segments.push_back({base + d, top + d});
      }
      break;
    }
    case ObjectKind::kBox: {
      const double a = 0.5 * o.size.x(), b = 0.5 * o.size.y();
      out.loops.push_back(Rectangle(base, e1, e2, a, b));
      out.loops.push_back(Rectangle(top, e1, e2, a, b));
      for (int i = 0; i < 4; ++i) out.segments.push_back({out.loops[0][i], out.loops[1][i]});
      break;
    }
    case ObjectKind::kPatch: {
      // An irregular bump within `radius`: its bounding circle and its height.
      out.loops.push_back(Circle(base, e1, e2, o.radius, 32));
      out.segments.push_back({base, top});
      break;
    }
  }
  return out;
}

std::vector<Frustum> ComputeFrusta(const SurveyBundle& bundle, int stride) {
  std::vector<Frustum> frusta;
  if (stride < 1) stride = 1;
  std::unordered_map<std::int64_t, double> standoff;
  for (const DvlRecord& d : bundle.dvl) {
    double sum = 0;
    int n = 0;
    for (int b = 0; b < 4; ++b) {
      if (!DvlRecord::HasReturn(d.range[b])) continue;
      sum += d.range[b] * bundle.manifest.BeamDirection(b).z();  // depth along the head's axis
      ++n;
    }
    if (n > 0) standoff[d.keyframe] = sum / n;
  }
  const CameraRig& cam = bundle.manifest.camera;
  const double w = cam.width - 0.5, h = cam.height - 0.5;
  const Eigen::Vector2d pixels[4] = {{-0.5, -0.5}, {w, -0.5}, {w, h}, {-0.5, h}};
  for (std::size_t i = 0; i < bundle.nav.size(); i += static_cast<std::size_t>(stride)) {
    const NavRecord& nav = bundle.nav[i];
    const Pose x_gc = CameraPose(bundle.manifest, nav.x_gv, nav.servo);
    auto range = standoff.find(nav.keyframe);
    const double depth = range == standoff.end() ? 1.0 : range->second;
    Frustum f;
    f.nav_index = static_cast<int>(i);
    f.apex = x_gc.translation();
    for (int k = 0; k < 4; ++k) f.corners[k] = x_gc * (depth * cam.top.Unproject(pixels[k]));
    frusta.push_back(f);
  }
  return frusta;
}

SurveyOverlays ComputeSurveyOverlays(const SurveyBundle& bundle) {
  SurveyOverlays out;
  for (const NavRecord& nav : bundle.nav) out.trajectory.push_back(nav.x_gv.head<3>());
  if (bundle.truth) {
    const auto nav_index = bundle.KeyframeIndex();
    for (const TruePose& p : bundle.truth->poses) {
      out.true_trajectory.push_back(p.x_gv.head<3>());
      auto it = nav_index.find(p.keyframe);
      out.true_nav_index.push_back(it == nav_index.end() ? -1 : it->second);
    }
  }
  out.dvl_hits = ComputeDvlHits(bundle, PoseSource::kInitial);

  std::unordered_map<std::int64_t, int> observations;
  for (const FeatureObservation& f : bundle.features) ++observations[f.landmark];
  auto count = [&](std::int64_t id) {
    auto it = observations.find(id);
    return it == observations.end() ? 0 : it->second;
  };
  if (bundle.truth && !bundle.truth->landmarks.empty()) {
    out.landmark_source = LandmarkSource::kTruth;
    for (const TrueLandmark& l : bundle.truth->landmarks) {
      LandmarkMarker m;
      m.id = l.landmark;
      m.position = l.p;
      m.has_truth = true;
      m.deviation = l.deviation;
      m.object = l.object;
      m.observations = count(l.landmark);
      out.landmarks.push_back(m);
    }
  } else if (bundle.landmarks) {
    out.landmark_source = LandmarkSource::kInitial;
    for (const LandmarkRecord& l : *bundle.landmarks) {
      LandmarkMarker m;
      m.id = l.landmark;
      m.position = l.p;
      m.observations = count(l.landmark);
      out.landmarks.push_back(m);
    }
  }
  if (bundle.truth) {
    for (const TrueObject& o : bundle.truth->objects) out.objects.push_back(OutlineOf(o));
  }

  for (const auto& p : out.trajectory) out.bounds.extend(p);
  for (const auto& p : out.true_trajectory) out.bounds.extend(p);
  for (const auto& h : out.dvl_hits) out.bounds.extend(h.point);
  bool first = true;
  for (const auto& l : out.landmarks) {
    out.bounds.extend(l.position);
    if (!l.has_truth) continue;
    out.min_deviation = first ? l.deviation : std::min(out.min_deviation, l.deviation);
    out.max_deviation = first ? l.deviation : std::max(out.max_deviation, l.deviation);
    first = false;
  }
  return out;
}

std::vector<ModelPlacement> AvailablePlacements(const SurveyBundle* bundle) {
  std::vector<ModelPlacement> out;
  if (bundle && bundle->truth) out.push_back(ModelPlacement::kTruth);
  if (bundle && bundle->manifest.model_pose_guess) out.push_back(ModelPlacement::kGuess);
  out.push_back(ModelPlacement::kIdentity);
  return out;
}

Pose PlacementPose(const SurveyBundle* bundle, ModelPlacement p) {
  if (bundle && p == ModelPlacement::kTruth && bundle->truth) return Pose::FromVector(bundle->truth->x_gM);
  if (bundle && p == ModelPlacement::kGuess && bundle->manifest.model_pose_guess) {
    return Pose::FromVector(*bundle->manifest.model_pose_guess);
  }
  return Pose::Identity();
}

}  // namespace hull::ui
