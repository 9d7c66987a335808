// Sub-pixel refinement of feature tracks and SIFT's duplicate keypoints
// (vision/track_refinement.h, vision/patch_alignment.h) on surfaces rendered
// in code, whose true correspondences are known.
#include "vision/track_refinement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <opencv2/core.hpp>
#include <set>

#include "support/test_files.h"
#include "survey/survey_io.h"
#include "unit/vision/vision_scene.h"
#include "vision/camera_geometry.h"
#include "vision/feature_detection.h"
#include "vision/front_end.h"
#include "vision/patch_alignment.h"

namespace hull {
namespace {
using testing::MakeVisionScene;
using testing::VisionScene;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[v.size() / 2];
}

double Quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

TEST(PatchAlignment, InfiniteHomographyWarpOfARollIsTheImageRotation) {
  const Eigen::Matrix3d K = CameraMatrix(PinholeIntrinsics{560, 560, 319.5, 255.5});
  // Camera b rolled by 180 degrees about the optical axis: the image turns over.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix2d w = InfiniteHomographyWarp(K, K, R, Eigen::Vector2d(319.5, 255.5));
  EXPECT_TRUE(w.isApprox(-Eigen::Matrix2d::Identity(), 1e-9)) << w;
  EXPECT_TRUE(InfiniteHomographyWarp(K, K, Eigen::Matrix3d::Identity(), Eigen::Vector2d(10, 400))
                  .isApprox(Eigen::Matrix2d::Identity(), 1e-12));
}

TEST(PatchAlignment, FindsTheReferencePointUnderGainAndRotation) {
  const VisionScene s = MakeVisionScene(false, false, 2);
  const cv::Mat a = s.Render(0);
  cv::Mat b = s.Render(1);
  b.convertTo(b, CV_8U, 0.7, 20);  // another strobe distance: gain and bias
  const GradientImage ga = MakeGradientImage(a), gb = MakeGradientImage(b);
  // A rotated copy of b (180 degrees): the prior's warp starts the alignment.
  cv::Mat b180;
  cv::rotate(b, b180, cv::ROTATE_180);
  const GradientImage gr = MakeGradientImage(b180);
  const Eigen::Vector2d centre(b.cols - 1, b.rows - 1);  // b180(x) = b(centre - x)
  const ImageFeatures f = DetectFeatures(a, DetectionOptions{});
  std::vector<double> err, err180;
  for (std::size_t i = 0; i < f.size(); i += 5) {
    const auto truth = s.Transfer(0, f.points[i], 1);
    std::vector<float> patch;
    if (!truth || !SamplePatch(ga.image, f.points[i], 7, patch)) continue;
    const Eigen::Vector2d start = *truth + Eigen::Vector2d(1.2, -0.8);
    const PatchAlignment al = AlignPatch(patch, 7, gb, start, Eigen::Matrix2d::Identity(), false);
    const PatchAlignment al180 = AlignPatch(patch, 7, gr, centre - start, -Eigen::Matrix2d::Identity(), false);
    if (!al.converged || !al180.converged) continue;
    err.push_back((al.point - *truth).norm());
    err180.push_back((al180.point - (centre - *truth)).norm());
    EXPECT_GT(al.ncc, 0.8);
  }
  ASSERT_GT(err.size(), 100u);
  // Sensor noise (2 grey levels) leaves about 0.1 px; the start was 1.44 px off.
  EXPECT_LT(Median(err), 0.15);
  EXPECT_LT(Quantile(err, 0.9), 0.3);
  EXPECT_LT(Median(err180), 0.15);
}

// The cause of the mono box's max (docs/vision.md): two-view tracks whose
// second pixel is off by SIFT's sub-pixel noise along the epipolar line
// triangulate centimetres off the surface; aligned with the first member's
// patch they meet at its point.
TEST(TrackRefinement, TwoViewTracksWithPlantedSubPixelErrorsMeetAtTheSurface) {
  const VisionScene s = MakeVisionScene(false, false, 2);
  const std::vector<cv::Mat> images{s.Render(0), s.Render(1)};
  const ImageFeatures f = DetectFeatures(images[0], DetectionOptions{});
  std::vector<std::vector<Eigen::Vector2d>> points(2);
  std::vector<TrackBuilder::Track> tracks;
  std::vector<Eigen::Vector2d> truth;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const auto t = s.Transfer(0, f.points[i], 1);
    if (!t || t->x() < 10 || t->y() < 10 || t->x() > 630 || t->y() > 502) continue;
    const int id = static_cast<int>(points[0].size());
    points[0].push_back(f.points[i]);
    // 1.5 px along the motion (the epipolar line), alternating in sign,
    // plus 0.3 px across it.
    const Eigen::Vector2d along = (*t - f.points[i]).normalized();
    const Eigen::Vector2d across(-along.y(), along.x());
    points[1].push_back(*t + (id % 2 ? 1.5 : -1.5) * along + 0.3 * across);
    truth.push_back(*t);
    tracks.push_back({{0, id}, {1, id}});
  }
  ASSERT_GT(tracks.size(), 200u);
  const Pose c0 = s.TruePose(0), c1 = s.TruePose(1);
  const auto depth_errors = [&](const std::vector<std::vector<Eigen::Vector2d>>& p) {
    std::vector<double> e;
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      const Eigen::Vector3d X =
          TriangulateDlt(ProjectionMatrix(s.K(), c0), ProjectionMatrix(s.K(), c1), p[0][t], p[1][t]);
      e.push_back((X - *s.SurfacePoint(0, p[0][t])).norm());
    }
    return e;
  };
  const std::vector<double> before = depth_errors(points);
  EXPECT_GT(Median(before), 0.02);  // the planted case: centimetres at 1.5 m over 0.15 m

  const std::vector<Eigen::Vector2d> references = points[0];
  TrackOptions o;
  const TrackRefinementStats stats = RefineTrackPixels(
      tracks, [&](std::size_t k) { return images[k]; },
      {CameraPoseFromNav(s.manifest, s.nav[0]), CameraPoseFromNav(s.manifest, s.nav[1])}, s.manifest.camera.top, points,
      o, 1);
  EXPECT_EQ(stats.members, static_cast<int>(tracks.size()));
  EXPECT_GE(stats.refined, static_cast<int>(0.95 * static_cast<double>(tracks.size())));
  std::vector<double> pixel;
  for (std::size_t t = 0; t < tracks.size(); ++t) pixel.push_back((points[1][t] - truth[t]).norm());
  EXPECT_LT(Median(pixel), 0.15);
  EXPECT_LT(Quantile(pixel, 0.95), 0.35);
  const std::vector<double> after = depth_errors(points);
  EXPECT_LT(Median(after), 0.003);
  EXPECT_LT(Quantile(after, 0.95), 0.008);
  EXPECT_EQ(points[0], references);  // the references are not moved
}

