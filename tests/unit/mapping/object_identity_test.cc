// Object ids across runs (mapping/object_identity.h): a first run keeps
// the bow-aft numbering; later runs give each object the id of the one it
// is (by position and footprint), whatever order and however many the run
// finds; ids are never reused; an object a run missed gets its id back;
// a split keeps the id on the nearer part.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mapping/object_identity.h"

namespace hull {
namespace {

// An object at x (m along the hull) with a round footprint of radius r.
DetectedObject At(double x, double r, double y = 0.0) {
  DetectedObject o;
  o.id = "fresh";
  o.centroid_m = Eigen::Vector3d(x, y, -1.0);
  o.area = M_PI * r * r;
  return o;
}

const TriangleMesh kNoModel;  // objects without footprint vertices: matched by their discs

std::vector<std::string> Ids(const std::vector<DetectedObject>& objects) {
  std::vector<std::string> ids;
  for (const auto& o : objects) ids.push_back(o.id);
  return ids;
}

TEST(ObjectIdentity, FirstRunNumbersInTheRunsOrder) {
  ObjectIdentity identity;
  std::vector<DetectedObject> run = {At(1.0, 0.2), At(3.0, 0.1), At(7.0, 0.3)};
  identity.Assign(&run, kNoModel);
  EXPECT_EQ(Ids(run), (std::vector<std::string>{"obj-1", "obj-2", "obj-3"}));
  EXPECT_EQ(identity.known().size(), 3u);
}

TEST(ObjectIdentity, IdsFollowTheObjectsNotTheirRank) {
  ObjectIdentity identity;
  std::vector<DetectedObject> first = {At(1.0, 0.2), At(3.0, 0.1), At(7.0, 0.3)};
  identity.Assign(&first, kNoModel);
  // A higher tau: the object at 3 m is gone, the others moved by 4 cm and
  // shrank; a new one appears at 5 m. Fresh numbering would call the object
  // at 7 m "obj-2".
  std::vector<DetectedObject> second = {At(1.04, 0.15), At(5.0, 0.1), At(6.96, 0.25)};
  identity.Assign(&second, kNoModel);
  EXPECT_EQ(Ids(second), (std::vector<std::string>{"obj-1", "obj-4", "obj-3"}));
  // Back to the first parameters: the object at 3 m is obj-2 again, and no
  // id is given twice.
  std::vector<DetectedObject> third = {At(1.0, 0.2), At(3.0, 0.1), At(7.0, 0.3)};
  identity.Assign(&third, kNoModel);
  EXPECT_EQ(Ids(third), (std::vector<std::string>{"obj-1", "obj-2", "obj-3"}));
  EXPECT_EQ(identity.known().size(), 4u);
}

TEST(ObjectIdentity, MatchesWithinTheLargerFootprintOnly) {
  ObjectIdentity identity;
  std::vector<DetectedObject> first = {At(1.0, 0.3)};
  identity.Assign(&first, kNoModel);
  // 25 cm off: inside the known 30 cm footprint although the new one is
  // small; 40 cm off across the hull: another object.
  std::vector<DetectedObject> near = {At(1.25, 0.05)};
  identity.Assign(&near, kNoModel);
  EXPECT_EQ(near[0].id, "obj-1");
  std::vector<DetectedObject> far = {At(1.25, 0.05, 0.4)};
  identity.Assign(&far, kNoModel);
  EXPECT_EQ(far[0].id, "obj-2");
}

TEST(ObjectIdentity, ASplitKeepsTheIdOnTheNearerPart) {
  ObjectIdentity identity;
  std::vector<DetectedObject> first = {At(2.0, 0.4)};
  identity.Assign(&first, kNoModel);
  std::vector<DetectedObject> split = {At(1.7, 0.15), At(2.1, 0.2)};
  identity.Assign(&split, kNoModel);
  EXPECT_EQ(Ids(split), (std::vector<std::string>{"obj-2", "obj-1"}));
}

TEST(ObjectIdentity, AnElongatedFootprintKeepsItsLumps) {
  // A 60 cm x 10 cm object (its disc: 14 cm) seen again as two lumps 22 cm
  // either side of its centre: on its footprint, so the nearer lump keeps
  // its id (a disc alone would call both new); a lump beside it is new.
  TriangleMesh model;
  DetectedObject strip = At(5.0, 0.0);
  strip.area = 0.6 * 0.1;
  for (int i = -15; i <= 15; ++i) {
    for (int j = -2; j <= 2; ++j) {
      strip.vertices.push_back(static_cast<int>(model.vertices.size()));
      model.vertices.emplace_back(5.0 + 0.02 * i, 0.02 * j, -1.0);
    }
  }
  ObjectIdentity identity;
  std::vector<DetectedObject> first = {strip};
  identity.Assign(&first, model);
  ASSERT_EQ(first[0].id, "obj-1");
  std::vector<DetectedObject> lumps = {At(4.78, 0.03), At(5.23, 0.03), At(5.0, 0.03, 0.3)};
  identity.Assign(&lumps, kNoModel);
  EXPECT_EQ(Ids(lumps), (std::vector<std::string>{"obj-1", "obj-2", "obj-3"}));
  EXPECT_GT(std::sqrt(strip.area / M_PI), 0.13);
  EXPECT_LT(std::sqrt(strip.area / M_PI), 0.22);
}

TEST(ObjectIdentity, IdNumbers) {
  EXPECT_EQ(ObjectIdNumber("obj-1"), 1);
  EXPECT_EQ(ObjectIdNumber("obj-12"), 12);
  EXPECT_EQ(ObjectIdNumber("obj-"), 0);
  EXPECT_EQ(ObjectIdNumber("obj-1x"), 0);
  EXPECT_EQ(ObjectIdNumber("slab"), 0);
  EXPECT_EQ(ObjectIdNumber("obj-99999999999999"), 0);
}

TEST(ObjectIdentity, ClearStartsAgain) {
  ObjectIdentity identity;
  std::vector<DetectedObject> first = {At(1.0, 0.2), At(3.0, 0.1)};
  identity.Assign(&first, kNoModel);
  identity.Clear();
  std::vector<DetectedObject> other = {At(3.0, 0.1)};
  identity.Assign(&other, kNoModel);
  EXPECT_EQ(other[0].id, "obj-1");
}

}  // namespace
}  // namespace hull
