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
#include "vision/front_end_evidence.h"
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

// One run of the front end: the survey, the options and what the stages
// hand on to each other (the keyframes' views, the pairs to match and their
// matches, the match verdicts), filling `r` stage by stage.
class FrontEndRun {
 public:
  FrontEndRun(const SurveyBundle& bundle, const FrontEndOptions& o, Progress& progress)
      : bundle_(bundle),
        o_(o),
        progress_(progress),
        man_(bundle.manifest),
        rig_(man_.camera),
        n_(bundle.nav.size()),
        views_(n_),
        arena_(o.threads > 0 ? o.threads : tbb::task_arena::automatic) {
    r_.keyframes.resize(n_);
    detected_.assign(n_, 0);
  }

  FrontEndResult Run() {
    const auto t0 = std::chrono::steady_clock::now();
    if (rig_.stereo()) ProbeSwap();
    DetectFeaturesAndStereo();
    CheckImages();
    PlanNeighbourPairs();
    SharedProgress match_progress(progress_, 0.6, 0.85, static_cast<int>(pairs_.size()));
    MatchPairs(0, pairs_.size(), match_progress);
    FindDvlRecords();
    if (o_.loops.enabled) MatchLoops();
    progress_.Update(0.95, "building tracks");
    std::vector<TrackBuilder::Track> tracks = BuildTracks(CollectPairs());
    DropDuplicateTracks(tracks);
    FindStereoOfTopFeatures();
    if (o_.tracks.refine) RefineTracks(tracks);
    if (o_.tracks.check_dvl_height) CheckMonoTracks(tracks);
    WriteObservations(tracks);
    CheckTracks();
    r_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress_.Update(1.0, "front end done");
    return std::move(r_);
  }

 private:
  struct PairJob {
    std::size_t a, b;
    bool loop;
    double overlap;
    TemporalOptions options;
  };

  std::string ImagesFolder() const { return (fs::path(bundle_.directory) / "images").string(); }

  // 0. Evidence rule 0 (front_end_evidence.h): a few keyframes spread over
  // the survey matched as named and with the cameras exchanged, before
  // anything else; their features are kept for stage 1.
  void ProbeSwap() {
    const SurveyImages& images = *bundle_.images;
    std::vector<std::size_t> both;
    for (std::size_t i = 0; i < n_ && i < images.frames.size(); ++i) {
      if (!images.frames[i].top.empty() && !images.frames[i].bottom.empty()) both.push_back(i);
    }
    const std::size_t probes = std::min<std::size_t>(both.size(), evidence::kSwapProbeKeyframes);
    std::vector<SwapProbe> found(probes);
    std::vector<std::size_t> which(probes);
    for (std::size_t p = 0; p < probes; ++p) which[p] = both[(2 * p + 1) * both.size() / (2 * probes)];
    arena_.execute([&] {
      tbb::parallel_for(std::size_t{0}, probes, [&](std::size_t p) {
        progress_.ThrowIfCancelled();
        ImageFeatures bottom;
        DetectKeyframe(which[p], &bottom);
        found[p].as_named = r_.keyframes[which[p]].stereo_matches;
        found[p].exchanged = static_cast<int>(MatchStereo(bottom, views_[which[p]].top, rig_, o_.stereo).size());
      });
    });
    CheckSwapEvidence(evidence_, found, ImagesFolder());
  }

