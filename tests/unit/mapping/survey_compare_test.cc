// Change between two surveys on a scene with a known answer: a flat bottom
// (CAD) and two fused models over it, survey B's with one lump grown, one
// removed and one new; per-vertex change and significance against the
// heights put in, objects classed by position.
#include "results/compare_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "base/error.h"
#include "base/file_io.h"
#include "base/progress.h"
#include "geometry/mesh_io.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

struct Lump {
  Eigen::Vector2d c;
  double h;
};

// A fused model over the plane z = 0 (outward -z; 2 x 2 m, vertices
// `spacing` apart): vertices raised by height(x, y), deviation and a
// constant sigma.
template <typename Height>
TriangleMesh HeightModel(Height height, double sigma, double spacing = 0.05) {
  const int n = static_cast<int>(std::lround(2.0 / spacing));
  TriangleMesh m = test::MakeGrid(n, n, spacing);
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  std::vector<double> dev(m.num_vertices(), 0.0);
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    dev[i] = height(m.vertices[i].head<2>());
    m.vertices[i].z() = -dev[i];
  }
  m.ComputeNormals();
  m.SetScalar("deviation", dev);
  m.SetScalar("sigma", std::vector<double>(m.num_vertices(), sigma));
  return m;
}

// The lumps as cones of radius 0.3.
TriangleMesh Model(const std::vector<Lump>& lumps, double sigma, double spacing = 0.05) {
  return HeightModel(
      [&](const Eigen::Vector2d& p) {
        double h = 0;
        for (const Lump& l : lumps) h = std::max(h, l.h * std::max(0.0, 1 - (p - l.c).norm() / 0.3));
        return h;
      },
      sigma, spacing);
}

std::vector<DetectedObject> Objects(const std::vector<Lump>& lumps, const char* prefix) {
  std::vector<DetectedObject> out;
  for (std::size_t i = 0; i < lumps.size(); ++i) {
    DetectedObject o;
    o.id = std::string(prefix) + std::to_string(i + 1);
    // Detected centroids a few centimetres off, as a survey finds them.
    o.centroid_m = Eigen::Vector3d(lumps[i].c.x() + 0.03, lumps[i].c.y() - 0.02, 0.0);
    o.max_height = lumps[i].h;
    out.push_back(o);
  }
  return out;
}

