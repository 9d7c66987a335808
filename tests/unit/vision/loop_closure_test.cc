// Loop closures: footprints, the candidate search on a lawnmower, the
// drift-grown matching options, and the front end on a two-track survey
// rendered in code (vision_scene.h) whose revisits are verified against the
// true correspondences.
#include "vision/loop_closure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "results/front_end_files.h"
#include "support/test_files.h"
#include "survey/survey_io.h"
#include "unit/vision/vision_scene.h"
#include "vision/camera_geometry.h"
#include "vision/front_end.h"

namespace hull {
namespace {

// A manifest whose top camera is 640 x 512 with f = 560 px.
SurveyManifest SmallCamera() {
  SurveyManifest man;
  man.camera.width = 640;
  man.camera.height = 512;
  man.camera.top = PinholeIntrinsics{560, 560, 319.5, 255.5};
  return man;
}
namespace fs = std::filesystem;
using testing::MakeTwoTrackScene;
using testing::ScratchDir;
using testing::VisionScene;
using testing::WriteSceneBundle;

constexpr double kDeg = M_PI / 180.0;

// DVL ranges to the plane z = depth of the top camera frame.
DvlRecord DvlToPlane(const SurveyManifest& man, double depth) {
  const Pose x_c_d = Pose::FromVector(man.camera.servo_to_top).Inverse() * Pose::FromVector(man.servo_to_dvl);
  DvlRecord d;
  for (int b = 0; b < 4; ++b) {
    const Eigen::Vector3d dir = x_c_d.Rotate(man.BeamDirection(b));
    d.range[static_cast<std::size_t>(b)] = (depth - x_c_d.translation().z()) / dir.z();
  }
  return d;
}

TEST(LoopClosure, DvlFootprintLiesOnThePlaneOfTheReturns) {
  const SurveyManifest man = SmallCamera();
  const KeyframeFootprint f = DvlFootprint(man, DvlToPlane(man, 1.5), 100);
  ASSERT_EQ(f.source, KeyframeFootprint::Source::kDvl);
  ASSERT_GE(f.points.size(), 90u);
  for (const auto& p : f.points) {
    EXPECT_NEAR(p.z(), 1.5, 1e-9);
    EXPECT_TRUE(man.camera.InImage(man.camera.top.Project(p)));
  }
  EXPECT_NEAR(f.depth, 1.5, 1e-9);
  EXPECT_NEAR(f.min_depth, 1.5, 1e-9);
  EXPECT_NEAR(f.max_depth, 1.5, 1e-9);
  // One return: the fronto-parallel plane at its depth; none: no footprint.
  DvlRecord one = DvlToPlane(man, 2.0);
  one.range[1] = one.range[2] = one.range[3] = kNoReturn;
  const KeyframeFootprint g = DvlFootprint(man, one, 100);
  ASSERT_FALSE(g.empty());
  EXPECT_NEAR(g.depth, 2.0, 1e-9);
  EXPECT_TRUE(DvlFootprint(man, DvlRecord{}, 100).empty());
  // A footprint seen from itself is all in view; moved sideways by its
  // width, none of it.
  KeyframeFootprint placed = f;
  PlaceFootprint(placed, Pose());
  EXPECT_NEAR(placed.centre_g.z(), 1.5, 1e-9);
  EXPECT_GT(placed.radius, 0.8);  // half the diagonal of a 1.71 x 1.37 m footprint: 1.10 m (grid centres)
  EXPECT_LT(placed.radius, 1.1);
  EXPECT_DOUBLE_EQ(FootprintShareInView(f, Pose(), Pose(), man.camera), 1.0);
  EXPECT_DOUBLE_EQ(FootprintShareInView(f, Pose(), Pose::FromXyzRpy(1.8, 0, 0, 0, 0, 0), man.camera), 0.0);
  EXPECT_NEAR(FootprintShareInView(f, Pose(), Pose::FromXyzRpy(0.857, 0, 0, 0, 0, 0), man.camera), 0.5, 0.06);
}

// A lawnmower of `tracks` tracks of `per_track` keyframes (0.3 m apart,
// tracks 0.6 m apart, back and forth, one transit keyframe between tracks)
// under a camera looking up at a plane 1.5 m away.
std::vector<LoopKeyframe> Lawnmower(const SurveyManifest& man, int tracks, int per_track, std::vector<int>* track_of) {
  const KeyframeFootprint f = DvlFootprint(man, DvlToPlane(man, 1.5), 100);
  std::vector<LoopKeyframe> out;
  Eigen::Vector3d last(0, 0, 0);
  double path = 0;
  for (int t = 0; t < tracks; ++t) {
    for (int i = -1; i < per_track; ++i) {
      if (i < 0 && t == 0) continue;
      // i = -1: the transit keyframe halfway to this track.
      const double x = 0.3 * (t % 2 ? per_track - 1 - std::max(i, 0) : std::max(i, 0));
      const double y = i < 0 ? 0.6 * t - 0.3 : 0.6 * t;
      LoopKeyframe k;
      k.x_g_cT = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(x, y, 0));
      path += (k.x_g_cT.translation() - last).norm();
      last = k.x_g_cT.translation();
      k.path = path;
      k.t = path / 0.25;
      k.order = static_cast<int>(out.size());
      k.footprint = f;
      PlaceFootprint(k.footprint, k.x_g_cT);
      out.push_back(k);
      track_of->push_back(i < 0 ? -1 : t);
    }
  }
  return out;
}

TEST(LoopClosure, CandidatesAreOverlappingKeyframesOfOtherTracks) {
  const SurveyManifest man = SmallCamera();
  std::vector<int> track;
  const std::vector<LoopKeyframe> kf = Lawnmower(man, 3, 10, &track);
  LoopOptions o;
  std::size_t considered = 0;
  const auto c = FindLoopCandidates(kf, man.camera, 2, o, &considered);
  ASSERT_FALSE(c.empty());
  EXPECT_GT(considered, c.size());
  std::map<std::size_t, int> per_keyframe;
  std::set<std::pair<int, int>> track_pairs;
  for (const LoopCandidate& x : c) {
    EXPECT_LT(x.a, x.b);
    EXPECT_GT(kf[x.b].order - kf[x.a].order, 2);  // neighbours are matched anyway
    // Never the next keyframes along a track: the path between them is long.
    EXPECT_GE(x.path, 2 * (kf[x.b].x_g_cT.translation() - kf[x.a].x_g_cT.translation()).norm());
    EXPECT_NE(track[x.a], track[x.b]) << x.a << "-" << x.b;
    EXPECT_GE(x.overlap, o.min_overlap);
    // The overlap is the smaller of both ways.
    EXPECT_DOUBLE_EQ(x.overlap,
                     std::min(FootprintShareInView(kf[x.a].footprint, kf[x.a].x_g_cT, kf[x.b].x_g_cT, man.camera),
                              FootprintShareInView(kf[x.b].footprint, kf[x.b].x_g_cT, kf[x.a].x_g_cT, man.camera)));
    ++per_keyframe[x.a];
    ++per_keyframe[x.b];
    track_pairs.insert({track[x.a], track[x.b]});
  }
  // Adjacent tracks (0.6 m apart on a 1.37 m wide footprint) overlap;
  // tracks 1.2 m apart overlap by 12 %, too little: those far pairs are not tried.
  EXPECT_TRUE(track_pairs.count({0, 1}));
  EXPECT_TRUE(track_pairs.count({1, 2}));
  EXPECT_FALSE(track_pairs.count({0, 2}));
  // The keyframe across from keyframe 4 of the first track is a candidate.
  const std::size_t k4 = 4, across = 10 + 1 + (10 - 1 - 4);  // track 1 runs back
  ASSERT_EQ(track[across], 1);
  EXPECT_NEAR(kf[across].x_g_cT.translation().x(), kf[k4].x_g_cT.translation().x(), 1e-12);
  EXPECT_TRUE(std::any_of(c.begin(), c.end(), [&](const LoopCandidate& x) { return x.a == k4 && x.b == across; }));
  // At most `candidates` per keyframe of its own choosing: at most 2 K
  // altogether (each pair is some keyframe's choice), and fewer with K = 1.
  EXPECT_LE(c.size(), static_cast<std::size_t>(o.candidates) * kf.size());
  LoopOptions one = o;
  one.candidates = 1;
  const auto c1 = FindLoopCandidates(kf, man.camera, 2, one);
  EXPECT_LT(c1.size(), c.size());
  EXPECT_LE(c1.size(), kf.size());
  for (const LoopCandidate& x : c1) {
    EXPECT_TRUE(std::any_of(c.begin(), c.end(), [&](const LoopCandidate& y) { return y.a == x.a && y.b == x.b; }));
  }
  // A keyframe without a footprint takes no part; cameras facing apart neither.
  std::vector<LoopKeyframe> some = kf;
  some[across].footprint = KeyframeFootprint{};
  for (const LoopCandidate& x : FindLoopCandidates(some, man.camera, 2, o)) {
    EXPECT_NE(x.a, across);
    EXPECT_NE(x.b, across);
  }
  some = kf;
  some[across].x_g_cT = some[across].x_g_cT * Pose::FromXyzRpy(0, 0, 0, 60 * kDeg, 0, 0);
  for (const LoopCandidate& x : FindLoopCandidates(some, man.camera, 2, o)) EXPECT_NE(x.b, across);
  LoopOptions bad = o;
  bad.min_overlap = 0;
  EXPECT_THROW(FindLoopCandidates(kf, man.camera, 2, bad), OptionError);
}

TEST(LoopClosure, WindowAndTolerancesGrowWithTheDrift) {
  TemporalOptions base;
  LoopOptions loop;
  NoiseModel noise;  // 0.005 m/s, 0.000388 rad/s
  KeyframeFootprint f;
  f.points = {{0, 0, 1.2}, {0, 0, 1.5}, {0, 0, 1.8}};
  f.depth = 1.5;
  f.min_depth = 1.2;
  f.max_depth = 1.8;
  // No time between them: the neighbours' options, but the loop's inlier count.
  TemporalOptions same = LoopMatchingOptions(base, loop, noise, 575, f, 0, 0, 1);
  EXPECT_DOUBLE_EQ(same.window, base.window);
  EXPECT_DOUBLE_EQ(same.max_translation_error, base.max_translation_error);
  EXPECT_DOUBLE_EQ(same.max_rotation_error_deg, base.max_rotation_error_deg);
  EXPECT_EQ(same.min_inliers, loop.min_inliers);
  // 40 s and 10 m: rotation 0.01552 rad, position 0.2 + 0.0776 m.
  const TemporalOptions t = LoopMatchingOptions(base, loop, noise, 575, f, 40, 10, 0.8);
  const double rot = 0.000388 * 40, pos = 0.005 * 40 + 0.5 * rot * 10;
  EXPECT_NEAR(t.window, base.window + 575 * (pos / 1.5 + rot), 1e-9);
  EXPECT_NEAR(t.max_translation_error, base.max_translation_error + pos, 1e-12);
  EXPECT_NEAR(t.max_rotation_error_deg, base.max_rotation_error_deg + rot / kDeg, 1e-9);
  EXPECT_NEAR(t.max_direction_error_deg, base.max_direction_error_deg + std::atan(pos / 0.8) / kDeg, 1e-9);
  // The mono search segment: the footprint's depths / 1.5 .. x 1.5.
  EXPECT_NEAR(t.mono_min_depth, 0.8, 1e-12);
  EXPECT_NEAR(t.mono_max_depth, 2.7, 1e-12);
  EXPECT_DOUBLE_EQ(LoopMatchingOptions(base, loop, noise, 575, KeyframeFootprint{}, 40, 10, 0.8).mono_max_depth,
                   base.mono_max_depth);
  // Capped, and scaled by drift_sigmas.
  EXPECT_DOUBLE_EQ(LoopMatchingOptions(base, loop, noise, 575, f, 400, 100, 0.8).window, loop.max_window);
  LoopOptions two = loop;
  two.drift_sigmas = 2;
  EXPECT_NEAR(LoopMatchingOptions(base, two, noise, 575, f, 40, 10, 0.8).max_translation_error,
              base.max_translation_error + 2 * pos, 1e-12);
}

// True correspondences of the loop pairs' inliers (within 2 px).
struct LoopTruth {
  int tried = 0, accepted = 0, inliers = 0, true_inliers = 0;
};

LoopTruth CheckLoops(const VisionScene& s, const FrontEndResult& r) {
  LoopTruth t;
  for (const FrontEndPair& p : r.pairs) {
    if (!p.loop) continue;
    ++t.tried;
    if (!p.accepted) continue;
    ++t.accepted;
    const std::size_t a = static_cast<std::size_t>(r.KeyframeIndex(p.from));
    const std::size_t b = static_cast<std::size_t>(r.KeyframeIndex(p.to));
    for (const FrontEndMatch& m : p.matches) {
      if (!m.inlier) continue;
      ++t.inliers;
      const auto x = s.Transfer(a, r.keyframes[a].top_points[static_cast<std::size_t>(m.a)], b);
      if (x && (*x - r.keyframes[b].top_points[static_cast<std::size_t>(m.b)]).norm() < 2.0) ++t.true_inliers;
    }
  }
  return t;
}

// Share of keyframe a's top features whose true surface point is in b's image.
double TrueOverlap(const VisionScene& s, const FrontEndResult& r, std::size_t a, std::size_t b) {
  int in = 0, all = 0;
  for (const auto& uv : r.keyframes[a].top_points) {
    const auto x = s.Transfer(a, uv, b);
    ++all;
    in += x && s.manifest.camera.InImage(*x);
  }
  return all ? static_cast<double>(in) / all : 0.0;
}

// The two-track survey written once per test program; each case runs the
// front end at most twice (the sanitizer build is slow).
class TwoTrackSurvey : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new VisionScene(MakeTwoTrackScene(true));
    dir_ = new ScratchDir("vision_loops");
    WriteSceneBundle(*scene_, dir_->path());
    bundle_ = new SurveyBundle(ReadSurveyBundle(dir_->path()));
  }
  static void TearDownTestSuite() {
    delete bundle_;
    delete dir_;
    delete scene_;
  }
  static FrontEndResult Run(const FrontEndOptions& o) {
    NullProgress progress;
    return RunFrontEnd(*bundle_, o, progress);
  }
  static int Keyframes() { return static_cast<int>(scene_->nav.size()); }
  // Landmarks seen from the first two keyframes and from the last two: 0.6 m
  // across, 1.8 m or more from the turn, so no chain of neighbours through
  // the turn links them; only loop closures do.
  static int FarEnds(const FrontEndResult& x) {
    const int n = Keyframes();
    std::map<std::int64_t, std::set<int>> ends;
    for (const FeatureObservation& f : x.features) {
      const int k = x.KeyframeIndex(f.keyframe);
      if (k < 2 || k >= n - 2) ends[f.landmark].insert(k < 2 ? 0 : 1);
    }
    return static_cast<int>(
        std::count_if(ends.begin(), ends.end(), [](const auto& e) { return e.second.size() == 2; }));
  }
  static VisionScene* scene_;
  static ScratchDir* dir_;
  static SurveyBundle* bundle_;
};
VisionScene* TwoTrackSurvey::scene_ = nullptr;
ScratchDir* TwoTrackSurvey::dir_ = nullptr;
SurveyBundle* TwoTrackSurvey::bundle_ = nullptr;

