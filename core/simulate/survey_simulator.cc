#include "simulate/survey_simulator.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <unordered_map>

#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_index.h"
#include "geometry/mesh_io.h"
#include "geometry/point_index.h"
#include "simulate/foreign_objects.h"
#include "simulate/random.h"
#include "simulate/survey_imaging.h"
#include "simulate/true_scene.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"
#include "survey/survey_origin.h"

namespace hull {
namespace {
constexpr double kDeg = M_PI / 180.0;
}

void SurveySimulationOptions::Check() const {
  hull_form.Check();
  if (!(shift.allFinite() && shift.z() == 0 && shift.cwiseAbs().maxCoeff() <= 1e7)) {
    throw OptionError("shift", "must be finite, horizontal (z 0) and at most 1e7 m (the survey contract's bound)");
  }
  if (!shift.isZero() && images) {
    throw OptionError("shift", "is for surveys without images (the renderer is not checked at large coordinates)");
  }
  if (!(mesh_scale > 0)) throw OptionError("mesh_scale", "must be positive");
  if (forward.norm() < 1e-9 || up.norm() < 1e-9 || std::abs(forward.normalized().dot(up.normalized())) > 0.1) {
    throw OptionError("forward/up", "must be non-zero and perpendicular");
  }
  if (!(plan.standoff > 0.3 && plan.standoff < max_feature_range)) {
    throw OptionError("plan.standoff", "must be between 0.3 m and the feature range");
  }
  if (!(plan.keyframe_spacing > 0.01)) throw OptionError("plan.keyframe_spacing", "must be > 0.01 m");
  if (!(plan.track_spacing > 0.05)) throw OptionError("plan.track_spacing", "must be > 0.05 m");
  if (!(plan.speed > 0)) throw OptionError("plan.speed", "must be positive");
  if (!(plan.half_width >= 0)) throw OptionError("plan.half_width", "must be >= 0");
  if (plan.start >= 0 && plan.end >= 0 && !(plan.end > plan.start)) throw OptionError("plan.end", "must exceed start");
  if (!(noise.pixel_sigma > 0 && noise.dvl_range_sigma > 0 && noise.depth_sigma > 0 && noise.roll_pitch_sigma > 0 &&
        noise.servo_sigma > 0 && noise.odometry_translation_rate > 0 && noise.odometry_rotation_rate > 0)) {
    throw OptionError("noise", "every sigma and rate must be positive");
  }
  if (!(hull_feature_density >= 0 && object_feature_density >= 0)) {
    throw OptionError("feature_density", "must be >= 0");
  }
  if (!(non_salient_fraction >= 0 && non_salient_fraction < 1)) {
    throw OptionError("non_salient_fraction", "must be in [0, 1)");
  }
  if (!(detection_probability > 0 && detection_probability <= 1)) {
    throw OptionError("detection_probability", "must be in (0, 1]");
  }
  if (!(wrong_match_fraction >= 0 && wrong_match_fraction < 0.5)) {
    throw OptionError("wrong_match_fraction", "must be in [0, 0.5)");
  }
  if (!(dvl_max_range > 0)) throw OptionError("dvl_max_range", "must be positive");
  if (!(dvl_dropout >= 0 && dvl_dropout < 1)) throw OptionError("dvl_dropout", "must be in [0, 1)");
  if (!(max_feature_range > 0.5)) throw OptionError("max_feature_range", "must be > 0.5 m");
  if (scattered_patches < 0) throw OptionError("scattered_patches", "must be >= 0");
  if (images) imaging.Check();
  if (!(camera_scale >= 0.05 && camera_scale <= 4)) throw OptionError("camera_scale", "must be in [0.05, 4]");
  changes.Check();
}

std::vector<std::string> SurveyPresetNames() { return {"demo", "mono", "curtiss"}; }

SurveySimulationOptions SurveyPreset(const std::string& name) {
  SurveySimulationOptions o;
  o.plan.start = -1;  // the middle 12 m of the hull
  o.plan.end = -1;
  if (name == "demo") {
    o.name = "Demo: a stretch of hull bottom around the keel (stereo)";
  } else if (name == "mono") {
    o.name = "Demo: a stretch of hull bottom around the keel (monocular)";
    o.camera = CameraType::kMono;
  } else if (name == "curtiss") {
    o.name = "SS Curtiss-size hull: full bottom and sides (stereo)";
    o.plan.coverage = SurveyCoverage::kFullHull;
    o.plan.start = 10.0;
    o.plan.end = 173.0;
    o.plan.half_width = 11.0;
    o.plan.track_spacing = 1.2;
    o.plan.keyframe_spacing = 0.45;
    o.objects = ObjectSet::kScattered;
    o.scattered_patches = 40;
    o.nav_source = SurveySimulationOptions::NavSource::kOnlineSlam;  // five hours of survey
  } else {
    throw OptionError("preset", "unknown preset '" + name + "' (known: demo, mono, curtiss)");
  }
  return o;
}

namespace {

struct Landmark {
  Eigen::Vector3d p_m;  // in M
  Eigen::Vector3d n_m;  // outward normal of the true surface there
  double deviation;
  int object;  // -1: hull
};

struct Observation {
  int landmark;
  Eigen::Vector2d top, bottom;
  bool wrong;
};

// A smooth random field over the hull: where it is low, the hull has no
// salient texture (no features).
struct SaliencyField {
  Eigen::Vector3d w[4];
  double ph[4];
  explicit SaliencyField(Rng& rng) {
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector3d d(rng.Gaussian(), rng.Gaussian(), rng.Gaussian());
      w[k] = d.normalized() * (2 * M_PI / rng.Uniform(3.0, 8.0));
      ph[k] = rng.Uniform(0, 2 * M_PI);
    }
  }
  double operator()(const Eigen::Vector3d& p) const {
    double s = 0;
    for (int k = 0; k < 4; ++k) s += std::sin(w[k].dot(p) + ph[k]);
    return s;
  }
};

Eigen::Vector3d SamplePointOnFace(const TriangleMesh& m, int f, Rng& rng) {
  double a = rng.Uniform(), b = rng.Uniform();
  if (a + b > 1) {
    a = 1 - a;
    b = 1 - b;
  }
  const auto& F = m.faces[static_cast<std::size_t>(f)];
  return m.vertices[F[0]] + a * (m.vertices[F[1]] - m.vertices[F[0]]) + b * (m.vertices[F[2]] - m.vertices[F[0]]);
}

int PoissonCount(double mean, Rng& rng) {
  if (mean > 50) return std::max(0, static_cast<int>(std::lround(mean + std::sqrt(mean) * rng.Gaussian())));
  const double L = std::exp(-mean);
  int k = 0;
  double p = 1;
  do {
    ++k;
    p *= rng.Uniform();
  } while (p > L);
  return k - 1;
}

Pose SmallRandomPose(Rng& rng, double metres, double degrees) {
  Eigen::Vector3d t(rng.Gaussian(), rng.Gaussian(), rng.Gaussian());
  Eigen::Vector3d a(rng.Gaussian(), rng.Gaussian(), rng.Gaussian());
  t = t.normalized() * metres * rng.Uniform(0.8, 1.2);
  const double angle = degrees * kDeg * rng.Uniform(0.8, 1.2);
  return Pose(Eigen::Quaterniond(Eigen::AngleAxisd(angle, a.normalized())), t);
}

std::vector<TrueObject> PlaceObjects(const SurveySimulationOptions& o, const MeshIndex& cad, const HullAxes& axes,
                                     double fmin, double umin, double s_centre,
                                     const std::vector<PlannedKeyframe>& keys, const Pose& x_gM,
                                     const SurveyManifest& rig, const Pose& x_s_cT, Rng& rng) {
  std::vector<TrueObject> objs;
  if (o.objects == ObjectSet::kNone) return objs;
  const Eigen::Vector3d f = axes.forward.normalized(), u = axes.up.normalized(), p = u.cross(f).normalized();
  auto bottom = [&](double s, double y) { return Eigen::Vector3d((fmin + s) * f + y * p + umin * u); };
  const double c = s_centre;
  for (auto& s : PlacePatchStrip(cad, "strip", bottom(c - 4.0, 0.0), bottom(c - 1.0, 0.0), 0.12, 0.20, 0.06, 0.18,
                                 o.seed * 31 + 7)) {
    objs.push_back(std::move(s));
  }
  objs.push_back(PlaceObject(cad, "cyl-1", ObjectKind::kCylinder, bottom(c + 2.0, 1.0), 0.15, 0.11));
  objs.push_back(
      PlaceObject(cad, "box-1", ObjectKind::kBox, bottom(c + 3.5, -1.2), 0, 0, Eigen::Vector3d(0.40, 0.25, 0.08)));
  objs.push_back(PlaceObject(cad, "patch-1", ObjectKind::kPatch, bottom(c + 0.5, -1.0), 0.18, 0.15));
  objs.push_back(PlaceObject(cad, "patch-2", ObjectKind::kPatch, bottom(c - 2.0, 1.6), 0.12, 0.07));
  objs.push_back(PlaceObject(cad, "patch-3", ObjectKind::kPatch, bottom(c + 4.5, 0.6), 0.10, 0.06));
  if (o.objects == ObjectSet::kScattered && !keys.empty()) {
    const Pose Mg = x_gM.Inverse();
    for (int i = 0; i < o.scattered_patches; ++i) {
      // Where a random keyframe's camera looks, shifted a little.
      const PlannedKeyframe& k = keys[rng.Index(keys.size())];
      const Pose cam = Mg * k.x_gv * VehicleToCamera(rig, x_s_cT, k.servo);
      const Eigen::Vector3d dir = cam.Rotate(Eigen::Vector3d(rng.Uniform(-0.3, 0.3), rng.Uniform(-0.2, 0.2), 1.0));
      const RayHit hit = cad.Raycast(cam.translation(), dir, 10.0);
      if (!hit.hit) continue;
      objs.push_back(PlaceObject(cad, "patch-" + std::to_string(4 + i), ObjectKind::kPatch, hit.point,
                                 rng.Uniform(0.10, 0.25), rng.Uniform(0.06, 0.18)));
    }
  }
  return objs;
}

// The CAD hull in M and where the survey goes along it.
struct HullFrame {
  HullAxes axes;
  double fmin = 1e300, fmax = -1e300, umin = 1e300;  // extent along forward; lowest point along up
};

// The parametric hull or the given mesh (its waterline at 60 % of its height
// unless given), and its extent along the hull's axes.
HullFrame LoadHull(const SurveySimulationOptions& o, TriangleMesh* cad) {
  HullFrame h;
  h.axes.forward = o.forward.normalized();
  h.axes.up = o.up.normalized();
  if (o.mesh_path.empty()) {
    *cad = MakeParametricHull(o.hull_form);
    h.axes.waterline = o.waterline >= 0 ? o.waterline : o.hull_form.draft;
  } else {
    MeshLoadOptions lo;
    lo.scale = o.mesh_scale;
    *cad = LoadMesh(o.mesh_path, lo);
    double umin = 1e300, umax = -1e300;
    for (const auto& v : cad->vertices) {
      umin = std::min(umin, v.dot(h.axes.up));
      umax = std::max(umax, v.dot(h.axes.up));
    }
    h.axes.waterline = o.waterline >= 0 ? o.waterline : umin + 0.6 * (umax - umin);
  }
  for (const auto& v : cad->vertices) {
    h.fmin = std::min(h.fmin, v.dot(h.axes.forward));
    h.fmax = std::max(h.fmax, v.dot(h.axes.forward));
    h.umin = std::min(h.umin, v.dot(h.axes.up));
  }
  return h;
}

// The survey's manifest (rig, noise, axes) and the rig's true extrinsic:
// nominal plus an error whose translation lies mostly along the camera's
// optical axis (z).
Pose DescribeRig(const SurveySimulationOptions& o, const HullAxes& axes, SurveyManifest* man, Rng& rng) {
  man->name = o.name;
  man->vehicle = "HAUV";
  man->model_hint = "hull.ply";
  man->camera.type = o.camera;
  if (o.camera_scale != 1.0) ScaleCamera(man->camera, o.camera_scale);
  if (o.camera == CameraType::kMono) man->camera.top_to_bottom.setZero();
  man->noise = o.noise;
  man->model_axes = ModelAxes{axes.forward, axes.up};
  const Pose e = SmallRandomPose(rng, o.extrinsic_error_m * 0.35, o.extrinsic_error_deg);
  const Eigen::Vector3d t = e.translation() + Eigen::Vector3d(0, 0, rng.Sign() * o.extrinsic_error_m * 0.9);
  return Pose::FromVector(man->camera.servo_to_top) * Pose(e.quaternion(), t);
}

// Landmarks on the true surface within feature range of a camera: Poisson
// per face at the hull's or the objects' feature density; object points
// only where they stand off the CAD, hull points only where the saliency
// field is above its non_salient_fraction quantile.
std::vector<Landmark> SampleLandmarks(const SurveySimulationOptions& o, const TriangleMesh& surface,
                                      const std::vector<int>& face_object, const MeshIndex& cad, const PointIndex& cams,
                                      Rng& rng) {
  std::vector<Landmark> lms;
  const SaliencyField field(rng);
  std::vector<Landmark> hull_candidates;
  for (int f = 0; f < static_cast<int>(surface.num_faces()); ++f) {
    const int obj = face_object[static_cast<std::size_t>(f)];
    const auto& F = surface.faces[static_cast<std::size_t>(f)];
    double reach = 0;
    const Eigen::Vector3d c = surface.FaceCentroid(f);
    for (int k = 0; k < 3; ++k) reach = std::max(reach, (surface.vertices[F[k]] - c).norm());
    if (cams.Nearest(c, 1).front().second > std::pow(o.max_feature_range + reach, 2)) continue;
    const double density = obj < 0 ? o.hull_feature_density : o.object_feature_density;
    const int n = PoissonCount(density * surface.FaceArea(f), rng);
    for (int i = 0; i < n; ++i) {
      Landmark l{SamplePointOnFace(surface, f, rng), surface.face_normals[static_cast<std::size_t>(f)], 0.0, obj};
      if (obj < 0) {
        hull_candidates.push_back(l);
      } else {
        l.deviation = cad.SignedDistance(l.p_m);
        if (l.deviation > 0.003) lms.push_back(l);
      }
    }
  }
  if (!hull_candidates.empty()) {
    std::vector<double> values;
    for (const auto& l : hull_candidates) values.push_back(field(l.p_m));
    std::vector<double> sorted = values;
    const std::size_t q = static_cast<std::size_t>(o.non_salient_fraction * (sorted.size() - 1));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(q), sorted.end());
    const double threshold = o.non_salient_fraction > 0 ? sorted[q] : -1e300;
    for (std::size_t i = 0; i < hull_candidates.size(); ++i) {
      if (values[i] > threshold) lms.push_back(hull_candidates[i]);
    }
  }
  return lms;
}

