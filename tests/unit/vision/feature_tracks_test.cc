#include "vision/feature_tracks.h"

#include <gtest/gtest.h>

#include <set>

namespace hull {
namespace {

TEST(TrackBuilder, LinksTransitivelyAndDropsShortTracks) {
  TrackBuilder b({3, 3, 3, 3});
  EXPECT_TRUE(b.Link(0, 0, 1, 1));
  EXPECT_TRUE(b.Link(1, 1, 2, 2));
  EXPECT_TRUE(b.Link(2, 2, 3, 0));
  EXPECT_TRUE(b.Link(0, 0, 3, 0));  // already the same track
  EXPECT_TRUE(b.Link(0, 2, 1, 0));
  int dropped = -1;
  const auto tracks = b.Tracks(3, &dropped);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0], (TrackBuilder::Track{{0, 0}, {1, 1}, {2, 2}, {3, 0}}));
  EXPECT_EQ(dropped, 1);  // the two-keyframe track (0,2)-(1,0)
  EXPECT_EQ(b.Tracks(2).size(), 2u);
  EXPECT_EQ(b.refused(), 0);
}

TEST(TrackBuilder, RefusesTwoFeaturesOfOneImage) {
  TrackBuilder b({2, 2, 2});
  EXPECT_TRUE(b.Link(0, 0, 1, 0));
  EXPECT_TRUE(b.Link(1, 0, 2, 0));
  // (0,1) - (2,1) is fine alone, but then linking it to the first track
  // would hold two features of keyframe 0 and of keyframe 2.
  EXPECT_TRUE(b.Link(0, 1, 2, 1));
  EXPECT_FALSE(b.Link(2, 1, 1, 0));
  EXPECT_FALSE(b.Link(0, 0, 0, 1));  // within one image
  EXPECT_EQ(b.refused(), 2);
  for (const auto& t : b.Tracks(2)) {
    std::set<int> keyframes;
    for (const auto& m : t) EXPECT_TRUE(keyframes.insert(m.first).second);
  }
  EXPECT_EQ(b.Tracks(2).size(), 2u);
  EXPECT_THROW(b.Link(0, 2, 1, 0), std::out_of_range);
}

}  // namespace
}  // namespace hull