TEST_F(TwoTrackSurvey, RevisitsAreFoundVerifiedAndMerged) {
  const VisionScene& s = *scene_;
  FrontEndOptions o;
  o.threads = 2;
  const FrontEndResult r = Run(o);
  const LoopTruth t = CheckLoops(s, r);
  EXPECT_EQ(t.tried, r.loop_pairs_tried);
  EXPECT_EQ(t.accepted, r.loop_pairs_accepted);
  EXPECT_GE(t.tried, 3);
  EXPECT_GE(t.accepted, 3);
  EXPECT_GT(t.inliers, 100);
  EXPECT_GE(t.true_inliers, 0.95 * t.inliers) << t.true_inliers << " of " << t.inliers;
  const int n = Keyframes();
  for (const FrontEndPair& p : r.pairs) {
    const std::size_t a = static_cast<std::size_t>(r.KeyframeIndex(p.from));
    const std::size_t c = static_cast<std::size_t>(r.KeyframeIndex(p.to));
    if (!p.loop) {
      EXPECT_TRUE(p.accepted) << p.from << "-" << p.to << ": " << p.note;
      EXPECT_DOUBLE_EQ(p.window, o.temporal.window);
      continue;
    }
    // Loop pairs are across the tracks, overlap in truth, and were searched
    // with a window grown by the drift.
    EXPECT_LT(a, static_cast<std::size_t>(n / 2)) << p.from << "-" << p.to;
    EXPECT_GE(c, static_cast<std::size_t>(n / 2)) << p.from << "-" << p.to;
    EXPECT_GT(TrueOverlap(s, r, a, c), 0.2) << p.from << "-" << p.to;
    EXPECT_GT(p.window, o.temporal.window);
    EXPECT_GE(p.overlap, o.loops.min_overlap);
  }
  // A far pair -- the first keyframe and the one 1.2 m along and 0.6 m
  // across, far apart along the way (3.6 m), whose footprints barely
  // overlap -- is not tried.
  const std::size_t far = static_cast<std::size_t>(n) - 5;
  EXPECT_NEAR(s.truth[far].x_gv[0] - s.truth[0].x_gv[0], 1.2, 1e-9);
  EXPECT_LT(TrueOverlap(s, r, 0, far), 0.25);
  EXPECT_FALSE(std::any_of(r.pairs.begin(), r.pairs.end(), [&](const FrontEndPair& p) {
    return p.from == s.nav[0].keyframe && p.to == s.nav[far].keyframe;
  }));
  // Tracks now run across both survey tracks, never twice in one image.
  std::map<std::int64_t, std::set<std::int64_t>> seen;
  for (const FeatureObservation& f : r.features)
    EXPECT_TRUE(seen[f.landmark].insert(f.keyframe).second) << "landmark " << f.landmark << " twice in " << f.keyframe;
  EXPECT_GT(FarEnds(r), 100);
  std::printf("loop pairs: %d tried, %d accepted, %d of %d inliers true; landmarks seen from both far ends: %d\n",
              t.tried, t.accepted, t.true_inliers, t.inliers, FarEnds(r));

  // match-graph.csv marks the loop pairs.
  WriteFrontEndResult(r, bundle_->manifest, *dir_ / "out/features.csv");
  std::ifstream in(*dir_ / "out/match-graph.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "from,to,method,putative,inliers,accepted,note,kind,overlap,window");
  int loop_rows = 0, rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    loop_rows += line.find(",loop,") != std::string::npos;
  }
  EXPECT_EQ(rows, static_cast<int>(r.pairs.size()));
  EXPECT_EQ(loop_rows, r.loop_pairs_tried);
}