// What the sensors of every keyframe measure.
struct KeyframeMeasurements {
  std::vector<std::vector<Observation>> obs;  // per keyframe
  std::vector<std::array<double, 4>> dvl;     // per keyframe: beam ranges (kNoReturn)
  std::vector<std::array<bool, 4>> dropped;   // per keyframe: beams that dropped out
};

// The scene every keyframe measures: the true surface, the landmarks (in M
// and in g, indexed) and the rig.
struct MeasuredScene {
  const SurveySimulationOptions& o;
  const SurveyManifest& man;
  const Pose& x_s_cT;
  const Pose& x_Mg;
  const MeshIndex& cad;
  const MeshIndex& truth_surface;
  const std::vector<int>& face_object;
  const std::vector<Landmark>& lms;
  const std::vector<Eigen::Vector3d>& lm_g;
  const PointIndex& lm_index;
};

// The camera features keyframe k sees: in both images of a stereo rig,
// unoccluded, near and frontal enough, detected; pixel noise; on a mono rig
// a share of wrong matches.
std::vector<Observation> ObserveFeatures(const MeasuredScene& s, const PlannedKeyframe& key, Rng& r) {
  const SurveySimulationOptions& o = s.o;
  const CameraRig& camrig = s.man.camera;
  const bool stereo = o.camera == CameraType::kStereo;
  const double m = o.image_margin;
  auto inside = [&](const Eigen::Vector2d& uv) {
    return uv.x() >= m && uv.y() >= m && uv.x() <= camrig.width - 1 - m && uv.y() <= camrig.height - 1 - m;
  };
  const Pose g_cT = key.x_gv * VehicleToCamera(s.man, s.x_s_cT, key.servo);
  const Pose g_cB = g_cT * Pose::FromVector(camrig.top_to_bottom);
  const Pose cT_g = g_cT.Inverse(), cB_g = g_cB.Inverse();
  const Eigen::Vector3d cT_m = s.x_Mg * g_cT.translation(), cB_m = s.x_Mg * g_cB.translation();
  auto visible = [&](const Eigen::Vector3d& cam_m, const Landmark& l) {
    const Eigen::Vector3d d = l.p_m - cam_m;
    const double dist = d.norm();
    if (dist > o.max_feature_range) return false;
    if (l.n_m.dot(-d / dist) < o.min_view_cosine) return false;
    return !s.truth_surface.Raycast(cam_m, d / dist, dist - 1e-3).hit;
  };
  std::vector<Observation> obs;
  for (const auto& [li, d2] : s.lm_index.Within(g_cT.translation(), o.max_feature_range)) {
    (void)d2;
    const Landmark& l = s.lms[static_cast<std::size_t>(li)];
    const Eigen::Vector3d pt = cT_g * s.lm_g[static_cast<std::size_t>(li)];
    if (pt.z() < 0.1) continue;
    const Eigen::Vector2d uvT = camrig.top.Project(pt);
    if (!inside(uvT)) continue;
    Eigen::Vector2d uvB = Eigen::Vector2d::Zero();
    if (stereo) {
      const Eigen::Vector3d pb = cB_g * s.lm_g[static_cast<std::size_t>(li)];
      if (pb.z() < 0.1) continue;
      uvB = camrig.bottom.Project(pb);
      if (!inside(uvB)) continue;
    }
    if (!visible(cT_m, l) || (stereo && !visible(cB_m, l))) continue;
    if (!r.Bernoulli(o.detection_probability)) continue;
    Observation ob{li, uvT, uvB, false};
    const double sigma = o.noise.pixel_sigma;
    ob.top += Eigen::Vector2d(r.TruncatedGaussian(sigma, 3.5), r.TruncatedGaussian(sigma, 3.5));
    if (stereo) ob.bottom += Eigen::Vector2d(r.TruncatedGaussian(sigma, 3.5), r.TruncatedGaussian(sigma, 3.5));
    if (!stereo && r.Bernoulli(o.wrong_match_fraction)) {
      // A wrong match: the descriptor matched another spot of the image.
      Eigen::Vector2d w;
      do {
        w = {r.Uniform(m, camrig.width - 1 - m), r.Uniform(m, camrig.height - 1 - m)};
      } while ((w - uvT).norm() < 40.0);
      ob.top = w;
      ob.wrong = true;
    }
    obs.push_back(ob);
  }
  return obs;
}

