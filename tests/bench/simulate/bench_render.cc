// bench_render: the underwater image renderer on the demo survey -- images
// per second at the survey's 1360x1024 (or --scale), rendering only (one
// view after another, each parallel over its rows) and rendering plus PNG
// encoding as the simulator writes a bundle (views in parallel), on the
// threads TBB is given.
//
//   build/bin/bench_render [--preset demo|mono] [--images N] [--threads T] [--scale S] [--no-shadows]
//                          [--write DIR]
//
// The survey is simulated first (not timed); N top-camera views spread over
// the survey are rendered once to warm up, then timed.
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>

#include "base/file_io.h"
#include "image/image_file.h"
#include "simulate/survey_imaging.h"
#include "support/bench_clock.h"

namespace {
using hull::bench::CpuSeconds;
using hull::bench::Seconds;
}  // namespace

int main(int argc, char** argv) {
  std::string preset = "demo", write_dir;
  int n = 20, threads = 2;
  double scale = 1.0;
  bool shadows = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--preset" && i + 1 < argc) {
      preset = argv[++i];
    } else if (a == "--images" && i + 1 < argc) {
      n = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--threads" && i + 1 < argc) {
      threads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--scale" && i + 1 < argc) {
      scale = std::atof(argv[++i]);
    } else if (a == "--no-shadows") {
      shadows = false;
    } else if (a == "--write" && i + 1 < argc) {
      write_dir = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: %s [--preset demo|mono] [--images N] [--threads T] [--scale S] [--no-shadows] "
                   "[--write DIR]\n",
                   argv[0]);
      return 2;
    }
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  hull::SurveySimulationOptions o = hull::SurveyPreset(preset);
  o.images = true;
  o.imaging.shadows = shadows;
  hull::NullProgress quiet;
  const hull::SimulatedSurvey survey = hull::SimulateSurvey(o, quiet);
  hull::SurveyManifest man = survey.bundle.manifest;
  hull::CameraRig& rig = man.camera;
  if (scale != 1.0) hull::ScaleCamera(rig, scale);
  auto t0 = std::chrono::steady_clock::now();
  const auto scene = hull::MakeTrueScene(survey);
  const auto camera = hull::MakeSurveyCamera(man, *survey.imaging, false);
  std::printf("scene: %zu triangles; scene and camera tables built in %.2f s\n", scene->mesh().num_faces(),
              Seconds(t0));
  const std::size_t K = survey.bundle.nav.size();
  auto view = [&](int i) { return static_cast<std::size_t>(i) * K / static_cast<std::size_t>(n); };
  camera->Render(*scene, hull::TrueCameraPose(survey, view(0), false), 0);  // warm-up

  t0 = std::chrono::steady_clock::now();
  double cpu0 = CpuSeconds();
  for (int i = 0; i < n; ++i) camera->Render(*scene, hull::TrueCameraPose(survey, view(i), false), i);
  const double render = Seconds(t0), render_cpu = CpuSeconds() - cpu0;
  t0 = std::chrono::steady_clock::now();
  cpu0 = CpuSeconds();
  // As the simulator writes a bundle (WriteSurveyImages): the views in
  // parallel, each rendered (itself in parallel over rows) and encoded, so
  // one view's PNG encoding overlaps another's rendering.
  hull::ImageWriteOptions wo;  // as WriteSurveyImages writes them
  wo.png_compression = survey.imaging->png_compression;
  wo.png_huffman_only = true;
  std::atomic<std::size_t> bytes{0};
  if (!write_dir.empty()) std::filesystem::create_directories(write_dir);
  tbb::parallel_for(0, n, [&](int i) {
    const cv::Mat image = camera->Render(*scene, hull::TrueCameraPose(survey, view(i), false), i);
    const std::string png = hull::EncodeImage(image, ".png", wo);
    bytes += png.size();
    if (!write_dir.empty()) hull::WriteFileAtomic(write_dir + "/" + std::to_string(view(i)) + "_top.png", png);
  });
  const double with_png = Seconds(t0), with_png_cpu = CpuSeconds() - cpu0;
  std::printf("%s, %dx%d, %d threads, shadows %s: %d views\n", preset.c_str(), rig.width, rig.height, threads,
              shadows ? "on" : "off", n);
  std::printf("render only      %6.2f images/s (%.1f ms per image; CPU %.1f ms per image)\n", n / render,
              1e3 * render / n, 1e3 * render_cpu / n);
  std::printf("render + PNG     %6.2f images/s (%.1f ms per image; CPU %.1f ms per image; %.0f kB per PNG)\n",
              n / with_png, 1e3 * with_png / n, 1e3 * with_png_cpu / n, static_cast<double>(bytes.load()) / 1024.0 / n);
  return 0;
}
