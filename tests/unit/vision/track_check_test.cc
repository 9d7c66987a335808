// The DVL height check of mono tracks (vision/track_check.h) on the mono
// survey of vision_scene.h (a plane 1.5 m above keyframes 0.15 m apart, the
// navigation prior off by up to ~3 cm): features placed where true points
// project with the TRUE cameras, the check triangulating with the prior.
// Points on the hull and on objects standing up to 0.2 m off it are kept;
// wrong matches along the epipolar line (points on the first feature's ray
// decimetres in front of or behind the hull, which triangulate exactly) are
// dropped when the track has at most check_max_keyframes keyframes; so is
// a three-keyframe track whose middle observation is off (its rays do not
// meet) when it stands in front of the hull.
#include <gtest/gtest.h>

#include "base/error.h"
#include "unit/vision/vision_scene.h"
#include "vision/camera_geometry.h"
#include "vision/track_check.h"

namespace hull {
namespace {

using testing::MakeVisionScene;
using testing::VisionScene;

struct Planted {
  double height;  // m in front of the hull (in keyframe 1's true frame)
  std::size_t keyframes;
  bool stereo;
};

TEST(TrackCheck, DropsMonoTracksStandingFarOffTheDvlPlane) {
  const VisionScene s = MakeVisionScene(false, false, 6);
  const CameraRig& rig = s.manifest.camera;
  const TrackOptions o;  // keyframes <= 3, heights in [-0.1, 0.25] m
  // The DVL's plane per keyframe (its returns are true ranges): through
  // three true surface points, in the true camera frame.
  std::vector<std::optional<CameraPlane>> planes(s.truth.size());
  for (std::size_t k = 0; k < s.truth.size(); ++k) {
    const Pose x_c_g = s.TruePose(k).Inverse();
    const Eigen::Vector3d p0 = x_c_g * *s.SurfacePoint(k, {320, 256}), p1 = x_c_g * *s.SurfacePoint(k, {100, 100}),
                          p2 = x_c_g * *s.SurfacePoint(k, {500, 120});
    CameraPlane plane;
    plane.normal = (p1 - p0).cross(p2 - p0).normalized();
    if (plane.normal.dot(p0) < 0) plane.normal = -plane.normal;
    plane.offset = plane.normal.dot(p0);
    planes[k] = plane;
  }
  planes[5].reset();  // keyframe 5 has no DVL returns
  std::vector<KeyframeView> views(s.truth.size());
  for (std::size_t k = 0; k < views.size(); ++k) {
    views[k].keyframe = s.nav[k].keyframe;
    views[k].x_g_cT = CameraPoseFromNav(s.manifest, s.nav[k]);  // the prior
  }
  // Points on keyframe 1's rays through a grid of pixels, at a height off
  // the hull; each seen from keyframe 1 on (true cameras).
  const Pose c1 = s.TruePose(1);
  const Eigen::Vector3d up = c1.rotation() * -planes[1]->normal;  // from the hull towards the camera
  std::vector<Planted> planted;
  for (double h : {0.0, 0.1, 0.15, -0.03, 0.4, 0.6, -0.25, -0.5}) {
    for (std::size_t views_n : {2, 3}) planted.push_back({h, views_n, false});
  }
  planted.push_back({0.4, 4, false});  // four keyframes: not checked
  planted.push_back({0.5, 2, true});   // a stereo depth: not checked
  std::vector<TrackBuilder::Track> tracks;
  std::vector<const Planted*> what;
  int u = 0;
  for (const Planted& p : planted) {
    for (int rep = 0; rep < 6; ++rep, ++u) {
      const Eigen::Vector2d uv(290 + 10 * (u % 7), 330 + 10 * ((u / 7) % 7));  // the view moves up the image
      const Eigen::Vector3d on_hull = *s.SurfacePoint(1, uv);
      const Eigen::Vector3d ray = (on_hull - c1.translation()).normalized();
      // Along the ray to the plane at height h (a wrong match's point lies on it).
      const Eigen::Vector3d X = on_hull - ray * (p.height / ray.dot(-up));
      TrackBuilder::Track t;
      for (std::size_t k = 1; k < 1 + p.keyframes; ++k) {
        const Eigen::Vector2d x = (s.K() * (s.TruePose(k).Inverse() * X)).hnormalized();
        ASSERT_TRUE(rig.InImage(x)) << x.transpose() << ", keyframe " << k << ", height " << p.height;
        t.push_back({static_cast<int>(k), static_cast<int>(views[k].top.points.size())});
        views[k].top.points.push_back(x);
      }
      tracks.push_back(t);
      what.push_back(&p);
    }
  }
  // Three keyframes, the middle observation 20 px off the point's
  // projection (one wrong match: the rays do not meet): dropped when the
  // point stands in front of the hull, kept on it.
  const std::size_t first_odd = tracks.size();
  for (double h : {0.12, 0.0}) {
    const Eigen::Vector3d on_hull = *s.SurfacePoint(1, {300, 380});
    const Eigen::Vector3d ray = (on_hull - c1.translation()).normalized();
    const Eigen::Vector3d X = on_hull - ray * (h / ray.dot(-up));
    TrackBuilder::Track t;
    for (std::size_t k = 1; k <= 3; ++k) {
      Eigen::Vector2d x = (s.K() * (s.TruePose(k).Inverse() * X)).hnormalized();
      if (k == 2) x.x() += 20;
      t.push_back({static_cast<int>(k), static_cast<int>(views[k].top.points.size())});
      views[k].top.points.push_back(x);
    }
    tracks.push_back(t);
  }
  std::vector<std::vector<char>> has_stereo(views.size());
  for (std::size_t k = 0; k < views.size(); ++k) has_stereo[k].assign(views[k].top.points.size(), 0);
  for (std::size_t t = 0; t < first_odd; ++t) {
    if (what[t]->stereo)
      has_stereo[static_cast<std::size_t>(tracks[t][0].first)][static_cast<std::size_t>(tracks[t][0].second)] = 1;
  }

  const std::vector<TrackCheck> checks = CheckTrackHeights(tracks, views, has_stereo, planes, rig, o, 2);
  std::vector<int> verdict(tracks.size(), -1);  // -1 not checked, 0 dropped, 1 kept
  for (const TrackCheck& c : checks) {
    if (static_cast<std::size_t>(c.track) >= first_odd) {
      EXPECT_GT(c.max_reprojection, 5.0);
      EXPECT_EQ(c.kept, static_cast<std::size_t>(c.track) == first_odd + 1);
      continue;
    }
    EXPECT_EQ(c.members, tracks[static_cast<std::size_t>(c.track)]);
    // Triangulated with the prior (its relative poses ~4 % off in scale):
    // the height within a few centimetres plus 5 % of the point's depth.
    const double h = what[static_cast<std::size_t>(c.track)]->height;
    EXPECT_NEAR(c.min_height, h, 0.02 + 0.05 * (1.5 - h));
    verdict[static_cast<std::size_t>(c.track)] = c.kept ? 1 : 0;
  }
  for (std::size_t t = 0; t < first_odd; ++t) {
    const Planted& p = *what[t];
    SCOPED_TRACE(::testing::Message() << "height " << p.height << ", keyframes " << p.keyframes);
    if (p.stereo || p.keyframes > 3) {
      EXPECT_EQ(verdict[t], -1);
    } else if (p.height > o.check_max_height || p.height < o.check_min_height) {
      EXPECT_EQ(verdict[t], 0);  // a wrong match (or nothing on a hull stands so far off)
    } else {
      EXPECT_EQ(verdict[t], 1);  // on the hull or on an object
    }
  }

  // A track whose keyframes have no DVL plane is never dropped.
  std::vector<std::optional<CameraPlane>> no_planes(planes.size());
  const std::vector<TrackCheck> none = CheckTrackHeights(tracks, views, has_stereo, no_planes, rig, o, 1);
  ASSERT_FALSE(none.empty());
  for (const TrackCheck& c : none) {
    EXPECT_TRUE(c.kept);
    EXPECT_TRUE(std::isnan(c.min_height));
  }

  TrackOptions bad = o;
  bad.check_max_height = 0;
  EXPECT_THROW(bad.Check(), OptionError);
  bad = o;
  bad.check_min_height = 0.1;
  EXPECT_THROW(bad.Check(), OptionError);
  bad = o;
  bad.check_max_keyframes = 1;
  EXPECT_THROW(bad.Check(), OptionError);
}

}  // namespace
}  // namespace hull