// The DVL's four Janus beams of keyframe k cast against the true surface:
// ranges with noise, drop-outs, and no return beyond dvl_max_range.
void MeasureDvl(const MeasuredScene& s, const PlannedKeyframe& key, Rng& r, std::array<double, 4>* range,
                std::array<bool, 4>* dropped) {
  const SurveySimulationOptions& o = s.o;
  const Pose g_d = key.x_gv * s.man.VehicleToServo(key.servo) * Pose::FromVector(s.man.servo_to_dvl);
  const Eigen::Vector3d o_m = s.x_Mg * g_d.translation();
  for (int b = 0; b < 4; ++b) {
    const Eigen::Vector3d dir = s.x_Mg.Rotate(g_d.Rotate(s.man.BeamDirection(b)));
    const RayHit hit = s.truth_surface.Raycast(o_m, dir, o.dvl_max_range);
    double rb = kNoReturn;
    bool drop = false;
    if (hit.hit) {
      // A return off foreign structure where the beam would miss the hull
      // altogether (a patch grazed at the hull's silhouette) is one a DVL's
      // bottom track rejects: treat it as a drop-out.
      const bool grazing =
          s.face_object[static_cast<std::size_t>(hit.face)] >= 0 && !s.cad.Raycast(o_m, dir, o.dvl_max_range).hit;
      if (grazing || r.Bernoulli(o.dvl_dropout)) {
        drop = true;
      } else {
        rb = hit.range + r.TruncatedGaussian(o.noise.dvl_range_sigma, 4.0);
      }
    }
    (*range)[static_cast<std::size_t>(b)] = rb;
    (*dropped)[static_cast<std::size_t>(b)] = drop;
  }
}

