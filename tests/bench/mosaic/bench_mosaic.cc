// bench_mosaic: the 3-D photomosaic of a pipeline's results (the demo
// preset's, say) -- wall and CPU time of BuildMosaic with its image reading,
// per stage, on the threads TBB is given; writing the folder timed apart.
//
//   build/bin/bench_mosaic RESULTS [--threads T] [--texel M] [--no-truth] [--write DIR]
//
// RESULTS as for 'hullinspect-cli mosaic' (run's folder with adjustment/ and
// mapping/model.ply). Loading the adjustment, bundle and model is not timed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>

#include "geometry/mesh_io.h"
#include "mosaic/mosaic_io.h"
#include "survey/survey_import.h"

namespace {
double Seconds(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}
// CPU time of the whole process (all threads): steadier than the wall clock
// on a shared machine.
double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

int main(int argc, char** argv) {
  std::string results, write_dir;
  int threads = 2;
  double texel = 0;
  bool use_truth = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) {
      threads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--texel" && i + 1 < argc) {
      texel = std::atof(argv[++i]);
    } else if (a == "--no-truth") {
      use_truth = false;
    } else if (a == "--write" && i + 1 < argc) {
      write_dir = argv[++i];
    } else if (results.empty() && a.rfind("--", 0) != 0) {
      results = a;
    } else {
      std::fprintf(stderr, "usage: %s RESULTS [--threads T] [--texel M] [--no-truth] [--write DIR]\n", argv[0]);
      return 2;
    }
  }
  if (results.empty()) {
    std::fprintf(stderr, "usage: %s RESULTS [--threads T] [--texel M] [--no-truth] [--write DIR]\n", argv[0]);
    return 2;
  }
  try {
    const hull::MosaicSources src = hull::LocateMosaicSources(results);
    const hull::AdjustmentResult adjustment = hull::ReadAdjustmentResult(src.adjustment_dir);
    const hull::SurveyBundle bundle = hull::OpenSurveyBundle(adjustment.bundle_path);
    hull::MeshLoadOptions lo;
    lo.weld = false;
    lo.orient_outward = false;
    hull::TriangleMesh model = hull::LoadMesh(src.model_path, lo);
    std::unique_ptr<hull::TrueScene> truth;
    if (use_truth && std::filesystem::exists(std::filesystem::path(bundle.directory) / "truth" / "albedo.json")) {
      truth = hull::TrueScene::Load(bundle);
    }
    hull::MosaicOptions o;
    o.num_threads = threads;
    if (texel > 0) o.texel_size = texel;
    const std::size_t faces = model.num_faces();
    hull::NullProgress progress;
    const double cpu0 = CpuSeconds();
    const auto t0 = std::chrono::steady_clock::now();
    const hull::MosaicResult r = hull::BuildMosaic(
        hull::MosaicInputFromAdjustment(adjustment, bundle, std::move(model)), o, progress, truth.get());
    const double wall = Seconds(t0), cpu = CpuSeconds() - cpu0;
    const hull::MosaicSummary& s = r.summary;
    std::printf("%zu faces (%zu textured, %.1f m^2), %zu images, %d x %d atlas at %.4g m, %d threads\n", faces,
                s.faces_textured, s.textured_area, r.views.size(), r.atlas.cols, r.atlas.rows, s.texel_size, threads);
    std::printf(
        "mosaic: wall %.2f s, CPU %.2f s (visibility %.2f, labelling %.2f, gains %.2f, texturing %.2f, "
        "scoring %.2f)\n",
        wall, cpu, s.seconds.visibility, s.seconds.labelling, s.seconds.gains, s.seconds.texturing, s.seconds.scoring);
    if (s.faces_scored > 0) {
      std::printf("truth: |error| median %.4f p95 %.4f; face means median %.4f p95 %.4f\n", s.error_median, s.error_p95,
                  s.mean_error_median, s.mean_error_p95);
    }
    if (!write_dir.empty()) {
      const auto t1 = std::chrono::steady_clock::now();
      hull::WriteMosaic(r, write_dir);
      std::printf("write: %.2f s -> %s\n", Seconds(t1), write_dir.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
