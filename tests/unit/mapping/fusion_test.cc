// Algorithm 2 and what follows it on a small scene with known answers: a
// flat 4 m x 4 m patch of hull bottom (outward normal down) carrying a 0.1 m
// high disk of radius 0.3 m, seen from below by a 3 x 3 lattice of cameras
// at 1.5 m; features sampled on the true surface. The fast fusion must equal
// the paper's loops bit for bit; the refinement, the fused heights, the
// detected object, the inspected area and the Mapper's caching are checked
// against the scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "base/error.h"
#include "geometry/mesh_index.h"
#include "geometry/point_index.h"
#include "keyframe_grid.h"
#include "mapping/mapper.h"
#include "mapping/mesh_refinement.h"
#include "mapping/refinement_region.h"
#include "mapping/shape_fusion.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

constexpr double kHeight = 0.10, kRadius = 0.30;
const Eigen::Vector2d kDisk(2.0, 2.0);

// The CAD: the plane z = 0 over [0, 4]^2, faces turned to face -z (a bottom).
TriangleMesh FlatBottom() {
  TriangleMesh m = test::MakeGrid(20, 20, 0.2);
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  m.ComputeNormals();
  return m;
}

// Height of the true surface below the CAD (outward, along -z).
double TrueHeight(double x, double y) { return (Eigen::Vector2d(x, y) - kDisk).norm() <= kRadius ? kHeight : 0.0; }

struct Scene {
  TriangleMesh cad;
  MappingInput input;
};

Scene MakeScene(double noise) {
  Scene s;
  s.cad = FlatBottom();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, noise > 0 ? noise : 1.0);
  s.input.source = "test scene";
  s.input.x_gM = Pose();  // g = M
  s.input.model_axes = ModelAxes{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  // Features: 60 per m^2 on the hull, 400 per m^2 on the disk.
  auto add = [&](double x, double y) {
    const double h = TrueHeight(x, y) + (noise > 0 ? g(rng) : 0.0);
    s.input.landmarks.push_back({static_cast<std::int64_t>(s.input.landmarks.size()), Eigen::Vector3d(x, y, -h), h});
  };
  for (int i = 0; i < 60 * 16; ++i) add(4 * u(rng), 4 * u(rng));
  for (int i = 0; i < static_cast<int>(400 * M_PI * kRadius * kRadius); ++i) {
    const double r = kRadius * std::sqrt(u(rng)), a = 2 * M_PI * u(rng);
    add(kDisk.x() + r * std::cos(a), kDisk.y() + r * std::sin(a));
  }
  // Cameras 1.5 m below, looking up (+z of M = the camera's optical axis).
  AddKeyframeGrid(s.input, 10, Eigen::Vector2d(1.5, 1.6), Eigen::Vector2d(0.5, 0.4));
  return s;
}

std::vector<Pose> CameraPoses(const MappingInput& in) {
  std::vector<Pose> out;
  for (const auto& k : in.keyframes) out.push_back(in.x_gM.Inverse() * k.x_g_cT);
  return out;
}

TEST(Fusion, FastEqualsThePapersLoopsBitForBit) {
  for (const double noise : {0.0, 0.003}) {
    const Scene s = MakeScene(noise);
    MappingOptions o;
    NullProgress p;
    const std::vector<KeyframeShapes> shapes = DetectAllShapes(s.input, o, p);
    const std::vector<Pose> cams = CameraPoses(s.input);
    const MeshIndex index(s.cad);
    const RefinedMesh refined = RefineMesh(s.cad, index, DepartureRegion(shapes, cams, index, o, p), o.refine_edge);
    const TriangleMesh& prior = refined.mesh;
    const PointConeTree tree(prior.vertices);
    FusionRule mean;  // eq. 15 as in the paper: the mean of the camera rays' hits
    mean.keep_peaks = false;
    mean.along_normal = false;
    const FusionResult brute_mean = FuseShapesBruteForce(prior, cams, shapes, o.fusion_radius, mean);
    const FusionResult fast_mean = FuseShapes(prior, tree, cams, shapes, o.fusion_radius, mean, p);
    EXPECT_EQ(fast_mean.count, brute_mean.count);
    EXPECT_EQ(fast_mean.vertices, brute_mean.vertices);
    // The peak-keeping rule along the camera's rays and along the normals.
    for (const bool along_normal : {false, true}) {
      SCOPED_TRACE(along_normal ? "along the normals" : "along the camera's rays");
      FusionRule rule;
      rule.along_normal = along_normal;
      const FusionResult brute = FuseShapesBruteForce(prior, cams, shapes, o.fusion_radius, rule);
      const FusionResult fast = FuseShapes(prior, tree, cams, shapes, o.fusion_radius, rule, p);
      EXPECT_GT(brute.hits, 500u);
      EXPECT_EQ(fast.hits, brute.hits);
      EXPECT_EQ(fast.count, brute.count);
      EXPECT_EQ(fast.support, brute.support);
      EXPECT_EQ(fast.vertices, brute.vertices);
      // A fused vertex rests on its supported hits: on the disk's top 0.1 m
      // below the CAD (the features' height), elsewhere near the plane; along
      // the normal it moves along -z only.
      int on_top = 0;
      for (std::size_t v = 0; v < prior.num_vertices(); ++v) {
        if (fast.support[v] == 0) {
          EXPECT_EQ(fast.vertices[v], prior.vertices[v]);
          continue;
        }
        if (along_normal) {
          EXPECT_NEAR((fast.vertices[v] - prior.vertices[v]).head<2>().norm(), 0.0, 1e-9);
        }
        const double r = (prior.vertices[v].head<2>() - kDisk).norm();
        if (r < kRadius - 0.06) {
          EXPECT_NEAR(-fast.vertices[v].z(), kHeight, 0.002 + 3 * noise);
          ++on_top;
        } else if (r > kRadius + 0.15) {
          EXPECT_NEAR(fast.vertices[v].z(), 0.0, 0.002 + 3 * noise);
        }
      }
      EXPECT_GT(on_top, 100);
    }
  }
}