// Every keyframe's features and DVL, in parallel and deterministic (a random
// stream per keyframe).
KeyframeMeasurements MeasureKeyframes(const MeasuredScene& s, const std::vector<PlannedKeyframe>& keys,
                                      Progress& progress) {
  const int K = static_cast<int>(keys.size());
  KeyframeMeasurements out;
  out.obs.resize(static_cast<std::size_t>(K));
  out.dvl.resize(static_cast<std::size_t>(K));
  out.dropped.resize(static_cast<std::size_t>(K));
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  tbb::parallel_for(0, K, [&](int k) {
    if (progress.Cancelled()) return;
    Rng r = Rng::ForItem(s.o.seed, 1, static_cast<std::uint64_t>(k));
    const auto ki = static_cast<std::size_t>(k);
    out.obs[ki] = ObserveFeatures(s, keys[ki], r);
    MeasureDvl(s, keys[ki], r, &out.dvl[ki], &out.dropped[ki]);
    const int n = ++done;
    if (n % 64 == 0) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress.Update(0.15 + 0.75 * n / K, "simulating keyframe " + std::to_string(n) + " of " + std::to_string(K));
    }
  });
  return out;
}

// The landmarks seen (correctly) in at least two keyframes, numbered from 0
// in order, become the bundle's tracks and the truth's landmarks.
void KeepTrackedLandmarks(const SurveySimulationOptions& o, const std::vector<Landmark>& lms,
                          const std::vector<Eigen::Vector3d>& lm_g, const KeyframeMeasurements& meas,
                          SimulatedSurvey* out, SurveyTruth* truth) {
  std::vector<int> views(lms.size(), 0);
  for (const auto& list : meas.obs) {
    for (const auto& ob : list) {
      if (!ob.wrong) ++views[static_cast<std::size_t>(ob.landmark)];
    }
  }
  std::vector<std::int64_t> new_id(lms.size(), -1);
  std::int64_t next = 0;
  for (std::size_t i = 0; i < lms.size(); ++i) {
    if (views[i] >= 2) new_id[i] = next++;
  }
  for (std::size_t i = 0; i < lms.size(); ++i) {
    if (new_id[i] < 0) continue;
    TrueLandmark t;
    t.landmark = new_id[i];
    t.p = lm_g[i];
    t.deviation = lms[i].object < 0 ? 0.0 : lms[i].deviation;
    t.object = lms[i].object < 0 ? "" : truth->objects[static_cast<std::size_t>(lms[i].object)].id;
    truth->landmarks.push_back(t);
  }
  const bool stereo = o.camera == CameraType::kStereo;
  for (std::size_t k = 0; k < meas.obs.size(); ++k) {
    for (const auto& ob : meas.obs[k]) {
      const std::int64_t id = new_id[static_cast<std::size_t>(ob.landmark)];
      if (id < 0) continue;
      FeatureObservation f;
      f.keyframe = static_cast<std::int64_t>(k);
      f.landmark = id;
      f.top = ob.top;
      f.bottom = ob.bottom;
      f.has_bottom = stereo;
      out->bundle.features.push_back(f);
      if (ob.wrong) out->wrong_matches.emplace_back(static_cast<std::int64_t>(k), id);
    }
  }
}