TEST(SurveyCompare, ChangesPerVertexAndPerObject) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const std::vector<Lump> a = {{{0.5, 0.5}, 0.10}, {{1.0, 1.5}, 0.12}, {{1.5, 0.5}, 0.08}};
  const std::vector<Lump> b = {{{0.5, 0.5}, 0.101}, {{1.0, 1.5}, 0.17}, {{1.6, 1.6}, 0.09}};
  const double sigma = 0.004;
  const SurveyComparison c =
      CompareSurveys(cad, Model(a, sigma), Objects(a, "a"), Model(b, sigma), Objects(b, "b"), SurveyCompareOptions{});
  ASSERT_EQ(c.objects.size(), 4u);
  EXPECT_EQ(c.objects[0].kind, ObjectChangeKind::kUnchanged);
  EXPECT_EQ(c.objects[0].id_a, "a1");
  EXPECT_EQ(c.objects[1].kind, ObjectChangeKind::kGrown);
  EXPECT_EQ(c.objects[1].id_b, "b2");
  EXPECT_NEAR(c.objects[1].change, 0.05, 1e-12);
  EXPECT_EQ(c.objects[2].kind, ObjectChangeKind::kNew);
  EXPECT_EQ(c.objects[2].id_b, "b3");
  EXPECT_EQ(c.objects[3].kind, ObjectChangeKind::kRemoved);
  EXPECT_EQ(c.objects[3].id_a, "a3");
  // Per vertex: the change is B's height minus A's at the same CAD point
  // (the grids coincide), significant beyond 1.96 sqrt(2) sigma.
  const std::vector<double>& change = *c.model.FindScalar("change");
  const std::vector<double>& sig = *c.model.FindScalar("change_significant");
  const std::vector<double>& s = *c.model.FindScalar("change_sigma");
  const TriangleMesh ma = Model(a, sigma), mb = Model(b, sigma);
  std::size_t expected_significant = 0;
  for (std::size_t i = 0; i < change.size(); ++i) {
    const double truth = (*mb.FindScalar("deviation"))[i] - (*ma.FindScalar("deviation"))[i];
    ASSERT_NEAR(change[i], truth, 1e-9) << i;
    EXPECT_NEAR(s[i], sigma * std::sqrt(2.0), 1e-12);
    const bool significant = std::abs(truth) > 1.96 * sigma * std::sqrt(2.0);
    EXPECT_EQ(sig[i] == 1.0, significant) << i;
    expected_significant += significant;
  }
  EXPECT_EQ(c.significant_vertices, expected_significant);
  EXPECT_GT(expected_significant, 50u);
  // Written and read back as the command line does.
  const std::string dir = (std::filesystem::path(::testing::TempDir()) / "hi_compare").string();
  WriteSurveyComparison(c, dir);
  EXPECT_TRUE(std::filesystem::exists(dir + "/model.ply"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/objects.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/compare.json"));
  // Bad options are refused.
  SurveyCompareOptions bad;
  bad.match_radius = 0;
  EXPECT_THROW(CompareSurveys(cad, ma, {}, mb, {}, bad), OptionError);
}

// The second survey's adjustment placed the model 0.4 m and 1.5 degrees
// along the flat surface from the first's (the free directions of a flat
// bottom): registered by the objects in common, nothing is new or removed
// but what changed, and the height field is compared at the same places.
TEST(SurveyCompare, RegistersTheSecondSurveyBeforeComparing) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const std::vector<Lump> a = {{{0.4, 0.4}, 0.10}, {{1.6, 0.5}, 0.12}, {{0.5, 1.6}, 0.08}, {{1.5, 1.5}, 0.09}};
  std::vector<Lump> moved = a;
  moved[1].h = 0.16;                                                           // grew by 4 cm
  const Pose x_ba = Pose::FromXyzRpy(0.30, -0.25, 0, 0, 0, 1.5 * M_PI / 180);  // B's map of A's places
  for (Lump& l : moved) l.c = (x_ba * Eigen::Vector3d(l.c.x(), l.c.y(), 0)).head<2>();
  // The peaks that register the maps stand at model vertices: 1 cm apart.
  const TriangleMesh ma = Model(a, 0.004, 0.01), mb = Model(moved, 0.004, 0.01);
  const std::vector<DetectedObject> oa = Objects(a, "a"), ob = Objects(moved, "b");
  SurveyCompareOptions o;
  const SurveyComparison c = CompareSurveys(cad, ma, oa, mb, ob, o);
  ASSERT_TRUE(c.registration.registered);
  EXPECT_EQ(c.registration.inliers, 4);
  EXPECT_LE(c.registration.identity_inliers, 1);
  EXPECT_LT(Pose::DistanceBetween(c.registration.a_from_b, x_ba.Inverse()), 0.01);
  ASSERT_EQ(c.objects.size(), 4u);
  for (const ObjectChange& x : c.objects) {
    EXPECT_EQ(x.kind, x.id_b == "b2" ? ObjectChangeKind::kGrown : ObjectChangeKind::kUnchanged) << x.id_b;
    EXPECT_EQ(x.id_a.substr(1), x.id_b.substr(1));
  }
  // Per vertex: where nothing changed the change is within the grid's
  // sampling of the cones (5 cm spacing) -- without registration the
  // displaced lumps read as +-10 cm.
  const std::vector<double>& change = *c.model.FindScalar("change");
  double worst_unchanged = 0;
  for (std::size_t i = 0; i < change.size(); ++i) {
    const Eigen::Vector3d p = c.registration.a_from_b * mb.vertices[i];
    if ((p.head<2>() - a[1].c).norm() < 0.45) continue;                          // the grown lump
    if (p.x() < 0.05 || p.y() < 0.05 || p.x() > 1.95 || p.y() > 1.95) continue;  // moved past the grid
    worst_unchanged = std::max(worst_unchanged, std::abs(change[i]));
  }
  EXPECT_LT(worst_unchanged, 0.03);
  o.register_surveys = false;
  const SurveyComparison raw = CompareSurveys(cad, ma, oa, mb, ob, o);
  EXPECT_FALSE(raw.registration.registered);
  EXPECT_GE(raw.objects.size(), 7u);  // all new and removed
  double worst_raw = 0;
  for (double v : *raw.model.FindScalar("change")) worst_raw = std::max(worst_raw, std::abs(v));
  EXPECT_GT(worst_raw, 0.07);
}