TEST(Fusion, VerticesMovedUnderFeaturesStayOnTheCad) {
  const Scene s = MakeScene(0.0);
  MappingOptions o;
  NullProgress p;
  const std::vector<KeyframeShapes> shapes = DetectAllShapes(s.input, o, p);
  const std::vector<Pose> cams = CameraPoses(s.input);
  const MeshIndex index(s.cad);
  const RefinedMesh refined = RefineMesh(s.cad, index, DepartureRegion(shapes, cams, index, o, p), o.refine_edge);
  TriangleMesh snapped = refined.mesh;
  const PointIndex prior_index(snapped.vertices);
  const int moved = SnapVerticesToFeatures(snapped, prior_index, index, shapes, Pose(), o.fusion_support,
                                           o.refine_threshold, 0.6 * o.refine_edge);
  // The disk's features (0.1 m high, in several keyframes' shapes) each move
  // one vertex; the flat hull's (below refine_threshold) none.
  EXPECT_GT(moved, 50);
  int changed = 0;
  for (std::size_t v = 0; v < snapped.num_vertices(); ++v) {
    if (snapped.vertices[v] == refined.mesh.vertices[v]) continue;
    ++changed;
    EXPECT_NEAR(snapped.vertices[v].z(), 0.0, 1e-12);  // on the CAD
    EXPECT_LE((snapped.vertices[v] - refined.mesh.vertices[v]).norm(), 0.6 * o.refine_edge + 1e-12);
    // Under a feature of the disk's top: some landmark's foot is the vertex.
    double nearest = 1e9;
    for (const auto& l : s.input.landmarks) {
      if (l.p_g.z() < -o.refine_threshold)
        nearest = std::min(nearest, (l.p_g.head<2>() - snapped.vertices[v].head<2>()).norm());
    }
    EXPECT_LT(nearest, 1e-9);
  }
  EXPECT_EQ(changed, moved);
  // No face flipped (the CAD faces -z).
  snapped.ComputeNormals();
  for (const auto& n : snapped.face_normals) EXPECT_LT(n.z(), -0.99);
  // The fusion along the normals on it: fast equals brute force, and the
  // disk's top is kept.
  FusionRule rule;
  rule.along_normal = true;
  const PointConeTree tree(snapped.vertices);
  const FusionResult brute = FuseShapesBruteForce(snapped, cams, shapes, o.fusion_radius, rule);
  const FusionResult fast = FuseShapes(snapped, tree, cams, shapes, o.fusion_radius, rule, p);
  EXPECT_EQ(fast.vertices, brute.vertices);
  EXPECT_EQ(fast.support, brute.support);
  int on_top = 0;
  for (std::size_t v = 0; v < snapped.num_vertices(); ++v) {
    if (fast.support[v] == 0 || (snapped.vertices[v].head<2>() - kDisk).norm() > kRadius - 0.06) continue;
    EXPECT_NEAR(-fast.vertices[v].z(), kHeight, 1e-9);
    ++on_top;
  }
  EXPECT_GT(on_top, 100);
}