// Navigation per keyframe: the truth, odometry with noise, the navigation
// solution (dead reckoning from that odometry, or an online SLAM's
// first-order Gauss-Markov error), depth, roll, pitch, the servo angle with
// its bias, and the DVL's ranges.
void SimulateNavigation(const SurveySimulationOptions& o, const std::vector<PlannedKeyframe>& keys,
                        const KeyframeMeasurements& meas, Rng& rng, SimulatedSurvey* out, SurveyTruth* truth) {
  SurveyBundle& b = out->bundle;
  const NoiseModel& nz = o.noise;
  const int K = static_cast<int>(keys.size());
  const double servo_bias = rng.Sign() * o.servo_bias_deg * kDeg * rng.Uniform(0.8, 1.2);
  Vector6d dr = (keys[0].x_gv * SmallRandomPose(rng, o.start_pose_error_m, o.start_pose_error_deg)).ToVector();
  Vector6d slam_err = Vector6d::Zero();
  for (int k = 0; k < K; ++k) {
    const PlannedKeyframe& key = keys[static_cast<std::size_t>(k)];
    Rng r = Rng::ForItem(o.seed, 2, static_cast<std::uint64_t>(k));
    const Vector6d xt = key.x_gv.ToVector();
    truth->poses.push_back({k, xt, key.servo});
    if (k > 0) {
      const PlannedKeyframe& prev = keys[static_cast<std::size_t>(k - 1)];
      const double dt = key.t - prev.t;
      Vector6d z = (prev.x_gv.Inverse() * key.x_gv).ToVector();
      for (int i = 0; i < 3; ++i) z[i] += r.TruncatedGaussian(nz.odometry_translation_rate * dt, 4.0);
      for (int i = 3; i < 6; ++i) z[i] = WrapAngle(z[i] + r.TruncatedGaussian(nz.odometry_rotation_rate * dt, 4.0));
      b.odometry.push_back({k - 1, k, z});
      dr = Oplus(dr, z);
    }
    NavRecord n;
    n.keyframe = k;
    n.t = key.t;
    if (o.nav_source == SurveySimulationOptions::NavSource::kDeadReckoning) {
      n.x_gv = dr;
    } else {
      // A first-order Gauss-Markov error per component, stationary std = slam_error.
      const double dt = k > 0 ? key.t - keys[static_cast<std::size_t>(k - 1)].t : 0.0;
      const double a = std::exp(-dt / o.slam_correlation_s), bb = std::sqrt(1 - a * a);
      for (int i = 0; i < 6; ++i) {
        // (depth: the pressure sensor keeps the SLAM depth closer)
        const double sigma = i < 3 ? o.slam_error_m * (i == 2 ? 0.3 : 1.0) : o.slam_error_deg * kDeg;
        slam_err[i] = k == 0 ? r.Gaussian(sigma) : a * slam_err[i] + bb * r.Gaussian(sigma);
      }
      n.x_gv = (key.x_gv * Pose::FromVector(slam_err)).ToVector();
    }
    n.depth = xt[2] + r.TruncatedGaussian(nz.depth_sigma, 4.0);
    n.roll_meas = WrapAngle(xt[3] + r.TruncatedGaussian(nz.roll_pitch_sigma, 4.0));
    n.pitch_meas = xt[4] + r.TruncatedGaussian(nz.roll_pitch_sigma, 4.0);
    n.servo = key.servo + servo_bias + r.TruncatedGaussian(o.servo_noise_deg * kDeg, 4.0);
    b.nav.push_back(n);
    DvlRecord d;
    d.keyframe = k;
    d.range = meas.dvl[static_cast<std::size_t>(k)];
    b.dvl.push_back(d);
    for (int bm = 0; bm < 4; ++bm) {
      if (meas.dropped[static_cast<std::size_t>(k)][static_cast<std::size_t>(bm)]) {
        out->dvl_dropouts.emplace_back(k, bm + 1);
      }
    }
  }
}

