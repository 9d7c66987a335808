// Detected objects' height uncertainty: max_height_sigma is the sigma_h of
// the supporting feature nearest to the object's highest vertex
// (docs/mapping.md, "Objects"), NaN when no supporting feature has one; a
// region smaller than object_min_area is an object when enough features
// above h_min from enough keyframes hold it up; found and false objects
// against the truth (CountFoundObjects).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/point_index.h"
#include "mapping/detected_objects.h"
#include "mapping/hull_zones.h"
#include "mapping/object_height_check.h"
#include "mapping/vertex_significance.h"

namespace hull {
namespace {

// A flat 2 m x 2 m bottom plate at z = 0 of M (outward normal -z), in 5 cm
// squares, and a round lump of `height` at the origin (Gaussian, `radius`
// its standard deviation).
struct Plate {
  TriangleMesh mesh;
  std::vector<double> deviation;
};

Plate MakePlate(double height, double radius = 0.1) {
  Plate p;
  const int n = 41;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d v(-1.0 + 0.05 * i, -1.0 + 0.05 * j, 0.0);
      p.mesh.vertices.push_back(v);
      p.deviation.push_back(height * std::exp(-v.head<2>().squaredNorm() / (2 * radius * radius)));
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      p.mesh.faces.push_back(Face{a, c, b});  // wound so that the normal is -z
      p.mesh.faces.push_back(Face{b, c, d});
    }
  }
  p.mesh.ComputeNormals();
  return p;
}

struct Landmark {
  Eigen::Vector3d p;
  double sigma_h;
};

// The landmarks, each a vertex of one shape in each of `keyframes` keyframes
// (ids 7, 8, ...).
ObjectDetection Detect(const Plate& plate, const std::vector<Landmark>& landmarks, int keyframes = 1,
                       const MappingOptions& o = MappingOptions()) {
  MappingInput input;
  input.x_gM = Pose();  // g = M
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    MappingLandmark l;
    l.id = static_cast<std::int64_t>(i);
    l.p_g = landmarks[i].p;
    l.sigma_h = landmarks[i].sigma_h;
    l.deviation = -landmarks[i].p.z();
    input.landmarks.push_back(l);
  }
  std::vector<KeyframeShapes> shapes;
  for (int kf = 0; kf < keyframes; ++kf) {
    KeyframeShapes k;
    k.id = 7 + kf;
    DetectedShape shape;
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      ShapePoint sp;
      sp.landmark = static_cast<int>(i);
      sp.cluster = 0;
      k.points.push_back(sp);
      shape.points.push_back(static_cast<int>(i));
    }
    k.shapes.push_back(shape);
    shapes.push_back(k);
  }
  const HullFrame hull(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), -1.0, 1.0, 4, 45.0);
  const PointIndex prior_index(plate.mesh.vertices);
  const MeshIndex cad_index(plate.mesh);
  return DetectObjects(plate.mesh, plate.deviation, prior_index, cad_index, hull, input, shapes, o);
}

TEST(DetectedObjects, HeightSigmaIsTheSupportingFeatureNearestThePeak) {
  const Plate plate = MakePlate(0.10);
  // Outside the hull is -z (the plate's outward normal).
  const std::vector<Landmark> landmarks = {
      {{0.0, 0.0, -0.10}, std::nan("")},  // at the peak, but without sigma_h: skipped
      {{0.02, 0.01, -0.099}, 0.004},      // the nearest with one
      {{0.06, 0.0, -0.085}, 0.007},      {{-0.08, 0.05, -0.06}, 0.020},
      {{0.9, 0.9, -0.001}, 0.001},  // on clean hull, far from the lump: not a supporting feature
  };
  const ObjectDetection d = Detect(plate, landmarks);
  ASSERT_EQ(d.objects.size(), 1u);
  const DetectedObject& o = d.objects[0];
  EXPECT_NEAR(o.max_height, 0.10, 1e-12);
  EXPECT_EQ(o.num_features, 4);
  EXPECT_DOUBLE_EQ(o.max_height_sigma, 0.004);
}

TEST(DetectedObjects, HeightSigmaIsNanWithoutFeatureSigmas) {
  const Plate plate = MakePlate(0.08);
  const ObjectDetection d = Detect(plate, {{{0.0, 0.0, -0.08}, std::nan("")}, {{0.03, 0.0, -0.07}, 0.0}});
  ASSERT_EQ(d.objects.size(), 1u);
  EXPECT_TRUE(std::isnan(d.objects[0].max_height_sigma));
}

