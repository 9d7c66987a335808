// Issue 14: no absurd input reaches PCL, Embree or Ceres; a runaway
// adjustment stops with an InputError naming the likely input; the same
// adjustment twice writes identical files; the capped validate -> adjust run
// ends every input quickly.
#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "adjust/bundle_adjuster.h"
#include "adjust/cost_watch.h"
#include "base/file_io.h"
#include "geometry/mesh_index.h"
#include "geometry/mesh_io.h"
#include "geometry/query_bounds.h"
#include "pipeline/capped_run.h"
#include "registration/gicp.h"
#include "results/adjustment_files.h"
#include "support/test_files.h"
#include "support/test_meshes.h"
#include "support/test_surveys.h"
#include "survey/survey_io.h"
#include "survey/survey_plausibility.h"

namespace hull {
namespace {

using testing::ReadText;
using testing::ScratchDir;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---- mesh loading ---------------------------------------------------------------

// A binary STL of n triangles, all with the same three collinear corners.
std::string DegenerateStl(std::uint32_t n) {
  std::string data(84 + 50 * static_cast<std::size_t>(n), '\0');
  std::memcpy(&data[80], &n, 4);
  for (std::uint32_t t = 0; t < n; ++t) {
    float* v = reinterpret_cast<float*>(&data[84 + 50 * static_cast<std::size_t>(t) + 12]);
    const float corners[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    std::memcpy(v, corners, sizeof(corners));
  }
  return data;
}

TEST(RobustMesh, DegenerateMeshBombIsRefusedQuickly) {
  const ScratchDir tmp("robust_bomb");
  // Gzipped: 2 M degenerate triangles (100 MB) from a few hundred kB stop at the gzip cap.
  const std::string gz = tmp / "bomb.stl.gz";
  {
    const std::string stl = DegenerateStl(2000000);
    gzFile f = gzopen(gz.c_str(), "wb9");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(gzwrite(f, stl.data(), static_cast<unsigned>(stl.size())), static_cast<int>(stl.size()));
    gzclose(f);
  }
  auto t0 = Clock::now();
  try {
    LoadMesh(gz);
    FAIL() << "the bomb loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("decompression bomb"), std::string::npos) << e.what();
  }
  EXPECT_LT(Since(t0), 20.0);  // loose: a guard against inflating whole, not a timing test
  // Uncompressed: the degenerate triangles are found before anything is allocated.
  const std::string plain = tmp / "flat.stl";
  WriteFileAtomic(plain, DegenerateStl(200000));
  try {
    LoadMesh(plain);
    FAIL() << "a mesh of zero-area triangles loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("200000 of 200000 triangles have zero area"), std::string::npos) << e.what();
  }
}

TEST(RobustMesh, AbsurdCoordinatesAndZeroAreaAreRefused) {
  const ScratchDir tmp("robust_mesh");
  TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 2, 3});
  box.vertices[3].x() = 1e30;
  SaveMesh(box, tmp / "far.ply");
  try {
    LoadMesh(tmp / "far.ply");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(vertex 3)"), std::string::npos) << e.what();
  }
  // A scale that takes a sane mesh beyond the bound is refused the same way.
  MeshLoadOptions huge;
  huge.scale = 1e8;
  SaveMesh(test::MakeBox({0, 0, 0}, {1, 2, 3}), tmp / "box.ply");
  EXPECT_THROW(LoadMesh(tmp / "box.ply", huge), InputError);
  EXPECT_NO_THROW(LoadMesh(tmp / "box.ply"));
}

// ---- the mesh index and GICP: the library boundaries -------------------------------

TEST(RobustBoundaries, MeshIndexQueriesWithAbsurdPointsNeverReachEmbree) {
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 1, 1});
  const MeshIndex index(box);
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d(1e30, 0, 0),
                                   Eigen::Vector3d(0, -INFINITY, 0), Eigen::Vector3d(0, 0, 2e9)}) {
    EXPECT_FALSE(index.Raycast(q, {0, 0, 1}).hit);
    const ClosestPoint c = index.Closest(q);
    EXPECT_TRUE(std::isinf(c.distance));
    EXPECT_GE(c.face, 0);
    EXPECT_LT(c.face, static_cast<int>(box.faces.size()));
    const SurfaceDistance d = index.OrthogonalSignedDistance(q);
    EXPECT_TRUE(std::isnan(d.signed_distance));
    EXPECT_GE(d.face, 0);
    EXPECT_TRUE(std::isnan(index.SignedDistance(q)));
    EXPECT_GE(index.NearestVertex(q), 0);
  }
  EXPECT_FALSE(index.Raycast({0.5, 0.5, -1}, {NAN, 0, 1}).hit);
  EXPECT_TRUE(index.Raycast({0.5, 0.5, -1}, {0, 0, 1}).hit);  // a sane ray still hits
  TriangleMesh far = box;
  far.vertices[0].z() = 1e30;
  try {
    MeshIndex bad(far);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(vertex 0)"), std::string::npos) << e.what();
  }
}