// A wrong model-pose guess: the true x_gM rotated about the surveyed region
// (the landmarks' centroid in M).
Vector6d GuessModelPose(const SurveySimulationOptions& o, const SurveyTruth& truth, const Pose& x_gM, Rng& rng) {
  const Pose x_Mg = x_gM.Inverse();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& t : truth.landmarks) c += x_Mg * t.p;
  if (!truth.landmarks.empty()) c /= static_cast<double>(truth.landmarks.size());
  const Pose d = SmallRandomPose(rng, o.model_pose_error_m, o.model_pose_error_deg);
  const Pose about(d.quaternion(), c - d.Rotate(c) + d.translation());
  return (x_gM * about).ToVector();
}

// Version 2: which images exist (a few frames may be dropped); the pixels are
// rendered when the bundle is written.
SurveyImages ListImages(const SurveySimulationOptions& o, int K) {
  const bool stereo = o.camera == CameraType::kStereo;
  SurveyImages listing;
  for (int k = 0; k < K; ++k) {
    Rng r = Rng::ForItem(o.seed, 3, static_cast<std::uint64_t>(k));
    KeyframeImages f;
    f.keyframe = k;
    for (bool bottom : {false, true}) {
      if (bottom && !stereo) continue;
      ++listing.expected;
      if (r.Bernoulli(o.imaging.image_dropout)) {
        ++listing.dropped;
        continue;
      }
      (bottom ? f.bottom : f.top) = "images/" + SurveyImageName(k, bottom);
    }
    listing.frames.push_back(f);
  }
  return listing;
}

}  // namespace