// An object one survey's detection missed is looked up in that survey's
// height field: still there (unchanged, grown) rather than removed or new.
TEST(SurveyCompare, LooksUpAnObjectMissedByOneMapInItsHeightField) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const std::vector<Lump> a = {{{0.5, 0.5}, 0.10}, {{1.5, 0.5}, 0.07}, {{1.0, 1.5}, 0.12}};
  const std::vector<Lump> b = {{{0.5, 0.5}, 0.10}, {{1.5, 0.5}, 0.068}, {{1.0, 1.5}, 0.17}};
  std::vector<DetectedObject> oa = Objects(a, "a"), ob = Objects(b, "b");
  ob.erase(ob.begin() + 1);  // B's detection missed the 0.068 m lump
  oa.erase(oa.begin() + 2);  // A's missed the 0.12 m one, which grew to 0.17 m
  for (auto* list : {&oa, &ob}) {
    for (DetectedObject& o : *list) o.area = 0.05;
  }
  const SurveyComparison c = CompareSurveys(cad, Model(a, 0.004), oa, Model(b, 0.004), ob, SurveyCompareOptions{});
  ASSERT_EQ(c.objects.size(), 3u);
  EXPECT_EQ(c.objects[0].kind, ObjectChangeKind::kUnchanged);  // a1 / b1, both detected
  EXPECT_FALSE(c.objects[0].from_height_field);
  EXPECT_EQ(c.objects[1].id_b, "b3");  // B's 0.17 m, A's field 0.12 m there
  EXPECT_TRUE(c.objects[1].from_height_field);
  EXPECT_EQ(c.objects[1].kind, ObjectChangeKind::kGrown);
  EXPECT_NEAR(c.objects[1].change, 0.05, 0.005);
  EXPECT_EQ(c.objects[2].id_a, "a2");  // still in B's field, not removed
  EXPECT_TRUE(c.objects[2].from_height_field);
  EXPECT_EQ(c.objects[2].kind, ObjectChangeKind::kUnchanged);
  EXPECT_NEAR(c.objects[2].height_b, 0.068, 0.005);
}

// An object made of lumps `which` of `lumps` with its footprint's vertices
// (those of the model above 2 cm nearest one of them), as the mapping
// writes them.
DetectedObject Joined(const TriangleMesh& model, const std::vector<Lump>& lumps, const std::vector<std::size_t>& which,
                      const std::string& id) {
  DetectedObject o;
  o.id = id;
  const std::vector<double>& dev = *model.FindScalar("deviation");
  for (std::size_t i = 0; i < model.num_vertices(); ++i) {
    if (dev[i] <= 0.02) continue;
    std::size_t nearest = 0;
    for (std::size_t k = 1; k < lumps.size(); ++k) {
      if ((model.vertices[i].head<2>() - lumps[k].c).norm() < (model.vertices[i].head<2>() - lumps[nearest].c).norm()) {
        nearest = k;
      }
    }
    if (std::find(which.begin(), which.end(), nearest) == which.end()) continue;
    o.vertices.push_back(static_cast<int>(i));
    o.max_height = std::max(o.max_height, dev[i]);
  }
  for (const std::size_t k : which) o.centroid_m += Eigen::Vector3d(lumps[k].c.x(), lumps[k].c.y(), 0) / which.size();
  return o;
}

