#include "simulate/foreign_objects.h"

#include "base/error.h"
#include "simulate/fouling_changes.h"

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

// Half the clumps have a narrow peak: their top centimetre is a few
// centimetres across, where a broad clump's is a wide plateau.
TEST_F(ForeignObjects, SomeClumpsHaveNarrowPeaks) {
  const TrueObject o = PlaceObject(index_, "patch", ObjectKind::kPatch, {0, 0, 0}, 0.15, 0.15);
  int narrow = 0, broad = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const TriangleMesh m = MakeObjectMesh(o, seed);
    double reach = 0;  // how far from the axis the top stays within 1 cm of the peak
    for (const auto& v : m.vertices) {
      const double h = (v - o.center).dot(o.normal);
      if (h >= o.height - 0.01) reach = std::max(reach, ((v - o.center) - h * o.normal).norm());
    }
    narrow += reach < 0.035;
    broad += reach > 0.045;
  }
  EXPECT_GE(narrow, 5);
  EXPECT_GE(broad, 5);
  EXPECT_EQ(narrow + broad, 20);
}

TEST_F(ForeignObjects, FoulingChangesGrowRemoveAndAdd) {
  std::vector<TrueObject> objs = {
      PlaceObject(index_, "patch-1", ObjectKind::kPatch, {-2, 0, 0}, 0.15, 0.08),
      PlaceObject(index_, "patch-2", ObjectKind::kPatch, {0, 0, 0}, 0.15, 0.10),
      PlaceObject(index_, "cyl-1", ObjectKind::kCylinder, {2, 0, 0}, 0.15, 0.11),
  };
  const std::vector<TrueObject> before = objs;
  FoulingChanges c;
  c.grow = 1;
  c.growth = 0.05;
  c.remove = 1;
  c.add = 2;
  ApplyFoulingChanges(objs, index_, Eigen::Vector3d::UnitX(), c);
  ASSERT_EQ(objs.size(), 4u);
  EXPECT_EQ(objs[0].id, "patch-1");
  EXPECT_NEAR(objs[0].height, 0.13, 1e-12);
  EXPECT_EQ(objs[1].id, "patch-2");
  EXPECT_EQ(objs[1].height, before[1].height);
  EXPECT_EQ(objs[1].center, before[1].center);
  EXPECT_EQ(objs[2].id, "new-1");
  EXPECT_EQ(objs[3].id, "new-2");
  for (int k = 2; k < 4; ++k) {
    EXPECT_NEAR(objs[static_cast<std::size_t>(k)].center.z(), 0.0, 1e-12);  // on the surface
    EXPECT_NEAR(objs[static_cast<std::size_t>(k)].height, c.new_height, 1e-12);
    for (const auto& b : before) {
      EXPECT_GT((objs[static_cast<std::size_t>(k)].center - b.center).norm(), 0.5) << b.id;
    }
  }
  c.growth = 0;
  EXPECT_THROW(ApplyFoulingChanges(objs, index_, Eigen::Vector3d::UnitX(), c), OptionError);
}

TEST_F(ForeignObjects, RemovalSkipsObjectsTooLowToBeDetectedAndKeepsShapes) {
  // The last object placed is a 0.06 m patch (the demo's patch-3, at the
  // limit of detection): the last one at least remove_min_height high goes.
  std::vector<TrueObject> objs = {
      PlaceObject(index_, "patch-1", ObjectKind::kPatch, {-2, 0, 0}, 0.15, 0.10),
      PlaceObject(index_, "cyl-1", ObjectKind::kCylinder, {0, 0, 0}, 0.15, 0.11),
      PlaceObject(index_, "patch-2", ObjectKind::kPatch, {2, 0, 0}, 0.10, 0.06),
  };
  FoulingChanges c;
  c.remove = 1;
  c.add = 1;
  const std::vector<std::size_t> seed = ApplyFoulingChanges(objs, index_, Eigen::Vector3d::UnitX(), c);
  ASSERT_EQ(objs.size(), 3u);
  EXPECT_EQ(objs[0].id, "patch-1");
  EXPECT_EQ(objs[1].id, "patch-2");  // kept: too low to be removed
  EXPECT_EQ(objs[2].id, "new-1");
  // Each kept object is seeded by its index before the changes, so its shape does not change.
  EXPECT_EQ(seed, (std::vector<std::size_t>{0, 2, 3}));
  c.remove_min_height = -1;
  EXPECT_THROW(ApplyFoulingChanges(objs, index_, Eigen::Vector3d::UnitX(), c), OptionError);
}

}  // namespace
}  // namespace hull