// A tall narrow lump (0.10 m, 3 cm standard deviation): its footprint
// above h_min = 3 cm is below object_min_area, so the area test alone drops
// it; three features above h_min over it, held by the shapes of two
// keyframes, make it an object (the demo's narrow strip lumps).
TEST(DetectedObjects, NarrowLumpHeldUpByFeaturesFromSeveralViews) {
  const Plate plate = MakePlate(0.10, 0.03);
  const std::vector<Landmark> three = {
      {{0.0, 0.0, -0.098}, 0.003}, {{0.01, 0.005, -0.09}, 0.003}, {{-0.005, 0.01, -0.09}, 0.003}};
  EXPECT_EQ(MappingOptions().object_min_features, 3);  // the default: the support test on
  MappingOptions area_only;
  area_only.object_min_features = 0;                                // the area test alone
  EXPECT_TRUE(Detect(plate, three, 2, area_only).objects.empty());  // the footprint alone is too small

  MappingOptions support;
  support.object_min_features = 3;
  const ObjectDetection d = Detect(plate, three, 2, support);
  ASSERT_EQ(d.objects.size(), 1u);
  const DetectedObject& o = d.objects[0];
  EXPECT_GT(o.area, 0.0);
  EXPECT_LT(o.area, MappingOptions().object_min_area);
  EXPECT_NEAR(o.max_height, 0.10, 1e-12);
  EXPECT_EQ(o.num_features, 3);
  EXPECT_EQ(o.num_views, 2);

  // One view only, two features only, or a third feature below h_min: no object.
  EXPECT_TRUE(Detect(plate, three, 1, support).objects.empty());
  EXPECT_TRUE(Detect(plate, {three[0], three[1]}, 2, support).objects.empty());
  EXPECT_TRUE(Detect(plate, {three[0], three[1], {{0.01, -0.01, -0.02}, 0.003}}, 2, support).objects.empty());
  // The thresholds are options.
  MappingOptions two;
  two.object_min_features = 2;
  EXPECT_EQ(Detect(plate, {three[0], three[1]}, 2, two).objects.size(), 1u);
  MappingOptions three_views = support;
  three_views.object_min_views = 3;
  EXPECT_TRUE(Detect(plate, three, 2, three_views).objects.empty());
  EXPECT_EQ(Detect(plate, three, 3, three_views).objects.size(), 1u);
}

// Found: a detected object has a vertex in the true object's region (one
// detected object may find several touching lumps); false: a detected object
// in no true object's region; objects below min_height are not required.
TEST(FoundObjects, CountsFoundMissedAndFalse) {
  std::vector<ObjectHeightCheck> checks(4);
  checks[0].id = "strip-1";
  checks[0].height = 0.13;
  checks[0].detected_as = {"obj-1"};
  checks[1].id = "strip-2";
  checks[1].height = 0.14;
  checks[1].detected_as = {"obj-1"};
  checks[2].id = "strip-3";
  checks[2].height = 0.09;
  checks[3].id = "low";
  checks[3].height = 0.04;
  checks[3].detected_as = {"obj-2"};
  std::vector<DetectedObject> objects(3);
  objects[0].id = "obj-1";
  objects[1].id = "obj-2";
  objects[2].id = "obj-3";
  const FoundObjects f = CountFoundObjects(checks, objects, 0.06);
  EXPECT_EQ(f.required, 3);
  EXPECT_EQ(f.found, 2);
  EXPECT_EQ(f.missed, std::vector<std::string>{"strip-3"});
  EXPECT_EQ(f.false_objects, std::vector<std::string>{"obj-3"});
  EXPECT_EQ(f.ToString(), "found 2 of 3 (missed: strip-3); false objects: 1 (obj-3)\n");
}

TEST(VertexSignificance, MaskFollowsK) {
  TriangleMesh m;
  m.vertices.assign(5, Eigen::Vector3d::Zero());
  m.SetScalar("deviation", {0.010, -0.010, 0.004, 0.020, 0.050});
  EXPECT_FALSE(HasVertexSigma(m));
  EXPECT_EQ(CountSignificant(m, 1.96), 0u);  // no sigma: nothing is significant
  m.SetScalar("sigma", {0.004, 0.004, 0.004, std::nan(""), 0.010});
  EXPECT_TRUE(HasVertexSigma(m));
  EXPECT_DOUBLE_EQ(MaxVertexSigma(m), 0.010);
  const std::vector<double> d = SignificantDeviation(m, 1.96);
  ASSERT_EQ(d.size(), 5u);
  EXPECT_DOUBLE_EQ(d[0], 0.010);   // 0.010 > 1.96 * 0.004
  EXPECT_DOUBLE_EQ(d[1], -0.010);  // |h| counts
  EXPECT_TRUE(std::isnan(d[2]));   // 0.004 < 0.00784
  EXPECT_TRUE(std::isnan(d[3]));   // sigma unknown
  EXPECT_DOUBLE_EQ(d[4], 0.050);
  EXPECT_EQ(CountSignificant(m, 1.96), 3u);
  EXPECT_EQ(CountSignificant(m, 3.0), 1u);  // 0.010 < 0.012; 0.050 > 0.030
  EXPECT_EQ(CountSignificant(m, 6.0), 0u);
}

}  // namespace
}  // namespace hull
