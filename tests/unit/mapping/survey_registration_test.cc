// Registering two surveys' objects (mapping/survey_registration.h): a known
// motion along a flat bottom recovered from the objects the two share, with
// objects new, removed and moved in between; too few in common: none.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "base/error.h"
#include "mapping/survey_registration.h"

namespace hull {
namespace {

// n objects scattered over a 12 m x 4 m stretch of a flat bottom (z = 0,
// outward normal -z), at least 0.7 m apart.
std::vector<DetectedObject> Scatter(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0, 12), y(-2, 2);
  std::vector<DetectedObject> out;
  while (static_cast<int>(out.size()) < n) {
    DetectedObject o;
    o.centroid_m = {x(rng), y(rng), 0};
    bool free = true;
    for (const DetectedObject& p : out) free = free && (p.centroid_m - o.centroid_m).norm() > 0.7;
    if (!free) continue;
    o.normal_m = {0, 0, -1};
    o.id = "obj-" + std::to_string(out.size() + 1);
    out.push_back(o);
  }
  return out;
}

// B's objects are A's seen through x_BA (B's map of the same hull placed
// differently), with noise.
std::vector<DetectedObject> Move(const std::vector<DetectedObject>& a, const Pose& x_ba, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, noise);
  std::vector<DetectedObject> b = a;
  for (DetectedObject& o : b) {
    o.centroid_m = x_ba * o.centroid_m + Eigen::Vector3d(n(rng), n(rng), 0);
    o.normal_m = x_ba.Rotate(o.normal_m);
  }
  return b;
}

TEST(SurveyRegistration, RecoversTheMotionAlongAFlatBottomFromTheObjectsInCommon) {
  const std::vector<DetectedObject> a = Scatter(14, 7);
  // The demo pair's size of disagreement: 2.4 deg of yaw about the normal
  // and a shift of half a metre along the surface.
  const Pose x_ba = Pose::FromXyzRpy(0.42, -0.28, 0, 0, 0, 2.4 * M_PI / 180);
  std::vector<DetectedObject> b = Move(a, x_ba, 0.01, 3);
  b.erase(b.begin() + 5);  // removed between the surveys
  b.erase(b.begin() + 2);
  for (const DetectedObject& o : Scatter(3, 99)) {  // new ones
    DetectedObject n = o;
    n.centroid_m = x_ba * o.centroid_m + Eigen::Vector3d(0.05, 0.31, 0);
    b.push_back(n);
  }
  SurveyRegistrationOptions opt;
  const SurveyRegistration r = RegisterSurveys(a, b, opt);
  ASSERT_TRUE(r.registered);
  EXPECT_LT(r.identity_inliers, 6);  // unregistered, most objects fall apart
  EXPECT_EQ(r.inliers, 12);          // every object the two share
  EXPECT_LT(r.rms, 0.02);
  const Pose expected = x_ba.Inverse();
  EXPECT_LT(Pose::AngleBetween(r.a_from_b, expected), 0.2 * M_PI / 180);
  EXPECT_LT(Pose::DistanceBetween(r.a_from_b, expected), 0.02);
  EXPECT_NEAR(r.rotation, 2.4 * M_PI / 180, 0.2 * M_PI / 180);
  // Deterministic.
  const SurveyRegistration again = RegisterSurveys(a, b, opt);
  EXPECT_EQ(again.a_from_b.ToVector(), r.a_from_b.ToVector());
}

TEST(SurveyRegistration, SampledHypothesesFindItToo) {
  const std::vector<DetectedObject> a = Scatter(14, 11);
  const Pose x_ba = Pose::FromXyzRpy(-0.6, 0.2, 0, 0, 0, -1.5 * M_PI / 180);
  const std::vector<DetectedObject> b = Move(a, x_ba, 0.005, 5);
  SurveyRegistrationOptions opt;
  opt.max_hypotheses = 3000;  // fewer than the pairs there are: sampled
  const SurveyRegistration r = RegisterSurveys(a, b, opt);
  ASSERT_TRUE(r.registered);
  EXPECT_EQ(r.inliers, 14);
  EXPECT_LT(Pose::DistanceBetween(r.a_from_b, x_ba.Inverse()), 0.02);
}

TEST(SurveyRegistration, AlreadyInPlaceOrTooFewInCommonLeavesTheIdentity) {
  const std::vector<DetectedObject> a = Scatter(8, 21);
  SurveyRegistrationOptions opt;
  // The same map: nothing to register.
  SurveyRegistration r = RegisterSurveys(a, a, opt);
  EXPECT_FALSE(r.registered);
  EXPECT_EQ(r.inliers, 8);
  EXPECT_EQ(r.a_from_b.translation().norm(), 0.0);
  // Two objects in common: a motion is not fixed by so few.
  const Pose x_ba = Pose::FromXyzRpy(0.5, 0.5, 0, 0, 0, 0.03);
  std::vector<DetectedObject> b = Move({a[0], a[1]}, x_ba, 0, 1);
  r = RegisterSurveys(a, b, opt);
  EXPECT_FALSE(r.registered);
  EXPECT_TRUE(r.a_from_b.ToVector().isZero());
  // Bad options are refused.
  opt.match_radius = 0;
  EXPECT_THROW(RegisterSurveys(a, a, opt), OptionError);
}

}  // namespace
}  // namespace hull