SimulatedSurvey SimulateSurvey(const SurveySimulationOptions& o, Progress& progress) {
  o.Check();
  Rng rng(o.seed);
  SimulatedSurvey out;
  progress.Update(0.0, "building the hull");
  const HullFrame hull = LoadHull(o, &out.cad);
  const MeshIndex cad(out.cad);
  LawnmowerOptions plan = o.plan;
  if (plan.start < 0 || plan.end < 0) {  // the middle 12 m
    const double mid = 0.5 * (hull.fmax - hull.fmin);
    plan.start = mid - 6.0;
    plan.end = mid + 6.0;
  }
  const double s_centre = 0.5 * (plan.start + plan.end);
  const Eigen::Vector3d centre_m = (hull.fmin + s_centre) * hull.axes.forward + hull.umin * hull.axes.up;
  const Pose x_gM = ShipPlacement(hull.axes, centre_m, o.heading_deg * kDeg);
  SurveyManifest& man = out.bundle.manifest;
  const Pose x_s_cT = DescribeRig(o, hull.axes, &man, rng);

  progress.Update(0.05, "planning the survey");
  const std::vector<PlannedKeyframe> keys = PlanLawnmower(cad, hull.axes, x_gM, man, x_s_cT, plan, rng);
  if (keys.size() < 3) throw OptionError("plan", "the survey region holds fewer than 3 keyframes on this hull");
  progress.ThrowIfCancelled();

  // Foreign objects and the true surface.
  SurveyTruth truth;
  truth.x_gM = x_gM.ToVector();
  truth.x_s_cT = x_s_cT.ToVector();
  truth.objects = PlaceObjects(o, cad, hull.axes, hull.fmin, hull.umin, s_centre, keys, x_gM, man, x_s_cT, rng);
  std::vector<std::size_t> seed_index(truth.objects.size());
  for (std::size_t i = 0; i < seed_index.size(); ++i) seed_index[i] = i;
  if (o.changes.any()) seed_index = ApplyFoulingChanges(truth.objects, cad, hull.axes.forward, o.changes);
  for (std::size_t i = 0; i < truth.objects.size(); ++i) {
    out.object_meshes.push_back(MakeObjectMesh(truth.objects[i], o.seed * 1000003 + seed_index[i]));
  }
  std::vector<int> face_object;
  const TriangleMesh surface = TrueSurfaceMesh(out.cad, out.object_meshes, &face_object);
  const MeshIndex truth_surface(surface);
  progress.Update(0.1, "sampling features");

  const Pose x_Mg = x_gM.Inverse();
  std::vector<Eigen::Vector3d> cam_m;
  for (const auto& k : keys) cam_m.push_back(x_Mg * (k.x_gv * VehicleToCamera(man, x_s_cT, k.servo)).translation());
  const std::vector<Landmark> lms = SampleLandmarks(o, surface, face_object, cad, PointIndex(cam_m), rng);
  std::vector<Eigen::Vector3d> lm_g;
  lm_g.reserve(lms.size());
  for (const auto& l : lms) lm_g.push_back(x_gM * l.p_m);
  const PointIndex lm_index(lm_g);
  progress.ThrowIfCancelled();

  const MeasuredScene scene{o, man, x_s_cT, x_Mg, cad, truth_surface, face_object, lms, lm_g, lm_index};
  const KeyframeMeasurements meas = MeasureKeyframes(scene, keys, progress);
  progress.ThrowIfCancelled();
  progress.Update(0.9, "assembling the bundle");
  KeepTrackedLandmarks(o, lms, lm_g, meas, &out, &truth);
  SimulateNavigation(o, keys, meas, rng, &out, &truth);
  man.model_pose_guess = GuessModelPose(o, truth, x_gM, rng);

  SurveyBundle& b = out.bundle;
  if (o.write_landmarks) {
    std::vector<LandmarkRecord> init;
    Rng r(o.seed ^ 0xABCDEF);
    for (const auto& t : truth.landmarks) {
      init.push_back({t.landmark, t.p + Eigen::Vector3d(r.Gaussian(0.05), r.Gaussian(0.05), r.Gaussian(0.05))});
    }
    b.landmarks = std::move(init);
  }
  b.truth = std::move(truth);
  out.albedo_seed = o.seed & ((std::uint64_t{1} << 52) - 1);  // exact in truth/albedo.json
  if (o.images) {
    man.version = 2;
    man.imaging = ImagingNote{std::nullopt, std::string("strobe")};
    b.images = ListImages(o, static_cast<int>(keys.size()));
    out.imaging = o.imaging;
  }
  if (!o.shift.isZero()) ShiftSurvey(b, o.shift);
  progress.Update(1.0, "simulated " + std::to_string(keys.size()) + " keyframes, " + std::to_string(b.features.size()) +
                           " observations of " + std::to_string(b.truth->landmarks.size()) + " landmarks");
  return out;
}