TEST(RobustBoundaries, GicpRefusesNonFiniteAndAbsurdPoints) {
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 200; ++i) cloud.emplace_back(0.1 * (i % 20), 0.1 * (i / 20), 0.01 * (i % 7));
  for (double bad : {static_cast<double>(NAN), 1e30, -2e9}) {
    std::vector<Eigen::Vector3d> source = cloud;
    source[17].y() = bad;
    try {
      AlignGicp(source, cloud, Pose());
      FAIL() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("source point 17"), std::string::npos) << e.what();
    }
    EXPECT_THROW(AlignGicp(cloud, source, Pose()), InputError);
  }
}

// ---- the solver: runaway detection ---------------------------------------------------

TEST(CostWatch, StopsNonFiniteAbsurdAndStalledCostsButNotSaneOnes) {
  CostWatchOptions o;
  {
    CostWatch w(o, 1000);
    EXPECT_NE(w.Observe(0, 1e12).find("initial cost"), std::string::npos);  // 1e9 per residual
  }
  {
    CostWatch w(o, 1000);
    EXPECT_EQ(w.Observe(0, 5e5), "");
    EXPECT_NE(w.Observe(1, NAN).find("the cost became nan"), std::string::npos);
  }
  {
    // Absurd (1e6 per residual) and flat: stopped after stall_iterations.
    CostWatch w(o, 1000);
    std::string why;
    int it = 0;
    for (; it < 50 && why.empty(); ++it) why = w.Observe(it, 1e9 * (1 - 1e-6 * it));
    EXPECT_EQ(it, o.stall_iterations + 1);
    EXPECT_NE(why.find("no progress over 10 iterations"), std::string::npos) << why;
  }
  {
    // Sane (0.5 per residual) and flat, or absurd but falling fast: never stopped.
    CostWatch flat(o, 1000), falling(o, 1000);
    for (int it = 0; it < 100; ++it) {
      EXPECT_EQ(flat.Observe(it, 500), "");
      EXPECT_EQ(falling.Observe(it, 1e10 * std::pow(0.5, it)), "");
    }
  }
  o.stall_iterations = 0;
  EXPECT_THROW(o.Check(), OptionError);
}

AdjustmentOptions QuickOptions() {
  AdjustmentOptions o;
  o.max_iterations = 30;
  return o;
}

TEST(RobustAdjust, AnInconsistentOdometryEdgeEndsTheSolveNamingIt) {
  const SimulatedSurvey& sim = test::SmallSurvey();
  SurveyBundle b = sim.bundle;
  // Finite, and within the validator's per-edge bounds (a non-consecutive
  // edge, 100 m off, with the tightest drift rate allowed): only the
  // solver's cost shows it.
  b.manifest.noise.odometry_translation_rate = 1e-7;
  const NavRecord &a = b.nav[0], &c = b.nav[5];
  Vector6d z = (Pose::FromVector(a.x_gv).Inverse() * Pose::FromVector(c.x_gv)).ToVector();
  z[0] += 100;
  b.odometry.push_back({a.keyframe, c.keyframe, z});
  std::vector<Problem> found;
  CheckSurveyPlausibility(b, SurveyPlaces::ForBundle(""), found);
  ASSERT_TRUE(found.empty()) << found.front().ToString();
  NullProgress p;
  const auto t0 = Clock::now();
  try {
    RunAdjustment(b, sim.cad, Pose::FromVector(*b.manifest.model_pose_guess), QuickOptions(), p);
    FAIL() << "the adjustment ran on";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the adjustment stopped: the initial cost"), std::string::npos) << what;
    EXPECT_NE(what.find("the odometry " + std::to_string(a.keyframe) + " -> " + std::to_string(c.keyframe)),
              std::string::npos)
        << what;
  }
  EXPECT_LT(Since(t0), 30.0);
}