TEST(TrackRefinement, KeepsTheDetectorsPixelWhenThePatchesDoNotMatch) {
  const VisionScene s = MakeVisionScene(false, false, 2);
  const std::vector<cv::Mat> images{s.Render(0), s.Render(1)};
  const ImageFeatures f = DetectFeatures(images[0], DetectionOptions{});
  std::vector<std::vector<Eigen::Vector2d>> points(2);
  std::vector<TrackBuilder::Track> tracks;
  for (std::size_t i = 0; i < f.size() && tracks.size() < 200; ++i) {
    const auto t = s.Transfer(0, f.points[i], 1);
    if (!t || t->x() < 60 || t->y() < 60 || t->x() > 580 || t->y() > 452) continue;
    const int id = static_cast<int>(points[0].size());
    points[0].push_back(f.points[i]);
    points[1].push_back(*t + Eigen::Vector2d(25, 17));  // a wrong match: other texture
    tracks.push_back({{0, id}, {1, id}});
  }
  const std::vector<Eigen::Vector2d> wrong = points[1];
  TrackOptions o;
  const TrackRefinementStats stats = RefineTrackPixels(
      tracks, [&](std::size_t k) { return images[k]; },
      {CameraPoseFromNav(s.manifest, s.nav[0]), CameraPoseFromNav(s.manifest, s.nav[1])}, s.manifest.camera.top, points,
      o, 1);
  // Nearly all kept; none pulled more than the shift limit.
  EXPECT_GE(stats.kept, static_cast<int>(0.9 * static_cast<double>(tracks.size())));
  for (std::size_t t = 0; t < tracks.size(); ++t) EXPECT_LE((points[1][t] - wrong[t]).norm(), o.refine_max_shift);
}