void WriteSimulatedSurvey(const SimulatedSurvey& s, const std::string& dir, bool generator_extras) {
  NullProgress progress;
  WriteSimulatedSurvey(s, dir, generator_extras, progress);
}

void WriteSimulatedSurvey(const SimulatedSurvey& s, const std::string& dir, bool generator_extras, Progress& progress) {
  namespace fs = std::filesystem;
  WriteSurveyBundle(s.bundle, dir);
  MeshSaveOptions mo;
  mo.binary = true;
  mo.double_precision = true;
  SaveMesh(s.cad, (fs::path(dir) / s.bundle.manifest.model_hint.value_or("hull.ply")).string(), mo);
  if (s.imaging) WriteSurveyImages(s, dir, progress);
  if (!generator_extras) return;
  std::string gdir = dir;
  while (!gdir.empty() && gdir.back() == '/') gdir.pop_back();
  gdir += ".gen";
  fs::create_directories(gdir);
  Json gen = Json::Object();
  gen.Set("generator", "hullinspect-cli simulate");
  gen.Set("keyframes", static_cast<std::int64_t>(s.bundle.nav.size()));
  WriteFileAtomic((fs::path(gdir) / "generator.json").string(), gen.Dump());
  Json objs = Json::Array();
  for (std::size_t i = 0; i < s.object_meshes.size(); ++i) {
    Json tris = Json::Array();
    const TriangleMesh& m = s.object_meshes[i];
    for (const auto& F : m.faces) {
      Json tri = Json::Array();
      for (int k = 0; k < 3; ++k) {
        const auto& v = m.vertices[F[static_cast<std::size_t>(k)]];
        tri.Push(Json::ArrayOf(std::vector<double>{v.x(), v.y(), v.z()}));
      }
      tris.Push(tri);
    }
    Json o = Json::Object();
    o.Set("id", s.bundle.truth->objects[i].id);
    o.Set("triangles", tris);
    objs.Push(o);
  }
  Json om = Json::Object();
  om.Set("objects", objs);
  WriteFileAtomic((fs::path(gdir) / "objects_mesh.json").string(), om.Dump(0));
  CsvWriter wm({"keyframe", "landmark"});
  for (const auto& [k, l] : s.wrong_matches) {
    wm.Add(k).Add(l);
    wm.EndRow();
  }
  WriteFileAtomic((fs::path(gdir) / "wrong_matches.csv").string(), wm.text());
  CsvWriter dd({"keyframe", "beam"});
  for (const auto& [k, bm] : s.dvl_dropouts) {
    dd.Add(k).Add(bm);
    dd.EndRow();
  }
  WriteFileAtomic((fs::path(gdir) / "dvl_dropouts.csv").string(), dd.text());
}

}  // namespace hull
