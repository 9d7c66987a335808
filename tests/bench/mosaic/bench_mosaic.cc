// bench_mosaic: the 3-D photomosaic of a pipeline's results (the demo
// preset's, say) -- wall and CPU time of BuildMosaic with its image reading,
// per stage, on the threads TBB is given; writing the folder timed apart.
//
//   build/bin/bench_mosaic RESULTS [--threads T] [--texel M] [--no-truth] [--write DIR]
//                          [--snapshot PNG]
//
// --snapshot renders the textured model (not timed) orthographically along
// the cameras' mean viewing direction, 5 mm per pixel, each pixel the atlas
// sampled bilinearly at the UV of the surface point it sees: a look at the
// mosaic (seams, gains) without a GUI; also its centre at full resolution
// (<name>_centre.png), and the same with the per-vertex colours of mosaic.ply
// (<name>_vertex.png, <name>_vertex_centre.png).
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

#include "geometry/mesh_index.h"
#include "geometry/mesh_io.h"
#include "image/image_file.h"
#include "mosaic/mosaic_io.h"
#include "results/adjustment_files.h"
#include "results/mosaic_files.h"
#include "support/bench_clock.h"
#include "survey/survey_import.h"

namespace {
using hull::bench::CpuSeconds;
using hull::bench::Seconds;
// Orthographic render of the textured faces along the cameras' mean axis.
// vertex_colours: shade with the per-vertex values (the PLY's colours) instead of the atlas.
cv::Mat Snapshot(const hull::MosaicResult& r, double pixel, bool vertex_colours) {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (const hull::MosaicView& v : r.views) d += v.x_Mc.rotation().col(2);
  d.normalize();
  const Eigen::Vector3d e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  double lo1 = 1e300, hi1 = -1e300, lo2 = 1e300, hi2 = -1e300;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int n = 0;
  for (std::size_t f = 0; f < r.faces.size(); ++f) {
    if (r.faces[f].view < 0) continue;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& p = r.model.vertices[static_cast<std::size_t>(r.model.faces[f][c])];
      lo1 = std::min(lo1, p.dot(e1)), hi1 = std::max(hi1, p.dot(e1));
      lo2 = std::min(lo2, p.dot(e2)), hi2 = std::max(hi2, p.dot(e2));
      centre += p;
      ++n;
    }
  }
  centre /= n;
  pixel = std::max(pixel, std::max(hi1 - lo1, hi2 - lo2) / 4000);
  const int w = static_cast<int>((hi1 - lo1) / pixel) + 1, h = static_cast<int>((hi2 - lo2) / pixel) + 1;
  const hull::MeshIndex index(r.model);
  cv::Mat out(h, w, CV_8UC(r.channels), cv::Scalar::all(0));
  const Eigen::Vector3d base = centre - 50 * d - centre.dot(e1) * e1 - centre.dot(e2) * e2;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector3d o = base + (lo1 + (i + 0.5) * pixel) * e1 + (lo2 + (j + 0.5) * pixel) * e2;
      const hull::RayHit hit = index.Raycast(o, d, 100.0);
      if (!hit.hit || r.faces[static_cast<std::size_t>(hit.face)].view < 0) continue;
      const hull::Face& F = r.model.faces[static_cast<std::size_t>(hit.face)];
      const Eigen::Vector3d a = r.model.vertices[static_cast<std::size_t>(F[0])],
                            b = r.model.vertices[static_cast<std::size_t>(F[1])],
                            c = r.model.vertices[static_cast<std::size_t>(F[2])];
      const Eigen::Vector3d nrm = (b - a).cross(c - a);
      const double area = nrm.squaredNorm();
      const double l1 = (c - a).cross(hit.point - a).dot(nrm) / area * -1.0;
      const double l2 = (b - a).cross(hit.point - a).dot(nrm) / area;
      const double l0 = 1 - l1 - l2;
      const Eigen::Vector2f uv = static_cast<float>(l0) * r.Uv(hit.face, 0) +
                                 static_cast<float>(l1) * r.Uv(hit.face, 1) +
                                 static_cast<float>(l2) * r.Uv(hit.face, 2);
      const float ax = uv.x() * static_cast<float>(r.atlas.cols) - 0.5f,
                  ay = (1 - uv.y()) * static_cast<float>(r.atlas.rows) - 0.5f;
      const int x0 = std::clamp(static_cast<int>(ax), 0, r.atlas.cols - 2),
                y0 = std::clamp(static_cast<int>(ay), 0, r.atlas.rows - 2);
      const float fx = std::clamp(ax - static_cast<float>(x0), 0.0f, 1.0f),
                  fy = std::clamp(ay - static_cast<float>(y0), 0.0f, 1.0f);
      if (vertex_colours) {
        for (int k = 0; k < r.channels; ++k) {
          const auto ch = static_cast<std::size_t>(r.channels);
          auto val = [&](int c) {
            return r.vertex_values[static_cast<std::size_t>(F[c]) * ch + static_cast<std::size_t>(k)];
          };
          const double v = (l0 * val(0) + l1 * val(1) + l2 * val(2)) * 255.0;
          out.ptr<std::uint8_t>(j)[i * r.channels + k] = static_cast<std::uint8_t>(std::clamp(v + 0.5, 0.0, 255.0));
        }
        continue;
      }
      for (int k = 0; k < r.channels; ++k) {
        auto at = [&](int y, int x) { return static_cast<float>(r.atlas.ptr<std::uint8_t>(y)[x * r.channels + k]); };
        const float v = (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x0 + 1)) +
                        fy * ((1 - fx) * at(y0 + 1, x0) + fx * at(y0 + 1, x0 + 1));
        out.ptr<std::uint8_t>(j)[i * r.channels + k] = static_cast<std::uint8_t>(v + 0.5f);
      }
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string results, write_dir, snapshot;
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
    } else if (a == "--snapshot" && i + 1 < argc) {
      snapshot = argv[++i];
    } else if (results.empty() && a.rfind("--", 0) != 0) {
      results = a;
    } else {
      std::fprintf(stderr, "usage: %s RESULTS [--threads T] [--texel M] [--no-truth] [--write DIR] [--snapshot PNG]\n",
                   argv[0]);
      return 2;
    }
  }
  if (results.empty()) {
    std::fprintf(stderr, "usage: %s RESULTS [--threads T] [--texel M] [--no-truth] [--write DIR] [--snapshot PNG]\n",
                 argv[0]);
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
    std::size_t candidates = 0;
    for (const hull::MosaicView& v : r.views) candidates += static_cast<std::size_t>(v.candidates);
    std::printf("visibility: %zu (view, face) pairs near a camera, %zu projected, %zu rays, %zu candidates\n",
                s.visibility_pairs_near, s.visibility_pairs_projected, s.visibility_rays, candidates);
    if (s.faces_scored > 0) {
      std::printf("truth: |error| median %.4f p95 %.4f; face means median %.4f p95 %.4f\n", s.error_median, s.error_p95,
                  s.mean_error_median, s.mean_error_p95);
    }
    if (!write_dir.empty()) {
      const auto t1 = std::chrono::steady_clock::now();
      hull::WriteMosaic(r, write_dir);
      std::printf("write: %.2f s -> %s\n", Seconds(t1), write_dir.c_str());
    }
    if (!snapshot.empty()) {
      for (bool vertex : {false, true}) {
        const cv::Mat shot = Snapshot(r, 0.005, vertex);
        const std::string stem = snapshot.substr(0, snapshot.size() - 4) + (vertex ? "_vertex" : "");
        hull::WriteImageFile(stem + ".png", shot);
        std::printf("snapshot %dx%d -> %s.png\n", shot.cols, shot.rows, stem.c_str());
        // And its centre at full resolution (900 x 700 pixels, 4.5 x 3.5 m), for seams.
        const int cw = std::min(900, shot.cols), chh = std::min(700, shot.rows);
        const cv::Mat centre = shot(cv::Rect((shot.cols - cw) / 2, (shot.rows - chh) / 2, cw, chh)).clone();
        hull::WriteImageFile(stem + "_centre.png", centre);
        std::printf("centre crop -> %s_centre.png\n", stem.c_str());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