// Touching lumps that one map splits and the other joins: the joined
// object's max stands on one lump, so comparing objects' max heights saw a
// grown lump next to the highest one as unchanged (or a neighbour's top as
// growth). Compared at each peak, the grown lump is grown and its
// neighbours unchanged, whichever way the maps cut them.
TEST(SurveyCompare, ComparesJoinedAndSplitLumpsAtTheirPeaks) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  // Three lumps in a row, 0.4 m apart (their cones touch): the middle one
  // grows by 5 cm, below the highest.
  const std::vector<Lump> a = {{{0.6, 1.0}, 0.20}, {{1.0, 1.0}, 0.12}, {{1.4, 1.0}, 0.15}};
  std::vector<Lump> b = a;
  b[1].h = 0.17;
  const TriangleMesh ma = Model(a, 0.004), mb = Model(b, 0.004);
  SurveyCompareOptions o;
  o.register_surveys = false;  // nothing to register: three peaks in a row
  // A splits all three; B joins them into one object.
  const std::vector<DetectedObject> split = {Joined(ma, a, {0}, "a1"), Joined(ma, a, {1}, "a2"),
                                             Joined(ma, a, {2}, "a3")};
  const std::vector<DetectedObject> joined = {Joined(mb, b, {0, 1, 2}, "b1")};
  for (const bool a_split : {true, false}) {
    // The other way round: A joins, B splits.
    const std::vector<DetectedObject> oa =
        a_split ? split : std::vector<DetectedObject>{Joined(ma, a, {0, 1, 2}, "a1")};
    const std::vector<DetectedObject> ob =
        a_split
            ? joined
            : std::vector<DetectedObject>{Joined(mb, b, {0}, "b1"), Joined(mb, b, {1}, "b2"), Joined(mb, b, {2}, "b3")};
    const SurveyComparison c = CompareSurveys(cad, ma, oa, mb, ob, o);
    ASSERT_EQ(c.objects.size(), 3u) << a_split;
    int grown = 0;
    for (const ObjectChange& x : c.objects) {
      EXPECT_FALSE(x.from_height_field);
      if (x.kind == ObjectChangeKind::kGrown) {
        ++grown;
        EXPECT_NEAR(x.change, 0.05, 1e-9);
        EXPECT_NEAR(x.height_b, 0.17, 1e-9);
        EXPECT_NEAR(x.centroid.x(), 1.0, 1e-9);  // the grown lump's top
        EXPECT_EQ(a_split ? x.id_a : x.id_b, a_split ? "a2" : "b2");
      } else {
        EXPECT_EQ(x.kind, ObjectChangeKind::kUnchanged) << x.id_a << " " << x.id_b;
        EXPECT_NEAR(x.change, 0.0, 1e-9);
      }
    }
    EXPECT_EQ(grown, 1) << a_split;
  }
}

// The footprints' vertices travel in objects.json; an index model.ply does
// not have is refused naming the file and field.
TEST(SurveyCompare, ReadsTheObjectsFootprintsAndRefusesBadOnes) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "hi_compare_vertices";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<Lump> lumps = {{{0.5, 0.5}, 0.10}};
  MeshSaveOptions ply;
  ply.binary = true;
  SaveMesh(Model(lumps, 0.004), (dir / "model.ply").string(), ply);
  auto objects = [&](const std::string& vertices) {
    WriteFileAtomic((dir / "objects.json").string(),
                    "{\"format\": \"hull-mapping-objects\", \"version\": 1, \"objects\": [\n"
                    "{\"id\": \"obj-1\", \"centroid\": [0.5, 0.5, 0], \"max_height\": 0.1,\n"
                    " \"vertices\": " +
                        vertices + "}]}");
  };
  objects("[10, 11, 12]");
  const MappingResultsOnDisk r = ReadMappingResultsForCompare(dir.string());
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.objects[0].vertices, (std::vector<int>{10, 11, 12}));
  for (const char* bad : {"[10, 1681]", "[-1]", "[2.5]", "[\"x\"]"}) {
    objects(bad);
    try {
      ReadMappingResultsForCompare(dir.string());
      ADD_FAILURE() << "no error for " << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("objects.json"), std::string::npos) << what;
      EXPECT_NE(what.find("vertices"), std::string::npos) << what;
      EXPECT_NE(what.find(":3"), std::string::npos) << what;  // the line
    }
  }
}

