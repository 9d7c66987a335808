// hullinspect-cli as a user runs it: --help on every command, bad command
// lines (exit 2 naming the option), bad input (the file, line and field), and
// a simulate -> validate round trip.
#include <gtest/gtest.h>

#include <zlib.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.h"
#include "support/test_files.h"
#include "support/test_surveys.h"
#include "unit/vision/vision_scene.h"

namespace {

using hull::testing::CliRun;

CliRun Cli(const std::vector<std::string>& args) { return hull::testing::RunProgram(HI_CLI_PATH, args); }

const std::vector<std::string> kCommands = {"simulate", "validate", "info",   "align",   "run",      "adjust",
                                            "map",      "sonar",    "export", "plugins", "features", "mosaic"};

TEST(Cli, EveryCommandHasHelp) {
  for (const std::string& c : kCommands) {
    for (const char* flag : {"--help", "-h"}) {
      const CliRun r = Cli({c, flag});
      EXPECT_EQ(r.exit_code, 0) << c << " " << flag << ":\n" << r.output;
      EXPECT_NE(r.output.find("usage: hullinspect-cli " + c), std::string::npos) << c << " " << flag << ":\n"
                                                                                 << r.output;
    }
  }
  const CliRun top = Cli({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  for (const std::string& c : kCommands) EXPECT_NE(top.output.find("  " + c + " "), std::string::npos) << c;
}

TEST(Cli, BadCommandLinesExitTwoNamingTheProblem) {
  CliRun r = Cli({});
  EXPECT_EQ(r.exit_code, 2);
  r = Cli({"frobnicate"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("frobnicate"), std::string::npos) << r.output;
  r = Cli({"validate", "somewhere", "--bogus", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("unknown option --bogus"), std::string::npos) << r.output;
  r = Cli({"adjust", "somewhere", "--mesh"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("option --mesh needs a value"), std::string::npos) << r.output;
  r = Cli({"run", "--bogus"});  // last on the line: unknown, not "needs a value"
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("unknown option --bogus"), std::string::npos) << r.output;
  r = Cli({"simulate", "--preset", "demo", "--out", "x", "--seed", "seven"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--seed expects an integer, got 'seven'"), std::string::npos) << r.output;
  r = Cli({"adjust", "somewhere", "--out", "x", "--linear-solver", "magic"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--linear-solver expects sparse-schur or iterative-schur"), std::string::npos) << r.output;
  r = Cli({"run", "somewhere", "--out", "x", "--max-features", "-1"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("max_features"), std::string::npos) << r.output;
}

TEST(Cli, MissingBundleIsNamed) {
  const hull::testing::ScratchDir tmp("cli_missing");
  const std::string missing = tmp / "no-such-bundle";
  const CliRun r = Cli({"validate", missing});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find(missing), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INVALID"), std::string::npos) << r.output;
}

// Field `field` (0-based) of a CSV line (no quoting in survey files).
std::string CsvField(const std::string& line, int field) {
  const auto start = static_cast<std::size_t>(hull::testing::CsvColumn(line, field) - 1);
  return line.substr(start, line.find(',', start) - start);
}

TEST(Cli, SimulateThenValidateAndNameACorruptField) {
  const hull::testing::ScratchDir tmp("cli_round_trip");
  const std::string bundle = tmp / "demo";
  CliRun r = Cli({"simulate", "--preset", "demo", "--out", bundle, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("valid (0 errors"), std::string::npos) << r.output;
  r = Cli({"info", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;

  // A number that is not one, on line 7 of nav.csv: the file, the line and
  // the field are named, and nothing else is reported broken.
  const std::string nav = bundle + "/nav.csv";
  const std::string text = hull::testing::ReadText(nav);
  const std::string field = CsvField(hull::testing::LineOf(text, 1), 1);
  ASSERT_FALSE(field.empty());
  const std::string line = hull::testing::LineOf(text, 7);
  const int column = hull::testing::CsvColumn(line, 1);
  const std::string value = CsvField(line, 1);
  hull::testing::ReplaceLine(nav, 7,
                             line.substr(0, static_cast<std::size_t>(column - 1)) + "12.5x" +
                                 line.substr(static_cast<std::size_t>(column - 1) + value.size()));
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("nav.csv:7:" + std::to_string(column)), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(" + field + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("INVALID (1 errors"), std::string::npos) << r.output;
  // The other commands refuse the bundle with the same location (exit 3).
  r = Cli({"info", bundle});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("nav.csv:7"), std::string::npos) << r.output;
}

TEST(Cli, SonarFromImages) {
  const hull::testing::ScratchDir tmp("cli_sonar_images");
  const std::string seq = tmp / "tank";
  CliRun r = Cli({"simulate", "--preset", "sonar-tank", "--images", "--out", seq, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(seq + "/images/7.png"));
  EXPECT_TRUE(std::filesystem::exists(seq + "/truth/scene.ply"));
  r = Cli({"validate", seq});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"info", seq});
  EXPECT_NE(r.output.find("512 range bins x 128 beams"), std::string::npos) << r.output;

  // With measurements.csv the default is the given correspondences...
  r = Cli({"sonar", seq, "--out", tmp / "given", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(hull::testing::ReadText(tmp / "given/summary.json").find("\"source\": \"measurements\""),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(tmp / "given/detections.csv"));
  // ... --from-images runs the whole chain ...
  r = Cli({"sonar", seq, "--from-images", "--out", tmp / "images", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("of the visible true features detected per frame"), std::string::npos) << r.output;
  const std::string summary = hull::testing::ReadText(tmp / "images/summary.json");
  EXPECT_NE(summary.find("\"source\": \"images\""), std::string::npos);
  EXPECT_NE(summary.find("\"mean_detection_rate\""), std::string::npos);
  EXPECT_NE(hull::testing::ReadText(tmp / "images/detections.csv").find("step,detection,row,col"), std::string::npos);
  // ... and without measurements.csv the images are the default.
  std::filesystem::remove(seq + "/measurements.csv");
  r = Cli({"sonar", seq, "--out", tmp / "default", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(hull::testing::ReadText(tmp / "default/summary.json").find("\"source\": \"images\""), std::string::npos);
  r = Cli({"sonar", seq, "--from-measurements", "--out", tmp / "x", "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("measurements.csv"), std::string::npos) << r.output;
  r = Cli({"sonar", seq, "--from-images", "--from-measurements", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;

  // A truncated image is named (exit 3).
  const std::string image = seq + "/images/3.png";
  const std::string bytes = hull::testing::ReadText(image);
  hull::testing::WriteText(image, bytes.substr(0, bytes.size() / 3));
  r = Cli({"sonar", seq, "--out", tmp / "x", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("images/3.png"), std::string::npos) << r.output;

  // The image size needs a sonar preset; a version 1 sequence has no images to use.
  r = Cli({"simulate", "--preset", "demo", "--range-bins", "256", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string v1 = tmp / "v1";
  ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--out", v1}).exit_code, 0);
  r = Cli({"sonar", v1, "--from-images", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no images"), std::string::npos) << r.output;
}

TEST(Cli, SimulateCameraImages) {
  // A version 2 survey bundle with rendered camera images (small and sparse
  // here), valid for the validator; dropped frames are warnings.
  const hull::testing::ScratchDir tmp("cli_camera_images");
  const std::string bundle = tmp / "demo";
  CliRun r = Cli({"simulate", "--preset", "demo", "--images", "--camera-scale", "0.25", "--keyframe-spacing", "1.2",
                  "--image-dropout", "0.1", "--seed", "4", "--out", bundle, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(" images ("), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(bundle + "/truth/scene.ply"));
  EXPECT_TRUE(std::filesystem::exists(bundle + "/truth/albedo.json"));
  EXPECT_NE(hull::testing::ReadText(bundle + "/survey.json").find("\"version\": 2"), std::string::npos);
  int images = 0;
  for (const auto& e : std::filesystem::directory_iterator(bundle + "/images")) images += e.is_regular_file();
  EXPECT_GT(images, 20);
  r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("dropped frame"), std::string::npos) << r.output;
  // The water needs images to act on.
  r = Cli({"simulate", "--preset", "demo", "--attenuation", "0.5", "--out", tmp / "x"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--attenuation needs --images"), std::string::npos) << r.output;
}

}  // namespace

namespace {

TEST(Cli, FeaturesFromImagesThenValidate) {
  const hull::testing::VisionScene s = hull::testing::MakeVisionScene(false, true, 3);
  const hull::testing::ScratchDir dir("cli_features");
  hull::testing::WriteSceneBundle(s, dir.path());
  CliRun r = Cli({"features", dir.path(), "--quiet", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("mean inlier ratio"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("landmarks"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "features.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "match-graph.csv"));
  r = Cli({"validate", dir.path()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = Cli({"features", dir.path(), "--quiet"});  // would overwrite
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--force"), std::string::npos) << r.output;
  r = Cli({"features", dir.path(), "--ratio", "2", "--out", dir / "other.csv"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("ratio"), std::string::npos) << r.output;
}

// ---- issue 14: what validate accepts never crashes or hangs adjust ----------------------

// The small simulated survey (tests/support) with one CSV field replaced:
// `field` (0-based) of data row `row` (0-based) of `file`.
void EditCsvField(const std::string& file, int row, int field, const std::string& value) {
  const std::string text = hull::testing::ReadText(file);
  const std::string line = hull::testing::LineOf(text, row + 2);
  const auto start = static_cast<std::size_t>(hull::testing::CsvColumn(line, field) - 1);
  const auto end = line.find(',', start);
  hull::testing::ReplaceLine(file, row + 2,
                             line.substr(0, start) + value + (end == std::string::npos ? "" : line.substr(end)));
}

TEST(CliRobust, AbsurdNavValuesFailValidateAndAdjustExitsThreeQuickly) {
  const hull::testing::ScratchDir tmp("cli_robust_nav");
  struct Case {
    int field;
    const char* value;
    const char* name;
  };
  // nav.csv: keyframe,t,x,y,z,...; the values on the second data row.
  for (const Case& c :
       {Case{2, "1e308", "x"}, Case{2, "1e30", "x"}, Case{2, "1e10", "x"}, Case{2, "1e6", "x"}, Case{4, "2e9", "z"}}) {
    const std::string bundle = tmp / (std::string("b") + c.value);
    hull::test::WriteSmallSurvey(bundle);
    EditCsvField(bundle + "/nav.csv", 1, c.field, c.value);
    const std::string line = hull::testing::LineOf(hull::testing::ReadText(bundle + "/nav.csv"), 3);
    const std::string place =
        "nav.csv:3:" + std::to_string(hull::testing::CsvColumn(line, c.field)) + " (" + c.name + ")";
    CliRun r = Cli({"validate", bundle});
    EXPECT_EQ(r.exit_code, 3) << c.value << "\n" << r.output;
    EXPECT_NE(r.output.find(place), std::string::npos) << r.output;
    const auto t0 = std::chrono::steady_clock::now();
    r = Cli({"adjust", bundle, "--out", tmp / "out", "--quiet"});
    EXPECT_EQ(r.exit_code, 3) << c.value << "\n" << r.output;  // not 134 (a library assertion), not a stall
    EXPECT_NE(r.output.find(place), std::string::npos) << r.output;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 20.0);
  }
}

TEST(CliRobust, AbsurdManifestDuplicatedOdometryAndBadMeshFailValidate) {
  const hull::testing::ScratchDir tmp("cli_robust_manifest");
  struct Case {
    std::string from, to, expect;
  };
  for (const Case& c : {Case{"\"fx\": 1150", "\"fx\": 2000000000", "(camera.top.fx)"},
                        Case{"\"pixel_sigma\": 2", "\"pixel_sigma\": 2000000000", "(noise.pixel_sigma)"}}) {
    const std::string bundle = tmp / "m";
    std::filesystem::remove_all(bundle);
    hull::test::WriteSmallSurvey(bundle);
    std::string json = hull::testing::ReadText(bundle + "/survey.json");
    const auto at = json.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from << "\n" << json;
    json.replace(at, c.from.size(), c.to);
    hull::testing::WriteText(bundle + "/survey.json", json);
    CliRun r = Cli({"validate", bundle});
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find("survey.json:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << r.output;
    r = Cli({"adjust", bundle, "--out", tmp / "out", "--quiet"});
    EXPECT_EQ(r.exit_code, 3) << r.output;
  }
  // A duplicated odometry row.
  const std::string dup = tmp / "dup";
  hull::test::WriteSmallSurvey(dup);
  const std::string odo = hull::testing::ReadText(dup + "/odometry.csv");
  hull::testing::WriteText(dup + "/odometry.csv", odo + hull::testing::LineOf(odo, 2) + "\n");
  CliRun r = Cli({"validate", dup});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("duplicates line 2"), std::string::npos) << r.output;
  // A corrupted hull.ply: validate opens the model_hint mesh.
  const std::string mesh = tmp / "mesh";
  hull::test::WriteSmallSurvey(mesh);
  std::string ply = hull::testing::ReadText(mesh + "/hull.ply");
  ply.resize(ply.size() - 200);
  hull::testing::WriteText(mesh + "/hull.ply", ply);
  r = Cli({"validate", mesh});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("(model_hint)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("hull.ply"), std::string::npos) << r.output;
}

TEST(CliRobust, OutputLocationIsCheckedBeforeAnyWork) {
  const hull::testing::ScratchDir tmp("cli_robust_out");
  const std::string bundle = tmp / "bundle";
  hull::test::WriteSmallSurvey(bundle);
  hull::testing::WriteText(tmp / "a-file", "x");
  struct Case {
    std::string out, expect;
  };
  for (const Case& c :
       {Case{tmp / "a-file", "is a file; expected a folder"}, Case{tmp / "no/such/parent/out", "does not exist"},
        Case{"/proc/hullinspect-out", "cannot write in '/proc'"}}) {
    for (const char* cmd : {"adjust", "run"}) {
      const auto t0 = std::chrono::steady_clock::now();
      const CliRun r = Cli({cmd, bundle, "--out", c.out, "--quiet"});
      EXPECT_EQ(r.exit_code, 2) << cmd << " " << c.out << "\n" << r.output;
      EXPECT_NE(r.output.find("--out " + c.out + ": "), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(c.expect), std::string::npos) << r.output;
      EXPECT_EQ(r.output.find("filesystem"), std::string::npos) << r.output;
      EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0) << cmd;
    }
  }
  CliRun r = Cli({"simulate", "--preset", "demo", "--out", tmp / "a-file"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = Cli({"export", bundle, "--out", tmp / "no/such/parent/x.ply"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
}

TEST(CliRobust, MosaicRefusesMissingResultsAndAFileAsOutput) {
  const hull::testing::ScratchDir tmp("cli_mosaic");
  hull::testing::WriteText(tmp / "a-file", "x");
  // RESULTS that does not exist: a bad command line, named.
  CliRun r = Cli({"mosaic", tmp / "no-such-results", "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no-such-results"), std::string::npos) << r.output;
  // --out onto a file: refused before any work.
  std::filesystem::create_directories(tmp / "results");
  r = Cli({"mosaic", tmp / "results", "--out", tmp / "a-file", "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is a file; expected a folder"), std::string::npos) << r.output;
  r = Cli({"mosaic", tmp / "results", "--normalise", "magic"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--normalise expects none, model or gains"), std::string::npos) << r.output;
  // A folder that is not results: unreadable input (exit 3), saying what is missing.
  r = Cli({"mosaic", tmp / "results", "--quiet"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("adjustment.json"), std::string::npos) << r.output;
}

TEST(CliRobust, NotGzipAndDegenerateBombAreRefused) {
  const hull::testing::ScratchDir tmp("cli_robust_gz");
  hull::testing::WriteText(tmp / "hull.stl.gz", "solid x\nendsolid x\n");
  CliRun r = Cli({"info", tmp / "hull.stl.gz"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("not gzip"), std::string::npos) << r.output;
  // 3 M degenerate triangles (150 MB of STL) in a small .stl.gz.
  const std::string bomb = tmp / "bomb.stl.gz";
  gzFile f = gzopen(bomb.c_str(), "wb9");
  ASSERT_NE(f, nullptr);
  const std::uint32_t n = 3000000;
  std::string head(84, '\0');
  std::memcpy(&head[80], &n, 4);
  gzwrite(f, head.data(), static_cast<unsigned>(head.size()));
  std::string rec(50, '\0');
  const float corners[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  std::memcpy(&rec[12], corners, sizeof(corners));
  std::string chunk;
  for (int i = 0; i < 10000; ++i) chunk += rec;
  for (std::uint32_t t = 0; t < n; t += 10000) gzwrite(f, chunk.data(), static_cast<unsigned>(chunk.size()));
  gzclose(f);
  const auto t0 = std::chrono::steady_clock::now();
  r = Cli({"info", bomb});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("decompression bomb"), std::string::npos) << r.output;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 20.0);
}

TEST(CliRobust, MalformedHeadersAreBoundedAndEscaped) {
  const hull::testing::ScratchDir tmp("cli_robust_header");
  const std::string bundle = tmp / "bundle";
  hull::test::WriteSmallSurvey(bundle);
  // A 100 kB binary header with a duplicated column name.
  std::string name;
  for (int i = 0; i < 50000; ++i) name += (i % 2) ? '\x1b' : 'k';
  hull::testing::WriteText(bundle + "/dvl.csv", name + "," + name + "\n1,2\n");
  const CliRun r = Cli({"validate", bundle});
  EXPECT_EQ(r.exit_code, 3) << r.output.substr(0, 2000);
  EXPECT_LT(r.output.size(), 4000u) << r.output.substr(0, 2000);
  EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << "an escape byte reached the terminal";
  EXPECT_NE(r.output.find("\\x1b"), std::string::npos) << r.output;
}

}  // namespace
