// Loop closures of the visual front end on a rendered survey with truth
// (hullinspect-cli simulate --preset demo --images ...): the front end with
// and without loop closures, the loop pairs tried and accepted (by survey
// leg: a leg is a run of keyframes moving the same way), the precision of
// their RANSAC inliers against the true surface (truth/scene.ply, the true
// camera poses), the track lengths before and after, the share of tracked
// observations whose true surface point lies within 2 cm of their track's,
// and the time the loops add.
//   bench_loops BUNDLE [threads=2] [--determinism]
// --determinism also runs the front end on one thread and compares.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "simulate/image_track_truth.h"
#include "simulate/true_scene.h"
#include "support/bench_clock.h"
#include "survey/survey_io.h"
#include "vision/camera_geometry.h"
#include "vision/front_end.h"

namespace hull {
namespace {

double Now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct Truth {
  std::vector<Pose> x_g_c;  // true top camera pose per nav index
  std::vector<int> leg;     // survey leg per nav index
  Pose x_Mg;
  const TrueScene* scene = nullptr;
  Eigen::Matrix3d K;

  // The true surface point (in g) seen at top pixel uv of keyframe k.
  std::optional<Eigen::Vector3d> Surface(std::size_t k, const Eigen::Vector2d& uv) const {
    const Pose x_M_c = x_Mg * x_g_c[k];
    const Eigen::Vector3d d = x_M_c.Rotate(K.inverse() * uv.homogeneous()).normalized();
    const RayHit h = scene->index().Raycast(x_M_c.translation(), d, 20.0);
    if (!h.hit) return std::nullopt;
    return x_Mg.Inverse() * h.point;
  }
  // Its pixel in keyframe j (nothing when behind the camera).
  std::optional<Eigen::Vector2d> Transfer(std::size_t k, const Eigen::Vector2d& uv, std::size_t j) const {
    const auto p = Surface(k, uv);
    if (!p) return std::nullopt;
    const Eigen::Vector3d q = x_g_c[j].Inverse() * *p;
    if (q.z() <= 0) return std::nullopt;
    return (K * q).hnormalized();
  }
};

// Legs: keyframes moving the same way along the dominant axis of motion
// (a lawnmower's tracks); keyframes moving across it are transits (-1).
std::vector<int> Legs(const std::vector<Pose>& x_g_v) {
  const std::size_t n = x_g_v.size();
  std::vector<int> leg(n, -1);
  if (n < 2) return leg;
  Eigen::Vector3d axis = (x_g_v[1].translation() - x_g_v[0].translation()).normalized();
  int current = 0, sign = 0;
  for (std::size_t k = 1; k < n; ++k) {
    const Eigen::Vector3d d = x_g_v[k].translation() - x_g_v[k - 1].translation();
    const double along = d.dot(axis);
    if (std::abs(along) < 0.7 * d.norm()) continue;  // transit
    const int s = along > 0 ? 1 : -1;
    if (sign != 0 && s != sign) ++current;
    sign = s;
    leg[k] = current;
  }
  leg[0] = leg[1];
  return leg;
}

struct Precision {
  int total = 0, within2 = 0, within5 = 0, missed = 0;
  void Add(const Truth& t, std::size_t a, const Eigen::Vector2d& ua, std::size_t b, const Eigen::Vector2d& ub) {
    const auto p = t.Transfer(a, ua, b);
    if (!p) {
      ++missed;
      return;
    }
    ++total;
    const double e = (*p - ub).norm();
    within2 += e <= 2.0;
    within5 += e <= 5.0;
  }
};

struct TrackStats {
  std::map<int, int> length;  // keyframes per track -> tracks
  int tracks = 0, multi_leg = 0;
  double mean = 0;
  int good = 0, checked = 0;  // observations within 2 cm of their track's first
};

TrackStats Tracks(const FrontEndResult& r, const Truth& t) {
  std::map<std::int64_t, std::vector<const FeatureObservation*>> by;
  for (const auto& f : r.features) by[f.landmark].push_back(&f);
  TrackStats s;
  long sum = 0;
  for (const auto& [id, obs] : by) {
    ++s.tracks;
    sum += static_cast<long>(obs.size());
    const int bucket = obs.size() >= 20   ? 20
                       : obs.size() >= 10 ? 10
                       : obs.size() >= 5  ? 5
                                          : static_cast<int>(obs.size());
    ++s.length[bucket];
    std::optional<Eigen::Vector3d> ref;
    int leg0 = -2;
    bool multi = false;
    for (const FeatureObservation* o : obs) {
      const std::size_t k = static_cast<std::size_t>(r.KeyframeIndex(o->keyframe));
      const int leg = t.leg[k];
      if (leg >= 0) {
        if (leg0 == -2) leg0 = leg;
        multi |= leg != leg0;
      }
      const auto p = t.Surface(k, o->top);
      if (!p) continue;
      if (!ref) {
        ref = p;
        continue;
      }
      ++s.checked;
      s.good += (*p - *ref).norm() < 0.02;
    }
    s.multi_leg += multi;
  }
  s.mean = s.tracks ? static_cast<double>(sum) / s.tracks : 0;
  return s;
}

void PrintTracks(const char* what, const TrackStats& s) {
  std::printf("%s: %d tracks, mean %.2f keyframes; length 2: %d, 3: %d, 4: %d, 5-9: %d, 10-19: %d, >=20: %d; ", what,
              s.tracks, s.mean, s.length.count(2) ? s.length.at(2) : 0, s.length.count(3) ? s.length.at(3) : 0,
              s.length.count(4) ? s.length.at(4) : 0, s.length.count(5) ? s.length.at(5) : 0,
              s.length.count(10) ? s.length.at(10) : 0, s.length.count(20) ? s.length.at(20) : 0);
  std::printf("in more than one leg: %d; observations within 2 cm of their track's point: %.2f %% of %d\n", s.multi_leg,
              100.0 * s.good / std::max(1, s.checked), s.checked);
}

}  // namespace
}  // namespace hull