TEST(Refinement, OnlyWhereShapesDepartAndOnTheCad) {
  const Scene s = MakeScene(0.0);
  MappingOptions o;
  NullProgress p;
  const std::vector<KeyframeShapes> shapes = DetectAllShapes(s.input, o, p);
  const MeshIndex index(s.cad);
  const RefinementRegion region = DepartureRegion(shapes, CameraPoses(s.input), index, o, p);
  ASSERT_FALSE(region.empty());
  // The disk (all its features depart) is in the region; the far corners are not.
  EXPECT_TRUE(region.Contains(Eigen::Vector3d(kDisk.x(), kDisk.y(), 0.01)));
  EXPECT_TRUE(region.Contains(Eigen::Vector3d(kDisk.x() + kRadius, kDisk.y(), 0.01)));
  EXPECT_FALSE(region.Contains(Eigen::Vector3d(0.5, 0.5, 0.01)));
  EXPECT_FALSE(region.Contains(Eigen::Vector3d(kDisk.x() + kRadius + 0.4, kDisk.y(), 0.01)));
  const RefinedMesh r = RefineMesh(s.cad, index, region, 0.03);
  EXPECT_GT(r.refined_faces, 500);
  // The refined area covers the disk and its margin, not the 16 m^2 patch.
  EXPECT_GT(r.refined_area, M_PI * kRadius * kRadius);
  EXPECT_LT(r.refined_area, 2.5);
  // Same surface: every vertex on the plane, the area unchanged, normals down.
  double worst = 0;
  for (const auto& v : r.mesh.vertices) worst = std::max(worst, std::abs(v.z()));
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(r.mesh.SurfaceArea(), 16.0, 1e-9);
  for (const auto& n : r.mesh.face_normals) EXPECT_LT(n.z(), -0.999);
  // Edges near the disk's centre are close to the target; far away the CAD's.
  double near_sum = 0, far_max = 0;
  int near_n = 0;
  for (const Face& f : r.mesh.faces) {
    const Eigen::Vector3d c = (r.mesh.vertices[f[0]] + r.mesh.vertices[f[1]] + r.mesh.vertices[f[2]]) / 3.0;
    const double e = (r.mesh.vertices[f[0]] - r.mesh.vertices[f[1]]).norm();
    const double d = (c.head<2>() - kDisk).norm();
    if (d < 0.2) {
      near_sum += e;
      ++near_n;
    } else if (d > 1.5) {
      far_max = std::max(far_max, e);
    }
  }
  ASSERT_GT(near_n, 50);
  EXPECT_NEAR(near_sum / near_n, 0.03, 0.01);
  EXPECT_GT(far_max, 0.19);
  // An empty region leaves the CAD as it is.
  const RefinedMesh same = RefineMesh(s.cad, index, RefinementRegion(), 0.03);
  EXPECT_EQ(same.mesh.vertices, s.cad.vertices);
  EXPECT_EQ(same.mesh.faces, s.cad.faces);
}