TEST(RobustAdjust, AbsurdInMemoryBundlesAreRefusedBeforeCeres) {
  const SimulatedSurvey& sim = test::SmallSurvey();
  NullProgress p;
  const Pose guess = Pose::FromVector(*sim.bundle.manifest.model_pose_guess);
  for (double x : {1e308, 1e30, 1e10, 1e6}) {
    SurveyBundle b = sim.bundle;
    b.nav[1].x_gv[0] = x;
    try {
      RunAdjustment(b, sim.cad, guess, QuickOptions(), p);
      FAIL() << x;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("nav.csv"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("(x of row 2)"), std::string::npos) << e.what();
    }
  }
  SurveyBundle b = sim.bundle;
  b.manifest.noise.pixel_sigma = 2e9;
  EXPECT_THROW(RunAdjustment(b, sim.cad, guess, QuickOptions(), p), InputError);
  b = sim.bundle;
  EXPECT_THROW(RunAdjustment(b, sim.cad, Pose::FromXyzRpy(1e30, 0, 0, 0, 0, 0), QuickOptions(), p), InputError);
}

// ---- deterministic results -------------------------------------------------------------

// Numbers of a CSV text, in order (fields that do not parse are skipped).
std::vector<double> Numbers(const std::string& text) {
  std::vector<double> out;
  std::size_t i = text.find('\n');  // after the header
  while (i != std::string::npos && i < text.size()) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str() + i + 1, &end);
    if (end != text.c_str() + i + 1) out.push_back(v);
    i = text.find_first_of(",\n", i + 1);
  }
  return out;
}

TEST(RobustAdjust, TheSameAdjustmentTwiceWritesIdenticalFiles) {
  const SimulatedSurvey& sim = test::SmallSurvey();
  const ScratchDir tmp("robust_determinism");
  NullProgress p;
  const Pose guess = Pose::FromVector(*sim.bundle.manifest.model_pose_guess);
  const char* files[] = {"adjustment.json", "poses.csv", "landmarks.csv", "dvl_residuals.csv"};
  // One thread: byte-identical files, run after run, whatever the heap holds
  // (the third run starts with other blocks allocated, so malloc places the
  // solver's and SuiteSparse's memory elsewhere: the covariances' column
  // order and the dense kernels' alignment no longer follow it).
  AdjustmentOptions o = QuickOptions();
  o.num_threads = 1;
  for (const char* dir : {"a", "b"}) WriteAdjustmentResult(RunAdjustment(sim.bundle, sim.cad, guess, o, p), tmp / dir);
  {
    std::vector<std::vector<char>> clutter;
    for (std::size_t n = 24; n < 3000000; n = n * 3 + 40) clutter.emplace_back(n, 'x');
    WriteAdjustmentResult(RunAdjustment(sim.bundle, sim.cad, guess, o, p), tmp / "e");
  }
  for (const char* f : files) {
    const std::string a = ReadText(tmp / (std::string("a/") + f));
    EXPECT_FALSE(a.empty()) << f;
    for (const char* other : {"b/", "e/"}) {
      EXPECT_TRUE(a == ReadText(tmp / (std::string(other) + f))) << f << " differs between runs (" << other << ")";
    }
  }
  // The wall times are kept apart, and read back.
  const AdjustmentResult back = ReadAdjustmentResult(tmp / "a");
  EXPECT_GT(back.seconds, 0);
  EXPECT_EQ(ReadText(tmp / "a/adjustment.json").find("seconds"), std::string::npos);
  // Two threads (Ceres adds the reduced system's blocks in thread order):
  // the same rows, and values that agree to far below the survey's noise.
  o.num_threads = 2;
  for (const char* dir : {"c", "d"}) WriteAdjustmentResult(RunAdjustment(sim.bundle, sim.cad, guess, o, p), tmp / dir);
  for (const char* f : {"poses.csv", "landmarks.csv"}) {
    const std::vector<double> c = Numbers(ReadText(tmp / (std::string("c/") + f)));
    const std::vector<double> d = Numbers(ReadText(tmp / (std::string("d/") + f)));
    ASSERT_EQ(c.size(), d.size()) << f;
    for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(c[i], d[i], 1e-6 * (1 + std::abs(c[i]))) << f << " " << i;
  }
}