int main(int argc, char** argv) {
  using namespace hull;
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_loops BUNDLE [threads=2] [--determinism]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int threads = argc > 2 && std::strcmp(argv[2], "--determinism") != 0 ? std::atoi(argv[2]) : 2;
  bool determinism = false;
  for (int i = 2; i < argc; ++i) determinism |= std::strcmp(argv[i], "--determinism") == 0;
  SurveyBundle bundle = ReadSurveyBundle(dir);
  if (!bundle.truth) {
    std::fprintf(stderr, "%s has no truth\n", dir.c_str());
    return 1;
  }
  bundle.features.clear();
  const auto scene = TrueScene::Load(bundle);
  Truth t;
  t.scene = scene.get();
  t.x_Mg = Pose::FromVector(bundle.truth->x_gM).Inverse();
  t.K = CameraMatrix(bundle.manifest.camera.top);
  std::vector<Pose> x_g_v;
  for (std::size_t k = 0; k < bundle.nav.size(); ++k) {
    t.x_g_c.push_back(t.x_Mg.Inverse() * TrueCameraPoseFromTruth(bundle, k, false));
    x_g_v.push_back(Pose::FromVector(bundle.truth->poses.at(k).x_gv));
  }
  t.leg = Legs(x_g_v);
  std::printf("%s: %zu keyframes, %d legs\n", dir.c_str(), bundle.nav.size(),
              *std::max_element(t.leg.begin(), t.leg.end()) + 1);

  NullProgress progress;
  FrontEndOptions o;
  o.threads = threads;
  o.loops.enabled = false;
  double w0 = Now(), c0 = bench::CpuSeconds();
  const FrontEndResult before = RunFrontEnd(bundle, o, progress);
  const double wall_before = Now() - w0, cpu_before = bench::CpuSeconds() - c0;
  o.loops.enabled = true;
  w0 = Now();
  c0 = bench::CpuSeconds();
  const FrontEndResult after = RunFrontEnd(bundle, o, progress);
  const double wall_after = Now() - w0, cpu_after = bench::CpuSeconds() - c0;

  // Sequential and loop pairs: tried / accepted, inlier precision.
  Precision seq, loop, loop_putative;
  int seq_pairs = 0, seq_accepted = 0, cross = 0, cross_accepted = 0;
  std::vector<double> windows, prior_rot, prior_pos;
  for (const FrontEndPair& p : after.pairs) {
    const std::size_t a = static_cast<std::size_t>(after.KeyframeIndex(p.from));
    const std::size_t b = static_cast<std::size_t>(after.KeyframeIndex(p.to));
    const auto& ka = after.keyframes[a];
    const auto& kb = after.keyframes[b];
    if (!p.loop) {
      ++seq_pairs;
      seq_accepted += p.accepted;
    } else {
      const bool x = t.leg[a] != t.leg[b];
      cross += x;
      cross_accepted += x && p.accepted;
      windows.push_back(p.window);
      // The prior's relative camera pose against the truth.
      const Pose prior = CameraPoseFromNav(bundle.manifest, bundle.nav[b]).Inverse() *
                         CameraPoseFromNav(bundle.manifest, bundle.nav[a]);
      const Pose truth = t.x_g_c[b].Inverse() * t.x_g_c[a];
      prior_rot.push_back(Pose::AngleBetween(prior, truth) * 180 / M_PI);
      prior_pos.push_back((prior.translation() - truth.translation()).norm());
    }
    for (const FrontEndMatch& m : p.matches) {
      const Eigen::Vector2d& ua = ka.top_points[static_cast<std::size_t>(m.a)];
      const Eigen::Vector2d& ub = kb.top_points[static_cast<std::size_t>(m.b)];
      if (p.loop) loop_putative.Add(t, a, ua, b, ub);
      if (!p.accepted || !m.inlier) continue;
      (p.loop ? loop : seq).Add(t, a, ua, b, ub);
    }
  }
  auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  auto maxof = [](const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); };
  std::printf(
      "sequential pairs: %d tried, %d accepted; inliers within 2 px of the truth %.2f %% (5 px %.2f %%) of %d\n",
      seq_pairs, seq_accepted, 100.0 * seq.within2 / std::max(1, seq.total),
      100.0 * seq.within5 / std::max(1, seq.total), seq.total);
  std::printf(
      "loop pairs: %zu considered (footprints near), %d tried, %d accepted; across legs %d tried, %d accepted\n",
      after.loop_pairs_considered, after.loop_pairs_tried, after.loop_pairs_accepted, cross, cross_accepted);
  std::printf("loop inliers within 2 px of the truth %.2f %% (5 px %.2f %%) of %d; putative matches %.2f %% of %d\n",
              100.0 * loop.within2 / std::max(1, loop.total), 100.0 * loop.within5 / std::max(1, loop.total),
              loop.total, 100.0 * loop_putative.within2 / std::max(1, loop_putative.total), loop_putative.total);
  std::printf(
      "loop window: median %.0f px, max %.0f px; prior error of the loop pairs: rotation median %.2f max %.2f "
      "deg, translation median %.3f max %.3f m\n",
      median(windows), maxof(windows), median(prior_rot), maxof(prior_rot), median(prior_pos), maxof(prior_pos));
  std::map<std::string, int> notes;
  for (const FrontEndPair& p : after.pairs) {
    if (p.loop && !p.accepted) ++notes[p.note];
  }
  for (const auto& [note, count] : notes) std::printf("  loop pairs dropped: %d %s\n", count, note.c_str());
  PrintTracks("tracks without loops", Tracks(before, t));
  PrintTracks("tracks with loops   ", Tracks(after, t));
  std::printf(
      "time, %d threads: without loops %.1f s wall (%.1f CPU-s), with loops %.1f s wall (%.1f CPU-s); "
      "loop stage %.2f s wall\n",
      threads, wall_before, cpu_before, wall_after, cpu_after, after.loop_seconds);
  if (determinism) {
    o.threads = 1;
    const FrontEndResult one = RunFrontEnd(bundle, o, progress);
    bool same = one.features.size() == after.features.size() && one.pairs.size() == after.pairs.size();
    for (std::size_t i = 0; same && i < one.features.size(); ++i) {
      same = one.features[i].keyframe == after.features[i].keyframe &&
             one.features[i].landmark == after.features[i].landmark && one.features[i].top == after.features[i].top;
    }
    std::printf("one thread vs %d: %s\n", threads, same ? "same features" : "DIFFERENT features");
  }
  return 0;
}
