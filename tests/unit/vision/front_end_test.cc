// The front end job on version 2 bundles written to disk: rendered images in
// images/, features.csv written in the version 1 contract and read back by
// the survey reader, tracks checked against the true surface.
#include "vision/front_end.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "base/error.h"
#include "geometry/mesh_io.h"
#include "image/image_file.h"
#include "pipeline/pipeline.h"
#include "results/front_end_files.h"
#include "support/test_files.h"
#include "support/test_meshes.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"
#include "unit/vision/vision_scene.h"

namespace hull {
namespace {
namespace fs = std::filesystem;
using testing::MakeVisionScene;
using testing::ScratchDir;
using testing::VisionScene;
using testing::WriteSceneBundle;

// Checks the tracks against the truth: no keyframe twice in a track, every
// track in >= 2 keyframes, and the share of observations whose true surface
// point lies within 2 cm of their track's (first observation's) point.
double TrackConsistency(const VisionScene& s, const std::vector<FeatureObservation>& features) {
  std::map<std::int64_t, std::size_t> index;
  for (std::size_t k = 0; k < s.nav.size(); ++k) index[s.nav[k].keyframe] = k;
  std::map<std::int64_t, std::vector<const FeatureObservation*>> tracks;
  for (const auto& f : features) tracks[f.landmark].push_back(&f);
  int good = 0, total = 0;
  for (const auto& [id, obs] : tracks) {
    EXPECT_GE(obs.size(), 2u) << "landmark " << id;
    std::set<std::int64_t> keyframes;
    std::optional<Eigen::Vector3d> ref;
    for (const FeatureObservation* o : obs) {
      EXPECT_TRUE(keyframes.insert(o->keyframe).second) << "landmark " << id << " twice in keyframe " << o->keyframe;
      const auto p = s.SurfacePoint(index.at(o->keyframe), o->top);
      if (!p) continue;
      if (!ref) {
        ref = p;
        continue;
      }
      ++total;
      if ((*p - *ref).norm() < 0.02) ++good;
    }
  }
  return total ? static_cast<double>(good) / total : 0.0;
}

TEST(FrontEnd, StereoBundleToFeaturesCsvAndBack) {
  const VisionScene s = MakeVisionScene(true, true, 5);
  const ScratchDir dir("vision_stereo");
  WriteSceneBundle(s, dir.path(), 3);
  SurveyBundle b = ReadSurveyBundle(dir.path());
  ASSERT_TRUE(b.features.empty());
  ASSERT_TRUE(b.images);
  EXPECT_EQ(b.images->dropped, 1);
  FrontEndOptions o;
  CallbackProgress progress;
  FrontEndResult r;
  ASSERT_TRUE(ExtractFeaturesIfNeeded(b, o, progress, &r));
  EXPECT_FALSE(ExtractFeaturesIfNeeded(b, o, progress));  // has features now
  ASSERT_EQ(r.keyframes.size(), 5u);
  EXPECT_FALSE(r.keyframes[3].has_bottom);
  EXPECT_EQ(r.keyframes[3].stereo_matches, 0);
  for (const auto& k : r.keyframes) {
    EXPECT_TRUE(k.has_top);
    EXPECT_GT(k.top_features, 500);
    EXPECT_GT(k.tracked, 100) << "keyframe " << k.keyframe;
  }
  EXPECT_EQ(r.pairs.size(), 7u);  // 5 keyframes, 2 neighbours each
  for (const auto& p : r.pairs) {
    EXPECT_TRUE(p.accepted) << p.from << "-" << p.to << ": " << p.note;
    // Pairs with the keyframe without a bottom image fall back to the essential matrix.
    EXPECT_EQ(p.stereo, p.from != 19 && p.to != 19) << p.from << "-" << p.to;
  }
  EXPECT_GT(r.landmarks, 200);
  EXPECT_GE(TrackConsistency(s, r.features), 0.95);
  int with_bottom = 0;
  for (const auto& f : r.features) with_bottom += f.has_bottom;
  EXPECT_GT(with_bottom, static_cast<int>(r.features.size()) / 2);

  // Written as features.csv and read back by the survey reader unchanged.
  WriteFrontEndResult(r, b.manifest, dir / "features.csv");
  EXPECT_TRUE(fs::exists(dir / "match-graph.csv"));
  const SurveyBundle again = ReadSurveyBundle(dir.path());
  ASSERT_EQ(again.features.size(), r.features.size());
  EXPECT_EQ(again.CountLandmarks(), static_cast<std::size_t>(r.landmarks));
  for (std::size_t i = 0; i < r.features.size(); i += 97) {
    EXPECT_EQ(again.features[i].landmark, r.features[i].landmark);
    EXPECT_EQ(again.features[i].has_bottom, r.features[i].has_bottom);
    EXPECT_NEAR((again.features[i].top - r.features[i].top).norm(), 0, 1e-6);
  }
}

// What the front end returns per keyframe and pair for the GUI's images
// view agrees with its counts and with the observations it wrote.
void ExpectDetailsMatchCounts(const FrontEndResult& r) {
  for (const FrontEndKeyframe& k : r.keyframes) {
    ASSERT_EQ(static_cast<int>(k.top_points.size()), k.top_features) << "keyframe " << k.keyframe;
    ASSERT_EQ(k.top_sizes.size(), k.top_points.size());
    ASSERT_EQ(static_cast<int>(k.bottom_points.size()), k.bottom_features);
    ASSERT_EQ(static_cast<int>(k.stereo.size()), k.stereo_matches);
    ASSERT_EQ(k.landmark.size(), k.top_points.size());
    EXPECT_EQ(static_cast<int>(std::count_if(k.landmark.begin(), k.landmark.end(), [](auto l) { return l >= 0; })),
              k.tracked);
    for (const FrontEndStereoLink& s : k.stereo) {
      ASSERT_GE(s.top, 0);
      ASSERT_LT(s.top, k.top_features);
      ASSERT_GE(s.bottom, 0);
      ASSERT_LT(s.bottom, k.bottom_features);
    }
  }
  for (const FrontEndPair& p : r.pairs) {
    ASSERT_EQ(static_cast<int>(p.matches.size()), p.putative) << p.from << "-" << p.to;
    EXPECT_EQ(static_cast<int>(std::count_if(p.matches.begin(), p.matches.end(), [](auto m) { return m.inlier; })),
              p.inliers)
        << p.from << "-" << p.to;
    const int a = r.KeyframeIndex(p.from), b = r.KeyframeIndex(p.to);
    ASSERT_GE(a, 0);
    ASSERT_GE(b, 0);
    for (const FrontEndMatch& m : p.matches) {
      ASSERT_LT(m.a, r.keyframes[static_cast<std::size_t>(a)].top_features);
      ASSERT_LT(m.b, r.keyframes[static_cast<std::size_t>(b)].top_features);
    }
  }
  // Each observation is the top feature its keyframe lists for that landmark.
  for (const FeatureObservation& f : r.features) {
    const int k = r.KeyframeIndex(f.keyframe);
    ASSERT_GE(k, 0);
    const FrontEndKeyframe& kf = r.keyframes[static_cast<std::size_t>(k)];
    const auto it = std::find(kf.landmark.begin(), kf.landmark.end(), f.landmark);
    ASSERT_NE(it, kf.landmark.end()) << "landmark " << f.landmark << " in keyframe " << f.keyframe;
    EXPECT_EQ(kf.top_points[static_cast<std::size_t>(it - kf.landmark.begin())], f.top);
  }
}

TEST(FrontEnd, ReturnsFeaturesMatchesAndVerdictsPerKeyframe) {
  const VisionScene s = MakeVisionScene(true, true, 4);
  const ScratchDir dir("vision_details");
  WriteSceneBundle(s, dir.path());
  const SurveyBundle b = ReadSurveyBundle(dir.path());
  NullProgress progress;
  const FrontEndResult r = RunFrontEnd(b, FrontEndOptions{}, progress);
  ExpectDetailsMatchCounts(r);
  int inliers = 0, unverified = 0;
  for (const FrontEndKeyframe& k : r.keyframes) {
    for (const FrontEndStereoLink& l : k.stereo) {
      inliers += l.verdict == MatchVerdict::kInlier;
      unverified += l.verdict == MatchVerdict::kUnverified;
    }
  }
  EXPECT_GT(inliers, 100);
  EXPECT_GT(unverified, 0);  // the first keyframe's features leaving the view
  EXPECT_EQ(r.KeyframeIndex(s.nav[2].keyframe), 2);
  EXPECT_EQ(r.KeyframeIndex(-5), -1);
  // A strict RANSAC threshold leaves outliers among the putative matches.
  FrontEndOptions strict;
  strict.temporal.ransac_threshold = 0.3;
  const FrontEndResult t = RunFrontEnd(b, strict, progress);
  ExpectDetailsMatchCounts(t);
  int rejected = 0;
  for (const FrontEndPair& p : t.pairs) {
    for (const FrontEndMatch& m : p.matches) rejected += !m.inlier;
  }
  EXPECT_GT(rejected, 0);
}

TEST(FrontEnd, MonoBundle) {
  const VisionScene s = MakeVisionScene(false, true, 4);
  const ScratchDir dir("vision_mono");
  WriteSceneBundle(s, dir.path());
  const SurveyBundle b = ReadSurveyBundle(dir.path());
  FrontEndOptions o;
  o.threads = 1;
  NullProgress progress;
  const FrontEndResult r = RunFrontEnd(b, o, progress);
  EXPECT_GT(r.landmarks, 200);
  for (const auto& p : r.pairs) EXPECT_TRUE(p.accepted && !p.stereo) << p.from << "-" << p.to << ": " << p.note;
  for (const auto& f : r.features) EXPECT_FALSE(f.has_bottom);
  EXPECT_GE(TrackConsistency(s, r.features), 0.95);
  ExpectDetailsMatchCounts(r);
}

TEST(FrontEnd, RefusesBundlesWithoutImagesAndStopsOnCancel) {
  const VisionScene s = MakeVisionScene(false, false, 2);
  const ScratchDir dir("vision_bad");
  WriteSceneBundle(s, dir.path());
  SurveyBundle b = ReadSurveyBundle(dir.path());
  CallbackProgress cancel;
  cancel.RequestCancel();
  EXPECT_THROW(RunFrontEnd(b, FrontEndOptions{}, cancel), Cancelled);
  // A truncated image: an InputError naming the file.
  const std::string bad = dir / ("images/" + SurveyImageName(s.nav[1].keyframe, false));
  fs::resize_file(bad, fs::file_size(bad) / 2);
  NullProgress progress;
  try {
    RunFrontEnd(b, FrontEndOptions{}, progress);
    ADD_FAILURE() << "a truncated image was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  b.images.reset();
  EXPECT_THROW(RunFrontEnd(b, FrontEndOptions{}, progress), InputError);
  FrontEndOptions o;
  o.temporal.ratio = 0;
  EXPECT_THROW(RunFrontEnd(b, o, progress), OptionError);
}

}  // namespace
}  // namespace hull

namespace hull {
namespace {
using testing::MakeVisionScene;
using testing::ScratchDir;
using testing::VisionScene;
using testing::WriteSceneBundle;

TEST(FrontEnd, PipelineInputsFromImagesWhenThereIsNoFeaturesCsv) {
  const VisionScene s = MakeVisionScene(false, true, 3);
  const ScratchDir dir("vision_pipeline");
  WriteSceneBundle(s, dir.path());
  const std::string mesh = dir / "hull.ply";
  SaveMesh(test::MakeBox({-1, -1, -1}, {1, 1, 1}), mesh);
  CallbackProgress progress;
  const PipelineInputs in = LoadPipelineInputs(dir.path(), mesh, 1.0, &progress);
  ASSERT_TRUE(in.front_end);
  EXPECT_GT(in.front_end->landmarks, 100);
  EXPECT_EQ(in.bundle.features.size(), in.front_end->features.size());
  // With a features.csv the bundle's own observations are used.
  WriteFrontEndResult(*in.front_end, in.bundle.manifest, dir / "features.csv");
  const PipelineInputs again = LoadPipelineInputs(dir.path(), mesh);
  EXPECT_FALSE(again.front_end);
  EXPECT_EQ(again.bundle.features.size(), in.bundle.features.size());
}

}  // namespace
}  // namespace hull