TEST(Mapper, ObjectInspectionAndCaching) {
  Scene s = MakeScene(0.002);
  Mapper mapper(s.input, s.cad);
  MappingOptions o;
  // Fine samples: the footprints' edges run along the grid's here, so the
  // sampling error (up to half a spacing times the perimeter) does not
  // average out as it does in a survey.
  o.inspection_spacing = 0.025;
  NullProgress p;
  const MappingResult r = mapper.Run(o, p);
  EXPECT_EQ(mapper.refinements(), 1);
  ASSERT_EQ(r.objects.size(), 1u);
  const DetectedObject& obj = r.objects[0];
  EXPECT_EQ(obj.id, "obj-1");
  EXPECT_LT((obj.centroid_m.head<2>() - kDisk).norm(), 0.02);
  EXPECT_NEAR(obj.centroid_m.z(), 0.0, 1e-9);  // on the CAD surface
  // The footprint where the fused model rises above h_min: the disk, less
  // the rim outside its outermost features (along the normals the disk's
  // shapes end there: 0.262 m^2 of 0.283), or a little more where the
  // camera rays' shapes slope from its rim to the next hull feature (about
  // 0.13 m away at 60 features per m^2).
  EXPECT_GT(obj.area, M_PI * kRadius * kRadius * 0.9);
  EXPECT_LT(obj.area, M_PI * (kRadius + 0.08) * (kRadius + 0.08));
  EXPECT_NEAR(obj.max_height, kHeight, 0.01);
  EXPECT_NEAR(obj.mean_height, kHeight, 0.015);
  EXPECT_EQ(obj.side, HullSide::kBottom);
  EXPECT_NEAR(obj.distance_from_bow, 2.0, 0.02);  // the bow is x = 4
  // 20 stations of 0.2 m: the disk's centre lies on the boundary of 9 and 10.
  EXPECT_TRUE(obj.station == 9 || obj.station == 10) << obj.station;
  EXPECT_GT(obj.num_features, 50);
  EXPECT_EQ(obj.num_views, 9);
  EXPECT_EQ(obj.keyframes.front(), 10);
  // The inspected area: the union of the nine image footprints on the plane
  // (1.5 m away: 1360 x 1024 px at f = 1150 px), counted on a fine grid.
  const CameraRig& cam = s.input.camera;
  double expected = 0;
  const double step = 0.005;
  for (double x = step / 2; x < 4; x += step) {
    for (double y = step / 2; y < 4; y += step) {
      bool seen = false;
      for (const auto& k : s.input.keyframes) {
        const Eigen::Vector3d pc = k.x_g_cT.Inverse() * Eigen::Vector3d(x, y, 0);
        seen = seen || cam.InImage(cam.top.Project(pc));
      }
      expected += seen ? step * step : 0;
    }
  }
  EXPECT_NEAR(r.summary.inspected_area, expected, 0.02 * expected);
  EXPECT_NEAR(r.summary.hull_area, 16.0, 1e-9);
  double covered = 0;
  for (const auto& z : r.zones) covered += z.covered_area;
  EXPECT_NEAR(covered, obj.area, 1e-12);
  // Re-runs: raising tau reuses the refinement and finds the same object.
  o.tau = 0.06;
  const MappingResult high = mapper.Run(o, p);
  EXPECT_TRUE(high.summary.refinement_reused);
  EXPECT_EQ(mapper.refinements(), 1);
  ASSERT_EQ(high.objects.size(), 1u);
  EXPECT_GT(high.objects[0].area, M_PI * kRadius * kRadius * 0.8);
  EXPECT_LT(high.objects[0].area, obj.area + 1e-9);  // no slopes to hull features at tau = 0.06
  // A larger margin grows the region: refined once more, then cached again.
  o.refine_margin = 0.3;
  EXPECT_FALSE(mapper.Run(o, p).summary.refinement_reused);
  EXPECT_TRUE(mapper.Run(o, p).summary.refinement_reused);
  EXPECT_EQ(mapper.refinements(), 2);
  // The same run on one thread gives the same model.
  MappingOptions one = o;
  one.num_threads = 1;
  EXPECT_EQ(mapper.Run(one, p).model.vertices, mapper.Run(o, p).model.vertices);
  // Bad options are refused before any work.
  o.alpha = -1;
  EXPECT_THROW(mapper.Run(o, p), OptionError);
}

// Peak features (shape_fusion.h): a narrow top seen by a pass that saw none
// of the flanks (its features are DBSCAN noise in every keyframe that saw
// them) reaches the model when two such features, each seen from two views,
// stand above an object the shapes made; one feature, one view, or a pair
// over clean hull raise nothing.
struct Top {
  Eigen::Vector2d xy;
  double height;
};

// The disk scene plus landmarks `tops` observed only by extra keyframes
// (ids 30, 31, ... 1.5 m below the disk's centre, looking up): top i by the
// keyframes views[i] (indices into those extra keyframes). Returns the
// mapping and the fused model's highest vertex within `radius` of `at`.
MappingResult MapWithTops(const std::vector<Top>& tops, const std::vector<std::vector<int>>& views, int keyframes,
                          const Eigen::Vector2d& at, double radius, double* model_max) {
  Scene s = MakeScene(0.0);
  std::vector<int> top_landmark;
  for (const Top& t : tops) {
    top_landmark.push_back(static_cast<int>(s.input.landmarks.size()));
    s.input.landmarks.push_back({static_cast<std::int64_t>(s.input.landmarks.size()),
                                 Eigen::Vector3d(t.xy.x(), t.xy.y(), -t.height), t.height});
  }
  for (int k = 0; k < keyframes; ++k) {
    MappingKeyframe kf;
    kf.id = 30 + k;
    kf.x_g_cT = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(kDisk.x() + 0.1 * k, kDisk.y(), -1.5));
    for (std::size_t i = 0; i < tops.size(); ++i) {
      if (std::find(views[i].begin(), views[i].end(), k) != views[i].end()) kf.landmarks.push_back(top_landmark[i]);
    }
    std::sort(kf.landmarks.begin(), kf.landmarks.end());
    s.input.keyframes.push_back(std::move(kf));
  }
  Mapper mapper(s.input, s.cad);
  NullProgress p;
  MappingResult r = mapper.Run(MappingOptions{}, p);
  const std::vector<double>& h = *r.model.FindScalar("deviation");
  *model_max = 0;
  for (std::size_t v = 0; v < r.model.num_vertices(); ++v) {
    if ((r.model.vertices[v].head<2>() - at).norm() <= radius) *model_max = std::max(*model_max, h[v]);
  }
  return r;
}