// ---- the capped run ---------------------------------------------------------------------

TEST(CappedRun, EndsSaneAndAbsurdBundlesQuickly) {
  const ScratchDir tmp("robust_capped");
  test::WriteSmallSurvey(tmp / "ok");
  CappedRunOptions o;
  o.max_iterations = 5;
  CappedRunOutcome r = RunCappedValidateAdjust(tmp / "ok", o);
  EXPECT_FALSE(r.refused) << r.message;
  EXPECT_EQ(r.stage, CappedRunOutcome::Stage::kDone);
  EXPECT_LE(r.iterations, 5 * (o.rejection_rounds + 1));
  // The nav.csv edit: refused by validation, never adjusted.
  SurveyBundle b = test::SmallSurvey().bundle;
  b.nav[1].x_gv[0] = 1e30;
  WriteSurveyBundle(b, tmp / "far");
  SaveMesh(test::SmallSurvey().cad, tmp / "far/hull.ply");
  r = RunCappedValidateAdjust(tmp / "far", o);
  EXPECT_TRUE(r.refused);
  EXPECT_EQ(r.stage, CappedRunOutcome::Stage::kValidate);
  EXPECT_NE(r.message.find("nav.csv:3:"), std::string::npos) << r.message;
  EXPECT_STREQ(CappedRunStageName(r.stage), "validate");
  o.max_seconds = 0;
  EXPECT_THROW(RunCappedValidateAdjust(tmp / "ok", o), OptionError);
}

// The survey harnesses' corpus (tests/fuzz/corpus/survey_*: seeds and what
// fuzzing found) through the whole path the harnesses run, in every build:
// each input replaces its file in a copy of the fuzzing base bundle (which
// validates and adjusts as it is); the reader may only refuse, and the capped
// run ends at a stage with a refusal or a finished adjustment, each within
// its cap.
TEST(CappedRun, FuzzCorpusRunsTheWholePathWithinItsCaps) {
  namespace fs = std::filesystem;
  const fs::path fuzz = fs::path(HI_SOURCE_DIR) / "tests/fuzz";
  const std::vector<std::pair<std::string, std::string>> harnesses = {
      {"survey_json", "survey.json"},     {"survey_nav", "nav.csv"},           {"survey_odometry", "odometry.csv"},
      {"survey_dvl", "dvl.csv"},          {"survey_features", "features.csv"}, {"survey_landmarks", "landmarks.csv"},
      {"survey_truth", "truth/poses.csv"}};
  const CappedRunOptions caps = CappedRunOptions::PerFuzzInput();
  const ScratchDir tmp("robust_corpus");
  // The base itself goes the whole way.
  fs::copy(fuzz / "base/survey", tmp / "base", fs::copy_options::recursive);
  const CappedRunOutcome base = RunCappedValidateAdjust(tmp / "base", caps);
  ASSERT_EQ(base.stage, CappedRunOutcome::Stage::kDone) << base.message;
  int inputs = 0, done = 0;
  for (const auto& [harness, file] : harnesses) {
    for (const auto& entry : fs::directory_iterator(fuzz / "corpus" / harness)) {
      const fs::path dir = tmp / "case";
      fs::remove_all(dir);
      fs::copy(fuzz / "base/survey", dir, fs::copy_options::recursive);
      fs::copy_file(entry.path(), dir / file, fs::copy_options::overwrite_existing);
      try {
        ReadSurveyBundle(dir.string());
      } catch (const InputError&) {
      }
      const CappedRunOutcome r = RunCappedValidateAdjust(dir.string(), caps);
      SCOPED_TRACE(harness + "/" + entry.path().filename().string());
      EXPECT_TRUE(r.refused || r.stage == CappedRunOutcome::Stage::kDone);
      EXPECT_LE(r.iterations, caps.max_iterations * (caps.rejection_rounds + 1));
      // Two solves at most, each capped at max_seconds; alignment and loading
      // of a 69-triangle mesh add little.
      EXPECT_LT(r.seconds, 3 * caps.max_seconds);
      ++inputs;
      done += r.stage == CappedRunOutcome::Stage::kDone;
    }
  }
  std::printf("fuzz corpus: %d inputs, %d adjusted to the end, the rest refused\n", inputs, done);
  EXPECT_GE(inputs, 21);
  EXPECT_GE(done, 7);  // at least the full seeds go the whole way
}

}  // namespace
}  // namespace hull