  // One keyframe's features and stereo matches (`bottom_out`: its bottom
  // features, when asked for); marks it detected.
  void DetectKeyframe(std::size_t i, ImageFeatures* bottom_out = nullptr) {
    const SurveyImages& images = *bundle_.images;
    const NavRecord& nav = bundle_.nav[i];
    FrontEndKeyframe& k = r_.keyframes[i];
    KeyframeView& v = views_[i];
    k.keyframe = v.keyframe = nav.keyframe;
    v.x_g_cT = CameraPoseFromNav(man_, nav);
    const KeyframeImages* img = i < images.frames.size() ? &images.frames[i] : nullptr;
    if (img && !img->top.empty()) {
      k.has_top = true;
      v.top = DetectFeatures(ReadSurveyImage(bundle_, nav.keyframe, false), o_.detection);
      k.top_features = static_cast<int>(v.top.size());
      k.top_points = v.top.points;
      k.top_sizes = v.top.sizes;
      if (rig_.stereo() && !img->bottom.empty()) {
        k.has_bottom = true;
        ImageFeatures bottom = DetectFeatures(ReadSurveyImage(bundle_, nav.keyframe, true), o_.detection);
        k.bottom_features = static_cast<int>(bottom.size());
        k.bottom_points = bottom.points;
        k.bottom_sizes = bottom.sizes;
        v.stereo = MatchStereo(v.top, bottom, rig_, o_.stereo);
        k.stereo_matches = static_cast<int>(v.stereo.size());
        for (const StereoMatch& m : v.stereo) k.stereo.push_back({m.top, m.bottom, MatchVerdict::kUnverified});
        if (bottom_out) *bottom_out = std::move(bottom);
      }
    }
    detected_[i] = 1;
  }

  // 1. Features and stereo matches per keyframe (those rule 0 did not detect).
  void DetectFeaturesAndStereo() {
    SharedProgress detect_progress(progress_, 0.0, 0.6, static_cast<int>(n_));
    arena_.execute([&] {
      tbb::parallel_for(std::size_t{0}, n_, [&](std::size_t i) {
        detect_progress.ThrowIfCancelled();
        if (!detected_[i]) DetectKeyframe(i);
        detect_progress.Step("features of keyframe " + std::to_string(bundle_.nav[i].keyframe));
      });
    });
  }

  // Evidence rules 1 and 2: images that show something, stereo pairs that match.
  void CheckImages() {
    const FrontEndEvidence probe = evidence_;
    evidence_ = ImageEvidence(r_, rig_.stereo());
    evidence_.swap_probed = probe.swap_probed;
    evidence_.swap_matched = probe.swap_matched;
    CheckImageEvidence(evidence_, rig_.stereo(), ImagesFolder());
  }

  // Evidence rule 3: enough tracks.
  void CheckTracks() {
    evidence_.pairs = static_cast<int>(r_.pairs.size());
    for (const FrontEndPair& p : r_.pairs) evidence_.pairs_accepted += p.accepted;
    evidence_.landmarks = r_.landmarks;
    r_.evidence = evidence_;
    CheckTrackEvidence(evidence_, ImagesFolder());
  }

  // 2. Temporal matches: each keyframe with its next `neighbours` keyframes
  // that have a top image, in nav order.
  void PlanNeighbourPairs() {
    for (std::size_t i = 0; i < n_; ++i) {
      if (r_.keyframes[i].has_top) with_image_.push_back(i);
    }
    for (std::size_t a = 0; a < with_image_.size(); ++a) {
      for (std::size_t b = a + 1; b < with_image_.size() && b <= a + static_cast<std::size_t>(o_.temporal.neighbours);
           ++b)
        pairs_.push_back({with_image_[a], with_image_[b], false, 0.0, o_.temporal});
    }
    matches_.resize(pairs_.size());
  }

  void MatchPairs(std::size_t begin, std::size_t end, SharedProgress& step) {
    arena_.execute([&] {
      tbb::parallel_for(begin, end, [&](std::size_t p) {
        step.ThrowIfCancelled();
        const PairJob& job = pairs_[p];
        matches_[p] = MatchKeyframes(views_[job.a], views_[job.b], rig_, job.options);
        step.Step(std::string(job.loop ? "loop closure " : "matching keyframes ") +
                  std::to_string(views_[job.a].keyframe) + " and " + std::to_string(views_[job.b].keyframe));
      });
    });
  }

