#include "simulate/foreign_objects.h"

#include <gtest/gtest.h>

#include "support/test_meshes.h"

namespace hull {
namespace {

class ForeignObjects : public ::testing::Test {
 protected:
  ForeignObjects() : plate_(test::MakeBox({-5, -5, -1}, {5, 5, 0})), index_(plate_) {}
  TriangleMesh plate_;
  MeshIndex index_;
};

TEST_F(ForeignObjects, PlacedOnTheSurfaceWithItsNormal) {
  const TrueObject c = PlaceObject(index_, "cyl", ObjectKind::kCylinder, {1, 2, 0.7}, 0.15, 0.11);
  EXPECT_NEAR(c.center.z(), 0.0, 1e-12);
  EXPECT_NEAR(c.center.x(), 1.0, 1e-12);
  EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
}

TEST_F(ForeignObjects, MeshesAreClosedWithExactHeightAndFootprint) {
  const TrueObject objs[] = {
      PlaceObject(index_, "cyl", ObjectKind::kCylinder, {0, 0, 0}, 0.15, 0.11),
      PlaceObject(index_, "box", ObjectKind::kBox, {1, 0, 0}, 0, 0, {0.4, 0.25, 0.08}),
      PlaceObject(index_, "patch", ObjectKind::kPatch, {-1, 0, 0}, 0.2, 0.13),
  };
  for (const auto& o : objs) {
    const TriangleMesh m = MakeObjectMesh(o, 7);
    EXPECT_TRUE(m.CheckTopology().closed) << o.id;
    EXPECT_GT(m.SignedVolume(), 0) << o.id;
    double top = -1e9, footprint = 0;
    for (const auto& v : m.vertices) {
      const double h = (v - o.center).dot(o.normal);
      top = std::max(top, h);
      footprint = std::max(footprint, ((v - o.center) - h * o.normal).norm());
    }
    EXPECT_NEAR(top, o.Height(), 1e-12) << o.id;
    EXPECT_LE(footprint, o.radius + 1e-9) << o.id;
    EXPECT_GT(footprint, 0.8 * o.radius) << o.id;
  }
}

TEST_F(ForeignObjects, StripIsAChainOfOverlappingPatches) {
  const auto strip = PlacePatchStrip(index_, "strip", {-2, 0, 0}, {2, 0, 0}, 0.12, 0.2, 0.06, 0.18, 3);
  ASSERT_GE(strip.size(), 10u);
  for (std::size_t i = 1; i < strip.size(); ++i) {
    const double gap = (strip[i].center - strip[i - 1].center).norm();
    EXPECT_LT(gap, strip[i].radius + strip[i - 1].radius) << "patches " << i - 1 << " and " << i << " do not overlap";
    EXPECT_GE(strip[i].height, 0.06);
    EXPECT_LE(strip[i].height, 0.18);
  }
}

}  // namespace
}  // namespace hull