// Flat tops measured with noise give many local maxima each. Three boxes,
// nothing moved or changed, 3 mm of noise in each survey: the maps are
// registered by one top per object, so the noise peaks cannot vote for a
// motion (they did when every peak voted: 0.17 m and 7 degrees on one
// box), and no change is reported.
TEST(SurveyCompare, NoisyFlatTopsNeitherMoveTheMapsNorChange) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const std::vector<Eigen::Vector2d> centres = {{0.5, 0.5}, {1.4, 0.6}, {0.8, 1.5}};
  auto boxes = [&](unsigned seed) {
    return HeightModel(
        [&, seed](const Eigen::Vector2d& p) {
          for (const Eigen::Vector2d& c : centres) {
            if ((p - c).cwiseAbs().maxCoeff() <= 0.25) {
              // Deterministic noise of +-3 mm per vertex and survey.
              const double u = std::sin(1e4 * p.x() + 7e3 * p.y() + seed) * 43758.5453;
              return 0.10 + 0.006 * (u - std::floor(u) - 0.5);
            }
          }
          return 0.0;
        },
        0.004);
  };
  const TriangleMesh ma = boxes(1), mb = boxes(2);
  std::vector<DetectedObject> oa, ob;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    for (auto* list : {&oa, &ob}) {
      DetectedObject o;
      o.id = std::string(list == &oa ? "a" : "b") + std::to_string(k + 1);
      o.centroid_m = Eigen::Vector3d(centres[k].x(), centres[k].y(), 0);
      o.area = 0.25;
      list->push_back(o);
    }
  }
  const SurveyComparison c = CompareSurveys(cad, ma, oa, mb, ob, SurveyCompareOptions{});
  EXPECT_LT(c.registration.translation, 0.10);
  EXPECT_LT(c.registration.rotation, 2.0 * M_PI / 180);
  ASSERT_GE(c.objects.size(), 3u);
  for (const ObjectChange& x : c.objects) {
    EXPECT_EQ(x.kind, ObjectChangeKind::kUnchanged) << x.id_a << " " << x.id_b;
    EXPECT_EQ(x.id_a.substr(1), x.id_b.substr(1));
    EXPECT_LT(std::abs(x.change), 0.007);
  }
  // Per vertex only the noise (|change| <= 6 mm) and the boxes' rims.
  double worst = 0;
  for (double v : *c.model.FindScalar("change")) worst = std::max(worst, std::abs(v));
  EXPECT_LT(worst, 0.02);
}

// With fewer than three tops in common the maps can be neither registered
// nor known to be in place: each peak's heights are then read within the
// match radius, so a lump 0.12 m off in B's map is still unchanged (read
// within the reach of a registered pair it came out grown and shrunk).
TEST(SurveyCompare, UnregisteredMapsAreReadWithinTheMatchRadius) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const std::vector<Lump> a = {{{1.0, 1.0}, 0.15}}, b = {{{1.12, 1.0}, 0.15}};
  const SurveyComparison c =
      CompareSurveys(cad, Model(a, 0.004), Objects(a, "a"), Model(b, 0.004), Objects(b, "b"), SurveyCompareOptions{});
  EXPECT_FALSE(c.registration.registered);
  EXPECT_DOUBLE_EQ(c.reach, SurveyCompareOptions{}.match_radius);
  ASSERT_EQ(c.objects.size(), 1u);
  EXPECT_EQ(c.objects[0].kind, ObjectChangeKind::kUnchanged);
  EXPECT_EQ(c.objects[0].id_a, "a1");
  EXPECT_EQ(c.objects[0].id_b, "b1");
}