  // Each keyframe's DVL record (null: none), for the loop footprints and
  // the mono track check.
  void FindDvlRecords() {
    dvl_of_.assign(n_, nullptr);
    std::unordered_map<std::int64_t, const DvlRecord*> by_keyframe;
    for (const DvlRecord& d : bundle_.dvl) by_keyframe.emplace(d.keyframe, &d);
    for (std::size_t i = 0; i < n_; ++i) {
      const auto d = by_keyframe.find(views_[i].keyframe);
      if (d != by_keyframe.end()) dvl_of_[i] = d->second;
    }
  }

  // Each keyframe's place along the path and its footprint, for the loop search.
  std::vector<LoopKeyframe> LoopKeyframes() const {
    std::vector<LoopKeyframe> lk(n_);
    double path = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      if (i > 0) path += (bundle_.nav[i].x_gv.head<3>() - bundle_.nav[i - 1].x_gv.head<3>()).norm();
      LoopKeyframe& k = lk[i];
      k.x_g_cT = views_[i].x_g_cT;
      k.t = bundle_.nav[i].t;
      k.path = path;
    }
    for (std::size_t w = 0; w < with_image_.size(); ++w) {
      const std::size_t i = with_image_[w];
      LoopKeyframe& k = lk[i];
      k.order = static_cast<int>(w);
      k.footprint = StereoFootprint(views_[i], o_.loops.footprint_points);
      if (k.footprint.empty() && dvl_of_[i]) k.footprint = DvlFootprint(man_, *dvl_of_[i], o_.loops.footprint_points);
      PlaceFootprint(k.footprint, k.x_g_cT);
    }
    return lk;
  }

  // 2b. Loop closures: pairs far apart in nav order whose footprints overlap
  // under the prior, matched with a window and tolerances grown by the
  // navigation drift between them.
  void MatchLoops() {
    const auto l0 = std::chrono::steady_clock::now();
    progress_.Update(0.85, "looking for loop closures");
    const std::vector<LoopKeyframe> lk = LoopKeyframes();
    const std::vector<LoopCandidate> candidates =
        FindLoopCandidates(lk, rig_, o_.temporal.neighbours, o_.loops, &r_.loop_pairs_considered);
    const std::size_t first_loop = pairs_.size();
    for (const LoopCandidate& c : candidates) {
      const double distance = (lk[c.b].x_g_cT.translation() - lk[c.a].x_g_cT.translation()).norm();
      pairs_.push_back({c.a, c.b, true, c.overlap,
                        LoopMatchingOptions(o_.temporal, o_.loops, man_.noise, rig_.top.fx, lk[c.a].footprint,
                                            c.seconds, c.path, distance)});
    }
    matches_.resize(pairs_.size());
    SharedProgress loop_progress(progress_, 0.85, 0.95, static_cast<int>(candidates.size()));
    MatchPairs(first_loop, pairs_.size(), loop_progress);
    r_.loop_pairs_tried = static_cast<int>(candidates.size());
    for (std::size_t p = first_loop; p < pairs_.size(); ++p) r_.loop_pairs_accepted += matches_[p].accepted;
    r_.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - l0).count();
  }

  // The match graph into r_.pairs, the verdicts on the top features, and
  // the links of the accepted pairs, best (smallest descriptor distance) first.
  std::vector<Link> CollectPairs() {
    std::vector<Link> links;
    verdicts_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) verdicts_[i].assign(views_[i].top.size(), MatchVerdict::kUnverified);
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
      const PairMatches& m = matches_[p];
      const PairJob& job = pairs_[p];
      FrontEndPair fp;
      fp.from = views_[job.a].keyframe;
      fp.to = views_[job.b].keyframe;
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
          std::vector<MatchVerdict>& v = verdicts_[ki];
          if (inlier) {
            v[static_cast<std::size_t>(f)] = MatchVerdict::kInlier;
          } else if (v[static_cast<std::size_t>(f)] == MatchVerdict::kUnverified) {
            v[static_cast<std::size_t>(f)] = MatchVerdict::kOutlier;
          }
        }
      }
      r_.pairs.push_back(std::move(fp));
      if (!m.accepted) continue;
      for (const auto& t : m.matches)
        links.push_back({t.distance, static_cast<int>(job.a), t.a, static_cast<int>(job.b), t.b});
    }
    std::stable_sort(links.begin(), links.end(), [](const Link& a, const Link& b) { return a.distance < b.distance; });
    return links;
  }

  // 3. Tracks from the links.
  std::vector<TrackBuilder::Track> BuildTracks(const std::vector<Link>& links) {
    std::vector<int> counts(n_);
    for (std::size_t i = 0; i < n_; ++i) counts[i] = static_cast<int>(views_[i].top.size());
    TrackBuilder builder(counts);
    for (const Link& l : links) builder.Link(l.ka, l.fa, l.kb, l.fb);
    r_.refused_merges = builder.refused();
    return builder.Tracks(o_.tracks.min_keyframes, &r_.dropped_tracks);
  }

  // SIFT's copies of one keypoint (one per dominant orientation) each match
  // on their own: a track whose members are, keyframe by keyframe, at the
  // same positions as an earlier track's is that track again, and dropped.
  // (Linking the copies as one feature instead joins their tracks, and one
  // copy's wrong match then spoils the other's right track: docs/vision.md.)
  void DropDuplicateTracks(std::vector<TrackBuilder::Track>& tracks) {
    std::vector<std::vector<int>> first_copy(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      first_copy[i] = DuplicateKeypoints(views_[i].top.points);
      for (std::size_t f = 0; f < first_copy[i].size(); ++f)
        r_.duplicate_keypoints += first_copy[i][f] != static_cast<int>(f);
    }
    std::set<TrackBuilder::Track> seen;
    std::vector<TrackBuilder::Track> unique;
    unique.reserve(tracks.size());
    for (TrackBuilder::Track& t : tracks) {
      TrackBuilder::Track key = t;
      for (auto& [k, f] : key) f = first_copy[static_cast<std::size_t>(k)][static_cast<std::size_t>(f)];
      if (!seen.insert(std::move(key)).second) {
        ++r_.duplicate_tracks;
        continue;
      }
      unique.push_back(std::move(t));
    }
    tracks = std::move(unique);
  }

  // top feature -> its stereo match (-1: none), per keyframe.
  void FindStereoOfTopFeatures() {
    bottom_of_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      bottom_of_[i].assign(views_[i].top.size(), -1);
      for (std::size_t s = 0; s < views_[i].stereo.size(); ++s)
        bottom_of_[i][static_cast<std::size_t>(views_[i].stereo[s].top)] = static_cast<int>(s);
    }
  }

  // 3b. Sub-pixel refinement of the tracks' top pixels.
  void RefineTracks(const std::vector<TrackBuilder::Track>& tracks) {
    progress_.Update(0.96, "refining the tracks' pixels");
    std::vector<std::vector<Eigen::Vector2d>> points(n_);
    std::vector<Pose> cameras(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      points[i] = views_[i].top.points;
      cameras[i] = views_[i].x_g_cT;
    }
    r_.refinement = RefineTrackPixels(
        tracks, [&](std::size_t k) { return ReadSurveyImage(bundle_, views_[k].keyframe, false); }, cameras, rig_.top,
        points, o_.tracks, o_.threads);
    for (std::size_t i = 0; i < n_; ++i) {
      views_[i].top.points = std::move(points[i]);
      r_.keyframes[i].top_points = views_[i].top.points;  // the tracks' members where they were aligned
    }
  }

  // 3c. The DVL height check of mono tracks (track_check.h): those not kept are dropped.
  void CheckMonoTracks(std::vector<TrackBuilder::Track>& tracks) {
    progress_.Update(0.97, "checking mono tracks against the DVL");
    std::vector<std::vector<char>> has_stereo(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      has_stereo[i].assign(views_[i].top.size(), 0);
      for (std::size_t f = 0; f < bottom_of_[i].size(); ++f) has_stereo[i][f] = bottom_of_[i][f] >= 0;
    }
    std::vector<std::optional<CameraPlane>> planes(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      CameraPlane plane;
      if (dvl_of_[i] && DvlPlane(man_, *dvl_of_[i], plane)) planes[i] = plane;
    }
    r_.track_checks = CheckTrackHeights(tracks, views_, has_stereo, planes, rig_, o_.tracks, o_.threads);
    std::vector<char> keep(tracks.size(), 1);
    for (const TrackCheck& c : r_.track_checks) {
      if (!c.kept) {
        keep[static_cast<std::size_t>(c.track)] = 0;
        ++r_.tracks_failed_check;
      }
    }
    std::vector<TrackBuilder::Track> kept;
    kept.reserve(tracks.size());
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      if (keep[t]) kept.push_back(std::move(tracks[t]));
    }
    tracks = std::move(kept);
  }

  // 4. Observations with global landmark ids (track order), and the
  // keyframes' verdicts and landmark ids for the images view.
  void WriteObservations(const std::vector<TrackBuilder::Track>& tracks) {
    for (std::size_t i = 0; i < n_; ++i) {
      for (FrontEndStereoLink& s : r_.keyframes[i].stereo) s.verdict = verdicts_[i][static_cast<std::size_t>(s.top)];
      r_.keyframes[i].landmark.assign(views_[i].top.size(), -1);
    }
    std::vector<std::tuple<int, std::int64_t, FeatureObservation>> rows;
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      for (const auto& [k, f] : tracks[t]) {
        const std::size_t ki = static_cast<std::size_t>(k);
        FeatureObservation obs;
        obs.keyframe = views_[ki].keyframe;
        obs.landmark = static_cast<std::int64_t>(t);
        obs.top = views_[ki].top.points[static_cast<std::size_t>(f)];
        const int s = bottom_of_[ki][static_cast<std::size_t>(f)];
        if (s >= 0) {
          obs.has_bottom = true;
          obs.bottom = views_[ki].stereo[static_cast<std::size_t>(s)].bottom_uv;
        }
        rows.emplace_back(k, obs.landmark, obs);
        r_.keyframes[ki].landmark[static_cast<std::size_t>(f)] = obs.landmark;
        ++r_.keyframes[ki].tracked;
      }
    }
    std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
      return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b));
    });
    r_.features.reserve(rows.size());
    for (auto& row : rows) r_.features.push_back(std::get<2>(row));
    r_.landmarks = static_cast<int>(tracks.size());
  }

  const SurveyBundle& bundle_;
  const FrontEndOptions& o_;
  Progress& progress_;
  const SurveyManifest& man_;
  const CameraRig& rig_;
  const std::size_t n_;
  FrontEndResult r_;
  FrontEndEvidence evidence_;
  std::vector<KeyframeView> views_;
  std::vector<char> detected_;  // per keyframe: stage 1 done (by the swap probe)
  tbb::task_arena arena_;
  std::vector<std::size_t> with_image_;              // keyframe indices with a top image, nav order
  std::vector<PairJob> pairs_;                       // neighbours, then loop candidates
  std::vector<PairMatches> matches_;                 // per pair
  std::vector<const DvlRecord*> dvl_of_;             // per keyframe (null: no DVL record)
  std::vector<std::vector<MatchVerdict>> verdicts_;  // per keyframe and top feature
  std::vector<std::vector<int>> bottom_of_;          // per keyframe and top feature: its stereo match (-1: none)
};

}  // namespace

FrontEndResult RunFrontEnd(const SurveyBundle& bundle, const FrontEndOptions& o, Progress& progress) {
  o.Check();
  if (!bundle.images || bundle.images->present() == 0) {
    throw InputError({(fs::path(bundle.directory) / "images").string(), 0, 0, ""},
                     "the bundle has no camera images to extract features from");
  }
  return FrontEndRun(bundle, o, progress).Run();
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
