#include "vision/front_end.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"
#include "vision/camera_geometry.h"
#include "vision/feature_detection.h"
#include "vision/feature_tracks.h"
#include "vision/loop_closure.h"
#include "vision/stereo_matching.h"
#include "vision/temporal_matching.h"
#include "vision/track_check.h"
#include "vision/track_refinement.h"

namespace hull {
namespace fs = std::filesystem;

namespace {

// Progress from worker threads: one update at a time, never going back.
class SharedProgress {
 public:
  SharedProgress(Progress& p, double begin, double end, int total) : p_(p), begin_(begin), end_(end), total_(total) {}
  void Step(const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    p_.Update(begin_ + (end_ - begin_) * done_ / std::max(1, total_), message);
  }
  void ThrowIfCancelled() const { p_.ThrowIfCancelled(); }

 private:
  Progress& p_;
  double begin_, end_;
  int total_;
  int done_ = 0;
  std::mutex mutex_;
};

struct Link {
  float distance;
  int ka, fa, kb, fb;
};

}  // namespace

FrontEndResult RunFrontEnd(const SurveyBundle& bundle, const FrontEndOptions& o, Progress& progress) {
  o.Check();
  const auto t0 = std::chrono::steady_clock::now();
  const SurveyManifest& man = bundle.manifest;
  const CameraRig& rig = man.camera;
  if (!bundle.images || bundle.images->present() == 0) {
    throw InputError({(fs::path(bundle.directory) / "images").string(), 0, 0, ""},
                     "the bundle has no camera images to extract features from");
  }
  const SurveyImages& images = *bundle.images;
  const std::size_t n = bundle.nav.size();
  FrontEndResult r;
  r.keyframes.resize(n);
  std::vector<KeyframeView> views(n);
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);