// Results written before objects.json listed the footprints: an object's
// footprint is the region above the change threshold nearest its
// centroid, whatever its shape. A ring of fouling (its centroid on bare
// hull) compared with itself is one unchanged row, neither removed nor
// "missed by A's detection".
TEST(SurveyCompare, OlderResultsGetTheirFootprintsFromTheHeightField) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const Eigen::Vector2d centre(1.0, 1.0);
  const TriangleMesh ring = HeightModel(
      [&](const Eigen::Vector2d& p) {
        const double r = (p - centre).norm();
        return std::abs(r - 0.3) <= 0.06
                   ? 0.08 * (1 - std::abs(r - 0.3) / 0.06) + 0.002 * std::cos(7 * std::atan2(p.y() - 1, p.x() - 1))
                   : 0.0;
      },
      0.004);
  DetectedObject listed;  // as this version writes it
  listed.id = "b1";
  listed.centroid_m = Eigen::Vector3d(centre.x(), centre.y(), 0);
  listed.area = 2 * M_PI * 0.3 * 0.06;
  const std::vector<double>& dev = *ring.FindScalar("deviation");
  for (std::size_t i = 0; i < ring.num_vertices(); ++i) {
    if (dev[i] >= 0.03) listed.vertices.push_back(static_cast<int>(i));
  }
  DetectedObject old = listed;  // as an earlier version wrote it
  old.id = "a1";
  old.vertices.clear();
  const SurveyComparison c = CompareSurveys(cad, ring, {old}, ring, {listed}, SurveyCompareOptions{});
  ASSERT_EQ(c.objects.size(), 1u);
  EXPECT_EQ(c.objects[0].kind, ObjectChangeKind::kUnchanged);
  EXPECT_EQ(c.objects[0].id_a, "a1");
  EXPECT_EQ(c.objects[0].id_b, "b1");
  EXPECT_FALSE(c.objects[0].from_height_field);
  EXPECT_NEAR(c.objects[0].change, 0.0, 1e-12);
}

TEST(SurveyCompare, ReportsProgressAndStopsWhenCancelled) {
  TriangleMesh cad = test::MakeGrid(4, 4, 0.5);
  for (Face& f : cad.faces) std::swap(f[1], f[2]);
  cad.ComputeNormals();
  const std::vector<Lump> a = {{{0.5, 0.5}, 0.10}};
  double last = -1;
  bool monotone = true;
  CallbackProgress progress([&](double f, const std::string&) {
    monotone = monotone && f >= last;
    last = f;
  });
  const SurveyComparison c =
      CompareSurveys(cad, Model(a, 0.004), Objects(a, "a"), Model(a, 0.004), Objects(a, "b"), {}, progress);
  EXPECT_TRUE(monotone);
  EXPECT_DOUBLE_EQ(last, 1.0);
  EXPECT_EQ(c.significant_vertices, 0u);
  CallbackProgress cancelled;
  cancelled.RequestCancel();
  EXPECT_THROW(CompareSurveys(cad, Model(a, 0.004), {}, Model(a, 0.004), {}, {}, cancelled), Cancelled);
}

TEST(SurveyCompare, FindsTheMappingResultsOfAFolder) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(::testing::TempDir()) / "hi_compare_find";
  fs::remove_all(root);
  fs::create_directories(root / "run" / "mapping");
  fs::create_directories(root / "map");
  fs::create_directories(root / "empty");
  WriteFileAtomic((root / "run" / "mapping" / "model.ply").string(), "x");
  WriteFileAtomic((root / "map" / "model.ply").string(), "x");
  EXPECT_EQ(FindMappingResults((root / "run").string()), (root / "run" / "mapping").string());
  EXPECT_EQ(FindMappingResults((root / "map").string()), (root / "map").string());
  EXPECT_FALSE(FindMappingResults((root / "empty").string()));
  NullProgress none;
  try {
    RunSurveyComparison((root / "map").string(), (root / "empty").string(), "", 1.0, {}, none);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hull