TEST(TrackRefinement, DuplicateKeypointsMapToTheFirstAtTheirPosition) {
  const std::vector<Eigen::Vector2d> p{{1, 2}, {3, 4}, {1, 2}, {1, 2.0001}, {3, 4}};
  EXPECT_EQ(DuplicateKeypoints(p), (std::vector<int>{0, 1, 0, 3, 1}));
  EXPECT_TRUE(DuplicateKeypoints({}).empty());
}

// SIFT repeats a keypoint per dominant orientation; each copy used to make
// its own track, and where both copies matched alike two landmarks had the
// same pixels in every keyframe (one point counted twice).
TEST(TrackRefinement, FrontEndDropsRepeatedTracksAndAlignsTheMembers) {
  const VisionScene s = MakeVisionScene(false, true, 4);
  const testing::ScratchDir dir("vision_refine");
  testing::WriteSceneBundle(s, dir.path());
  const SurveyBundle b = ReadSurveyBundle(dir.path());
  FrontEndOptions o;
  o.threads = 1;
  NullProgress progress;
  const FrontEndResult r = RunFrontEnd(b, o, progress);
  EXPECT_GT(r.duplicate_keypoints, 50);
  EXPECT_GT(r.duplicate_tracks, 10);
  // No two tracks at the same pixels in every keyframe (copies of one
  // track are aligned alike, so they stay at the same pixels).
  std::map<std::int64_t, std::set<std::pair<std::int64_t, std::pair<double, double>>>> tracks;
  for (const FrontEndKeyframe& k : r.keyframes) {
    for (std::size_t f = 0; f < k.landmark.size(); ++f) {
      if (k.landmark[f] < 0) continue;
      const Eigen::Vector2d& p = k.top_points[f];
      tracks[k.landmark[f]].insert({k.keyframe, {p.x(), p.y()}});
    }
  }
  std::set<std::set<std::pair<std::int64_t, std::pair<double, double>>>> distinct;
  for (const auto& [id, t] : tracks) EXPECT_TRUE(distinct.insert(t).second) << "landmark " << id << " repeats a track";
  EXPECT_GT(r.refinement.refined, 0.9 * r.refinement.members);

  // The members against the truth: where the first member's surface point
  // appears in their keyframe, with and without the refinement.
  auto member_errors = [&](const FrontEndResult& res) {
    std::map<std::int64_t, std::size_t> index;
    for (std::size_t k = 0; k < s.nav.size(); ++k) index[s.nav[k].keyframe] = k;
    std::map<std::int64_t, std::vector<const FeatureObservation*>> tracks;
    for (const auto& f : res.features) tracks[f.landmark].push_back(&f);
    std::vector<double> e;
    for (const auto& [id, obs] : tracks) {
      for (std::size_t j = 1; j < obs.size(); ++j) {
        const auto t = s.Transfer(index.at(obs[0]->keyframe), obs[0]->top, index.at(obs[j]->keyframe));
        if (t && (*t - obs[j]->top).norm() < 4) e.push_back((*t - obs[j]->top).norm());
      }
    }
    return e;
  };
  o.tracks.refine = false;
  const FrontEndResult raw = RunFrontEnd(b, o, progress);
  const std::vector<double> with = member_errors(r), without = member_errors(raw);
  ASSERT_GT(with.size(), 500u);
  EXPECT_LT(Median(with), 0.6 * Median(without)) << Median(with) << " vs " << Median(without);
  EXPECT_LT(Quantile(with, 0.95), 0.6 * Quantile(without, 0.95))
      << Quantile(with, 0.95) << " vs " << Quantile(without, 0.95);
}

}  // namespace
}  // namespace hull