TEST_F(TwoTrackSurvey, WithoutLoopsOrTheGrownWindowTheTracksStayApart) {
  // Without loop closures none is tried and no landmark links the far ends.
  FrontEndOptions off;
  off.loops.enabled = false;
  const FrontEndResult plain = Run(off);
  EXPECT_EQ(plain.loop_pairs_tried, 0);
  EXPECT_TRUE(std::none_of(plain.pairs.begin(), plain.pairs.end(), [](const FrontEndPair& p) { return p.loop; }));
  EXPECT_EQ(FarEnds(plain), 0);
  // Without the drift-grown window the revisits (decimetres off in the
  // prior) mostly fall outside the search: the same candidates are tried,
  // fewer than the 3 of the default accepted.
  FrontEndOptions fixed;
  fixed.loops.drift_sigmas = 0;
  const FrontEndResult narrow = Run(fixed);
  const LoopTruth nt = CheckLoops(*scene_, narrow);
  EXPECT_GE(nt.tried, 3);
  EXPECT_LT(nt.accepted, 3);
  std::printf("without the grown window: %d of %d loop pairs accepted\n", nt.accepted, nt.tried);
}

TEST_F(TwoTrackSurvey, SameResultOnOneThreadAsOnTwo) {
  FrontEndOptions o;
  o.threads = 2;
  const FrontEndResult r = Run(o);
  o.threads = 1;
  const FrontEndResult one = Run(o);
  EXPECT_GT(r.loop_pairs_accepted, 0);
  ASSERT_EQ(one.features.size(), r.features.size());
  for (std::size_t i = 0; i < r.features.size(); ++i) {
    ASSERT_EQ(one.features[i].keyframe, r.features[i].keyframe) << i;
    ASSERT_EQ(one.features[i].landmark, r.features[i].landmark) << i;
    ASSERT_EQ(one.features[i].top, r.features[i].top) << i;
  }
  ASSERT_EQ(one.pairs.size(), r.pairs.size());
  for (std::size_t i = 0; i < r.pairs.size(); ++i) {
    EXPECT_EQ(one.pairs[i].from, r.pairs[i].from);
    EXPECT_EQ(one.pairs[i].to, r.pairs[i].to);
    EXPECT_EQ(one.pairs[i].loop, r.pairs[i].loop);
    EXPECT_EQ(one.pairs[i].inliers, r.pairs[i].inliers);
  }
}

}  // namespace
}  // namespace hull
