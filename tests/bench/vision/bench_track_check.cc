// The DVL height check of mono tracks (vision/track_check.h) on a rendered
// survey with truth: runs the front end with the check recording but
// dropping nothing (tracks of up to 4 keyframes), scores every checked
// track against the true scene (its features' pixels cast from the TRUE
// cameras: a wrong match when the hits lie farther apart than 2 cm) and
// prints how many right and wrong tracks each height band and track length
// would drop. --out writes features.csv (and match-graph.csv) with the
// tracks the default options drop left out.
//
//   bench_track_check BUNDLE [--threads N] [--out FEATURES_CSV]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "results/front_end_files.h"
#include "simulate/image_track_truth.h"
#include "simulate/true_scene.h"
#include "survey/survey_io.h"
#include "vision/front_end.h"

int main(int argc, char** argv) {
  using namespace hull;
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_track_check BUNDLE [--threads N] [--out FEATURES_CSV]\n");
    return 2;
  }
  std::string out;
  FrontEndOptions o;
  o.threads = 2;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--threads") {
      o.threads = std::atoi(argv[i + 1]);
    } else if (a == "--out") {
      out = argv[i + 1];
    } else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  SurveyBundle bundle = ReadSurveyBundle(argv[1]);
  if (!bundle.truth) {
    std::fprintf(stderr, "%s: no truth\n", argv[1]);
    return 1;
  }
  bundle.features.clear();
  const auto scene = TrueScene::Load(bundle);
  const TrackOptions defaults = o.tracks;
  o.tracks.check_max_keyframes = 4;  // record, drop nothing
  o.tracks.check_max_height = 1e9;
  o.tracks.check_min_height = -1e9;
  o.tracks.check_max_reprojection = 1e9;
  NullProgress quiet;
  FrontEndResult r = RunFrontEnd(bundle, o, quiet);
  const CameraRig& rig = bundle.manifest.camera;
  const Pose x_Mg = Pose::FromVector(bundle.truth->x_gM).Inverse();

  struct Scored {
    const TrackCheck* c;
    bool wrong;
    double off;  // the prior's triangulated point (moved into M) from the first true hit
  };
  std::vector<Scored> scored;
  for (const TrackCheck& c : r.track_checks) {
    std::vector<Eigen::Vector3d> hits;
    for (const auto& [k, f] : c.members) {
      const Pose cam = TrueCameraPoseFromTruth(bundle, static_cast<std::size_t>(k), false);
      const Eigen::Vector2d uv = r.keyframes[static_cast<std::size_t>(k)].top_points[static_cast<std::size_t>(f)];
      const Eigen::Vector3d d((uv.x() - rig.top.cx) / rig.top.fx, (uv.y() - rig.top.cy) / rig.top.fy, 1.0);
      const RayHit h = scene->index().Raycast(cam.translation(), cam.rotation() * d.normalized());
      if (h.hit) hits.push_back(h.point);
    }
    if (hits.size() < c.members.size() || std::isnan(c.min_height)) continue;
    bool wrong = false;
    for (const Eigen::Vector3d& h : hits) wrong = wrong || (h - hits.front()).norm() > 0.02;
    scored.push_back({&c, wrong, (x_Mg * c.point - hits.front()).norm()});
  }
  std::printf("%d tracks, %zu checked, %zu scored; front end %.1f s\n", r.landmarks, r.track_checks.size(),
              scored.size(), r.seconds);
  for (std::size_t size = 2; size <= 4; ++size) {
    std::size_t right_n = 0, wrong_n = 0, far_n = 0;
    for (const Scored& s : scored) {
      if (s.c->members.size() != size) continue;
      right_n += !s.wrong;
      wrong_n += s.wrong;
      far_n += s.wrong && s.off > 0.1;
    }
    std::printf("tracks of %zu keyframes: %zu right, %zu wrong (%zu > 0.1 m off)\n", size, right_n, wrong_n, far_n);
    std::printf(
        "| dropped when | right dropped | wrong dropped | wrong > 0.1 m off dropped |\n| --- | --- | --- | --- |\n");
    for (double hi : {0.15, 0.2, 0.25, 0.3}) {
      for (double lo : {-0.05, -0.1, -0.2, -1e9}) {
        std::size_t rd = 0, wd = 0, wfd = 0;
        for (const Scored& s : scored) {
          if (s.c->members.size() != size) continue;
          if (s.c->min_height <= hi && s.c->max_height >= lo) continue;
          rd += !s.wrong;
          wd += s.wrong;
          wfd += s.wrong && s.off > 0.1;
        }
        std::printf("| h > %.2f or h < %.2f m | %zu | %zu | %zu |\n", hi, lo, rd, wd, wfd);
      }
    }
  }
  std::printf("tracks of 3 keyframes by the largest reprojection error (prior poses) and height:\n");
  std::printf(
      "| dropped when | right dropped | wrong dropped | wrong > 0.1 m off dropped |\n| --- | --- | --- | --- |\n");
  for (double px : {2.0, 4.0, 8.0, 16.0}) {
    for (double h : {0.0, 0.05, 0.1, -1e9}) {
      std::size_t rd = 0, wd = 0, wfd = 0;
      for (const Scored& s : scored) {
        if (s.c->members.size() != 3 || s.c->max_reprojection <= px || s.c->min_height <= h) continue;
        rd += !s.wrong;
        wd += s.wrong;
        wfd += s.wrong && s.off > 0.1;
      }
      std::printf("| reprojection > %.0f px and h > %.2f m | %zu | %zu | %zu |\n", px, h, rd, wd, wfd);
    }
  }
  std::printf("wrong tracks of 3 keyframes 0.1-0.25 m in front: off, min height, reprojection px, keyframes\n");
  for (const Scored& s : scored) {
    if (!s.wrong || s.c->members.size() != 3 || s.c->min_height < 0.1 || s.c->min_height > 0.25) continue;
    std::printf("  %.3f m, %.3f m, %.1f px,", s.off, s.c->min_height, s.c->max_reprojection);
    for (const auto& m : s.c->members)
      std::printf(" %lld", static_cast<long long>(r.keyframes[static_cast<std::size_t>(m.first)].keyframe));
    std::printf("\n");
  }
  std::printf("right tracks standing highest (min height over members), 2-3 keyframes: ");
  std::vector<double> right_h;
  for (const Scored& s : scored) {
    if (!s.wrong && s.c->members.size() <= 3) right_h.push_back(s.c->min_height);
  }
  std::sort(right_h.rbegin(), right_h.rend());
  for (std::size_t i = 0; i < std::min<std::size_t>(15, right_h.size()); ++i) std::printf("%.3f ", right_h[i]);
  std::printf("\n");

  if (!out.empty()) {  // the default options' verdicts
    std::set<std::int64_t> dropped;
    for (const TrackCheck& c : r.track_checks) {
      if (c.members.size() > static_cast<std::size_t>(defaults.check_max_keyframes) || std::isnan(c.min_height))
        continue;
      if (TrackCheckKeeps(c, defaults)) continue;
      const auto& [k, f] = c.members.front();
      dropped.insert(r.keyframes[static_cast<std::size_t>(k)].landmark[static_cast<std::size_t>(f)]);
    }
    std::vector<FeatureObservation> kept;
    std::map<std::int64_t, std::int64_t> renumber;
    for (const FeatureObservation& f : r.features) {
      if (!dropped.count(f.landmark)) renumber.emplace(f.landmark, 0);
    }
    std::int64_t next = 0;
    for (auto& [from, to] : renumber) to = next++;
    for (FeatureObservation f : r.features) {
      if (dropped.count(f.landmark)) continue;
      f.landmark = renumber[f.landmark];
      kept.push_back(f);
    }
    r.features = kept;
    WriteFrontEndResult(r, bundle.manifest, out);
    std::printf("wrote %s: %zu tracks dropped by the default options, %lld written\n", out.c_str(), dropped.size(),
                static_cast<long long>(next));
  }
  return 0;
}