TEST(Mapper, PeakFeaturesSeenByTwoViewsRaiseTheObjectTheShapesFound) {
  const MappingOptions o;
  const Eigen::Vector2d a = kDisk + Eigen::Vector2d(0.02, 0.01), b = kDisk + Eigen::Vector2d(-0.02, 0.0);
  double top = 0;
  // Two tops (0.16 and 0.14 m over the 0.10 m disk, 4 cm apart), each seen by
  // keyframes 30 and 31, where they are each other's only neighbour: DBSCAN
  // noise there, and no other keyframe observed them.
  {
    const MappingResult r = MapWithTops({{a, 0.16}, {b, 0.14}}, {{0, 1}, {0, 1}}, 2, kDisk, kRadius, &top);
    for (const KeyframeShapes& k : r.keyframes) {
      for (const ShapePoint& pt : k.points) {
        if (pt.deviation > 0.12) {
          EXPECT_EQ(pt.cluster, ShapePoint::kNoise);
        }
      }
    }
    EXPECT_EQ(r.summary.peak_features, 2u);
    EXPECT_EQ(r.summary.peak_features_raised, 2u);
    EXPECT_NEAR(top, 0.16, 1e-6);
    ASSERT_EQ(r.objects.size(), 1u);
    EXPECT_NEAR(r.objects[0].max_height, 0.16, 1e-6);
  }
  // Without them the disk's top is the model's top (the reference).
  {
    MapWithTops({}, {}, 0, kDisk, kRadius, &top);
    EXPECT_NEAR(top, kHeight, 1e-6);
  }
  // One top alone, seen by two views (a wrong match tracked over two
  // keyframes): nothing rises.
  {
    const MappingResult r = MapWithTops({{a, 0.16}}, {{0, 1}}, 2, kDisk, kRadius, &top);
    EXPECT_EQ(r.summary.peak_features, 0u);
    EXPECT_NEAR(top, kHeight, 1e-6);
  }
  // Two tops, each seen by one keyframe only: nothing rises.
  {
    const MappingResult r = MapWithTops({{a, 0.16}, {b, 0.14}}, {{0}, {1}}, 2, kDisk, kRadius, &top);
    EXPECT_EQ(r.summary.peak_features, 0u);
    EXPECT_NEAR(top, kHeight, 1e-6);
  }
  // A top below a supported feature nearby is no peak: 0.08 m tops on the
  // 0.10 m disk leave it as it is.
  {
    const MappingResult r = MapWithTops({{a, 0.08}, {b, 0.07}}, {{0, 1}, {0, 1}}, 2, kDisk, kRadius, &top);
    EXPECT_EQ(r.summary.peak_features, 0u);
    EXPECT_NEAR(top, kHeight, 1e-6);
  }
  // Two tops over clean hull, 1 m from the disk, seen by two views: peak
  // features, but no object the shapes made is there, so none rises and no
  // object appears.
  {
    const Eigen::Vector2d far = kDisk + Eigen::Vector2d(-1.0, 0.0);
    const MappingResult r =
        MapWithTops({{far + Eigen::Vector2d(0.02, 0.0), 0.16}, {far, 0.14}}, {{0, 1}, {0, 1}}, 2, far, 0.2, &top);
    EXPECT_EQ(r.summary.peak_features, 2u);
    EXPECT_EQ(r.summary.peak_features_raised, 0u);
    EXPECT_LT(top, o.object_min_height);
    EXPECT_EQ(r.objects.size(), 1u);
  }
}

class CancelAfter final : public Progress {
 public:
  explicit CancelAfter(int updates) : left_(updates) {}
  void Update(double, const std::string&) override { --left_; }
  bool Cancelled() const override { return left_ <= 0; }

 private:
  int left_;
};

TEST(Mapper, CancelledRunLeavesTheCachesUsable) {
  const Scene s = MakeScene(0.0);
  Mapper mapper(s.input, s.cad);
  for (int updates = 1; updates < 6; ++updates) {
    CancelAfter cancel(updates);
    EXPECT_THROW(mapper.Run(MappingOptions{}, cancel), Cancelled) << updates;
  }
  NullProgress p;
  const MappingResult r = mapper.Run(MappingOptions{}, p);
  EXPECT_EQ(r.objects.size(), 1u);
}

}  // namespace
}  // namespace hull