  // 1. Features and stereo matches per keyframe.
  SharedProgress detect_progress(progress, 0.0, 0.6, static_cast<int>(n));
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      detect_progress.ThrowIfCancelled();
      const NavRecord& nav = bundle.nav[i];
      FrontEndKeyframe& k = r.keyframes[i];
      KeyframeView& v = views[i];
      k.keyframe = v.keyframe = nav.keyframe;
      v.x_g_cT = CameraPoseFromNav(man, nav);
      const KeyframeImages* img = i < images.frames.size() ? &images.frames[i] : nullptr;
      if (img && !img->top.empty()) {
        k.has_top = true;
        v.top = DetectFeatures(ReadSurveyImage(bundle, nav.keyframe, false), o.detection);
        k.top_features = static_cast<int>(v.top.size());
        k.top_points = v.top.points;
        k.top_sizes = v.top.sizes;
        if (rig.stereo() && !img->bottom.empty()) {
          k.has_bottom = true;
          const ImageFeatures bottom = DetectFeatures(ReadSurveyImage(bundle, nav.keyframe, true), o.detection);
          k.bottom_features = static_cast<int>(bottom.size());
          k.bottom_points = bottom.points;
          k.bottom_sizes = bottom.sizes;
          v.stereo = MatchStereo(v.top, bottom, rig, o.stereo);
          k.stereo_matches = static_cast<int>(v.stereo.size());
          for (const StereoMatch& m : v.stereo) k.stereo.push_back({m.top, m.bottom, MatchVerdict::kUnverified});
        }
      }
      detect_progress.Step("features of keyframe " + std::to_string(nav.keyframe));
    });
  });

  // 2. Temporal matches: each keyframe with its next `neighbours` keyframes
  // that have a top image, in nav order.
  std::vector<std::size_t> with_image;
  for (std::size_t i = 0; i < n; ++i) {
    if (r.keyframes[i].has_top) with_image.push_back(i);
  }
  struct PairJob {
    std::size_t a, b;
    bool loop;
    double overlap;
    TemporalOptions options;
  };
  std::vector<PairJob> pairs;
  for (std::size_t a = 0; a < with_image.size(); ++a) {
    for (std::size_t b = a + 1; b < with_image.size() && b <= a + static_cast<std::size_t>(o.temporal.neighbours); ++b)
      pairs.push_back({with_image[a], with_image[b], false, 0.0, o.temporal});
  }
  std::vector<PairMatches> matches(pairs.size());
  auto match_range = [&](std::size_t begin, std::size_t end, SharedProgress& step) {
    arena.execute([&] {
      tbb::parallel_for(begin, end, [&](std::size_t p) {
        step.ThrowIfCancelled();
        const PairJob& job = pairs[p];
        matches[p] = MatchKeyframes(views[job.a], views[job.b], rig, job.options);
        step.Step(std::string(job.loop ? "loop closure " : "matching keyframes ") +
                  std::to_string(views[job.a].keyframe) + " and " + std::to_string(views[job.b].keyframe));
      });
    });
  };
  SharedProgress match_progress(progress, 0.6, 0.85, static_cast<int>(pairs.size()));
  match_range(0, pairs.size(), match_progress);

  // 2b. Loop closures: pairs far apart in nav order whose footprints overlap
  // under the prior, matched with a window and tolerances grown by the
  // navigation drift between them.
  // Each keyframe's DVL record (null: none), for the loop footprints and
  // the mono track check.
  std::vector<const DvlRecord*> dvl_of(n, nullptr);
  {
    std::unordered_map<std::int64_t, const DvlRecord*> by_keyframe;
    for (const DvlRecord& d : bundle.dvl) by_keyframe.emplace(d.keyframe, &d);
    for (std::size_t i = 0; i < n; ++i) {
      const auto d = by_keyframe.find(views[i].keyframe);
      if (d != by_keyframe.end()) dvl_of[i] = d->second;
    }
  }
  if (o.loops.enabled) {
    const auto l0 = std::chrono::steady_clock::now();
    progress.Update(0.85, "looking for loop closures");
    std::vector<LoopKeyframe> lk(n);
    double path = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) path += (bundle.nav[i].x_gv.head<3>() - bundle.nav[i - 1].x_gv.head<3>()).norm();
      LoopKeyframe& k = lk[i];
      k.x_g_cT = views[i].x_g_cT;
      k.t = bundle.nav[i].t;
      k.path = path;
    }
    for (std::size_t w = 0; w < with_image.size(); ++w) {
      const std::size_t i = with_image[w];
      LoopKeyframe& k = lk[i];
      k.order = static_cast<int>(w);
      k.footprint = StereoFootprint(views[i], o.loops.footprint_points);
      if (k.footprint.empty() && dvl_of[i]) k.footprint = DvlFootprint(man, *dvl_of[i], o.loops.footprint_points);
      PlaceFootprint(k.footprint, k.x_g_cT);
    }
    const std::vector<LoopCandidate> candidates =
        FindLoopCandidates(lk, rig, o.temporal.neighbours, o.loops, &r.loop_pairs_considered);
    const std::size_t first_loop = pairs.size();
    for (const LoopCandidate& c : candidates) {
      const double distance = (lk[c.b].x_g_cT.translation() - lk[c.a].x_g_cT.translation()).norm();
      pairs.push_back({c.a, c.b, true, c.overlap,
                       LoopMatchingOptions(o.temporal, o.loops, man.noise, rig.top.fx, lk[c.a].footprint, c.seconds,
                                           c.path, distance)});
    }
    matches.resize(pairs.size());
    SharedProgress loop_progress(progress, 0.85, 0.95, static_cast<int>(candidates.size()));
    match_range(first_loop, pairs.size(), loop_progress);
    r.loop_pairs_tried = static_cast<int>(candidates.size());
    for (std::size_t p = first_loop; p < pairs.size(); ++p) r.loop_pairs_accepted += matches[p].accepted;
    r.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - l0).count();
  }

  // 3. Tracks: links of accepted pairs, best (smallest descriptor distance) first.
  progress.Update(0.95, "building tracks");
  std::vector<Link> links;
  std::vector<std::vector<MatchVerdict>> verdicts(n);  // per top feature
  for (std::size_t i = 0; i < n; ++i) verdicts[i].assign(views[i].top.size(), MatchVerdict::kUnverified);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const PairMatches& m = matches[p];
    const PairJob& job = pairs[p];
    FrontEndPair fp;
    fp.from = views[job.a].keyframe;
    fp.to = views[job.b].keyframe;
    fp.loop = job.loop;
    fp.overlap = job.overlap;
    fp.window = job.options.window;
    fp.stereo = m.stereo;
    fp.putative = m.putative;
    fp.inliers = m.inliers;
    fp.accepted = m.accepted;
    fp.note = m.note;
    for (std::size_t q = 0; q < m.putative_matches.size(); ++q) {
      const TemporalMatch& t = m.putative_matches[q];
      const bool inlier = q < m.putative_inlier.size() && m.putative_inlier[q];
      fp.matches.push_back({t.a, t.b, inlier});
      // The verdict on the stereo matches of both keyframes' top features.
      for (const auto& [ki, f] : {std::pair{job.a, t.a}, std::pair{job.b, t.b}}) {
        std::vector<MatchVerdict>& v = verdicts[ki];
        if (inlier) {
          v[static_cast<std::size_t>(f)] = MatchVerdict::kInlier;
        } else if (v[static_cast<std::size_t>(f)] == MatchVerdict::kUnverified) {
          v[static_cast<std::size_t>(f)] = MatchVerdict::kOutlier;
        }
      }
    }
    r.pairs.push_back(std::move(fp));
    if (!m.accepted) continue;
    for (const auto& t : m.matches)
      links.push_back({t.distance, static_cast<int>(job.a), t.a, static_cast<int>(job.b), t.b});
  }
  std::stable_sort(links.begin(), links.end(), [](const Link& a, const Link& b) { return a.distance < b.distance; });
  std::vector<int> counts(n);
  for (std::size_t i = 0; i < n; ++i) counts[i] = static_cast<int>(views[i].top.size());
  TrackBuilder builder(counts);
  for (const Link& l : links) builder.Link(l.ka, l.fa, l.kb, l.fb);
  r.refused_merges = builder.refused();
  std::vector<TrackBuilder::Track> tracks = builder.Tracks(o.tracks.min_keyframes, &r.dropped_tracks);
  // SIFT's copies of one keypoint (one per dominant orientation) each match
  // on their own: a track whose members are, keyframe by keyframe, at the
  // same positions as an earlier track's is that track again, and dropped.
  // (Linking the copies as one feature instead joins their tracks, and one
  // copy's wrong match then spoils the other's right track: docs/vision.md.)
  {
    std::vector<std::vector<int>> first_copy(n);
    for (std::size_t i = 0; i < n; ++i) {
      first_copy[i] = DuplicateKeypoints(views[i].top.points);
      for (std::size_t f = 0; f < first_copy[i].size(); ++f)
        r.duplicate_keypoints += first_copy[i][f] != static_cast<int>(f);
    }
    std::set<TrackBuilder::Track> seen;
    std::vector<TrackBuilder::Track> unique;
    unique.reserve(tracks.size());
    for (TrackBuilder::Track& t : tracks) {
      TrackBuilder::Track key = t;
      for (auto& [k, f] : key) f = first_copy[static_cast<std::size_t>(k)][static_cast<std::size_t>(f)];
      if (!seen.insert(std::move(key)).second) {
        ++r.duplicate_tracks;
        continue;
      }
      unique.push_back(std::move(t));
    }
    tracks = std::move(unique);
  }
  std::vector<std::vector<int>> bottom_of(n);  // top feature -> stereo match (-1: none)
  for (std::size_t i = 0; i < n; ++i) {
    bottom_of[i].assign(views[i].top.size(), -1);
    for (std::size_t s = 0; s < views[i].stereo.size(); ++s)
      bottom_of[i][static_cast<std::size_t>(views[i].stereo[s].top)] = static_cast<int>(s);
  }
  // 3b. Sub-pixel refinement of the tracks' top pixels.
  if (o.tracks.refine) {
    progress.Update(0.96, "refining the tracks' pixels");
    std::vector<std::vector<Eigen::Vector2d>> points(n);
    std::vector<Pose> cameras(n);
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = views[i].top.points;
      cameras[i] = views[i].x_g_cT;
    }
    r.refinement = RefineTrackPixels(
        tracks, [&](std::size_t k) { return ReadSurveyImage(bundle, views[k].keyframe, false); }, cameras, rig.top,
        points, o.tracks, o.threads);
    for (std::size_t i = 0; i < n; ++i) {
      views[i].top.points = std::move(points[i]);
      r.keyframes[i].top_points = views[i].top.points;  // the tracks' members where they were aligned
    }
  }
  if (o.tracks.check_dvl_height) {
    progress.Update(0.97, "checking mono tracks against the DVL");
    std::vector<std::vector<char>> has_stereo(n);
    for (std::size_t i = 0; i < n; ++i) {
      has_stereo[i].assign(views[i].top.size(), 0);
      for (std::size_t f = 0; f < bottom_of[i].size(); ++f) has_stereo[i][f] = bottom_of[i][f] >= 0;
    }
    std::vector<std::optional<CameraPlane>> planes(n);
    for (std::size_t i = 0; i < n; ++i) {
      CameraPlane plane;
      if (dvl_of[i] && DvlPlane(man, *dvl_of[i], plane)) planes[i] = plane;
    }
    r.track_checks = CheckTrackHeights(tracks, views, has_stereo, planes, rig, o.tracks, o.threads);
    std::vector<char> keep(tracks.size(), 1);
    for (const TrackCheck& c : r.track_checks) {
      if (!c.kept) {
        keep[static_cast<std::size_t>(c.track)] = 0;
        ++r.tracks_failed_check;
      }
    }
    std::vector<TrackBuilder::Track> kept;
    kept.reserve(tracks.size());
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      if (keep[t]) kept.push_back(std::move(tracks[t]));
    }
    tracks = std::move(kept);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (FrontEndStereoLink& s : r.keyframes[i].stereo) s.verdict = verdicts[i][static_cast<std::size_t>(s.top)];
    r.keyframes[i].landmark.assign(views[i].top.size(), -1);
  }

  // 4. Observations with global landmark ids (track order).
  std::vector<std::tuple<int, std::int64_t, FeatureObservation>> rows;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    for (const auto& [k, f] : tracks[t]) {
      const std::size_t ki = static_cast<std::size_t>(k);
      FeatureObservation obs;
      obs.keyframe = views[ki].keyframe;
      obs.landmark = static_cast<std::int64_t>(t);
      obs.top = views[ki].top.points[static_cast<std::size_t>(f)];
      const int s = bottom_of[ki][static_cast<std::size_t>(f)];
      if (s >= 0) {
        obs.has_bottom = true;
        obs.bottom = views[ki].stereo[static_cast<std::size_t>(s)].bottom_uv;
      }
      rows.emplace_back(k, obs.landmark, obs);
      r.keyframes[ki].landmark[static_cast<std::size_t>(f)] = obs.landmark;
      ++r.keyframes[ki].tracked;
    }
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b));
  });
  r.features.reserve(rows.size());
  for (auto& row : rows) r.features.push_back(std::get<2>(row));
  r.landmarks = static_cast<int>(tracks.size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.Update(1.0, "front end done");
  return r;
}

int FrontEndResult::KeyframeIndex(std::int64_t keyframe) const {
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    if (keyframes[i].keyframe == keyframe) return static_cast<int>(i);
  }
  return -1;
}

bool ExtractFeaturesIfNeeded(SurveyBundle& bundle, const FrontEndOptions& options, Progress& progress,
                             FrontEndResult* result) {
  if (!bundle.features.empty() || !bundle.images || bundle.images->present() == 0) return false;
  FrontEndResult r = RunFrontEnd(bundle, options, progress);
  bundle.AdoptImageFeatureTracks(r.features);
  if (result) *result = std::move(r);
  return true;
}

}  // namespace hull
