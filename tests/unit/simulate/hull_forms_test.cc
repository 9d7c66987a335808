#include "simulate/hull_forms.h"

#include <gtest/gtest.h>

#include "geometry/mesh_index.h"

namespace hull {
namespace {

TEST(ParametricHull, ClosedOutwardAtCurtissSize) {
  const TriangleMesh m = MakeParametricHull();
  const OrientationReport topo = m.CheckTopology();
  EXPECT_TRUE(topo.closed);
  EXPECT_GT(m.SignedVolume(), 0);
  const auto box = m.Bounds();
  EXPECT_NEAR(box.sizes().x(), 183.0, 1e-9);
  EXPECT_NEAR(box.sizes().y(), 27.0, 1e-9);
  EXPECT_NEAR(box.min().z(), 0.0, 1e-9);
  // Block coefficient of a full cargo hull up to the deck: between 0.6 and 0.9.
  const double cb = m.SignedVolume() / (box.sizes().x() * box.sizes().y() * 14.0);
  EXPECT_GT(cb, 0.6);
  EXPECT_LT(cb, 0.9);
}

TEST(ParametricHull, FlatBottomBilgeAndTaper) {
  const TriangleMesh m = MakeParametricHull();
  const MeshIndex index(m);
  // Midship: the flat keel and bottom at z = 0 with a downward normal.
  for (double y : {0.0, 5.0, -10.9}) {
    const RayHit hit = index.Raycast({91.5, y, -5.0}, {0, 0, 1});
    ASSERT_TRUE(hit.hit) << y;
    EXPECT_NEAR(hit.point.z(), 0.0, 1e-9);
    EXPECT_NEAR(m.face_normals[hit.face].z(), -1.0, 1e-9);
  }
  // Bilge: a ray up at y = 12.5 hits above the keel (the arc), not the flat.
  const RayHit bilge = index.Raycast({91.5, 12.5, -5.0}, {0, 0, 1});
  ASSERT_TRUE(bilge.hit);
  EXPECT_GT(bilge.point.z(), 0.1);
  EXPECT_LT(bilge.point.z(), 2.5);
  // Side at the waterline: half-beam at midship, much narrower near the ends.
  const RayHit side = index.Raycast({91.5, -30, 9.1}, {0, 1, 0});
  ASSERT_TRUE(side.hit);
  EXPECT_NEAR(side.point.y(), -13.5, 1e-6);
  const RayHit bow = index.Raycast({180.0, -30, 9.1}, {0, 1, 0});
  ASSERT_TRUE(bow.hit);
  EXPECT_GT(bow.point.y(), -3.0);
  HullFormOptions bad;
  bad.length = -1;
  EXPECT_THROW(MakeParametricHull(bad), OptionError);
}

}  // namespace
}  // namespace hull
