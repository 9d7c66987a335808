#include "simulate/survey_imaging.h"

#include "simulate/image_track_truth.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <mutex>

#include "image/image_file.h"
#include "simulate/survey_plan.h"
#include "survey/survey_images.h"

namespace hull {

void ScaleCamera(CameraRig& rig, double s) {
  rig.width = static_cast<int>(std::lround(rig.width * s));
  rig.height = static_cast<int>(std::lround(rig.height * s));
  for (PinholeIntrinsics* k : {&rig.top, &rig.bottom}) {
    k->fx *= s;
    k->fy *= s;
    k->cx = (k->cx + 0.5) * s - 0.5;
    k->cy = (k->cy + 0.5) * s - 0.5;
  }
}

std::unique_ptr<TrueScene> MakeTrueScene(const SimulatedSurvey& s) {
  const ModelAxes axes = s.bundle.manifest.model_axes.value_or(ModelAxes{});
  return std::make_unique<TrueScene>(s.cad, s.object_meshes, s.bundle.truth->objects,
                                     SurfaceAlbedo(s.albedo_seed, axes.forward, axes.up));
}

Pose TrueCameraPose(const SimulatedSurvey& s, std::size_t k, bool bottom_camera) {
  return TrueCameraPoseFromTruth(s.bundle, k, bottom_camera);
}

std::unique_ptr<UnderwaterCamera> MakeSurveyCamera(const SurveyManifest& man, const UnderwaterImagingOptions& o,
                                                   bool bottom_camera) {
  const CameraRig& rig = man.camera;
  const Pose x_cT_c = bottom_camera ? Pose::FromVector(rig.top_to_bottom) : Pose();
  return std::make_unique<UnderwaterCamera>(bottom_camera ? rig.bottom : rig.top, rig.width, rig.height,
                                            StrobesInCamera(o.strobes, x_cT_c), o);
}

void WriteSurveyImages(const SimulatedSurvey& s, const std::string& dir, Progress& progress) {
  namespace fs = std::filesystem;
  if (!s.imaging || !s.bundle.images) throw std::invalid_argument("WriteSurveyImages: the survey has no imaging");
  const UnderwaterImagingOptions& o = *s.imaging;
  const SurveyImages& listing = *s.bundle.images;
  progress.Update(0.0, "building the true scene");
  const std::unique_ptr<TrueScene> scene = MakeTrueScene(s);
  scene->Write(dir);
  fs::create_directories(fs::path(dir) / "images");
  const bool stereo = s.bundle.manifest.camera.stereo();
  const std::unique_ptr<UnderwaterCamera> top = MakeSurveyCamera(s.bundle.manifest, o, false);
  const std::unique_ptr<UnderwaterCamera> bottom = stereo ? MakeSurveyCamera(s.bundle.manifest, o, true) : nullptr;
  ImageWriteOptions wo;
  wo.png_compression = o.png_compression;
  wo.png_huffman_only = true;  // sensor noise leaves little for string matching
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  const int total = listing.present();
  tbb::parallel_for(std::size_t{0}, listing.frames.size(), [&](std::size_t k) {
    const KeyframeImages& f = listing.frames[k];
    for (bool b : {false, true}) {
      const std::string& rel = b ? f.bottom : f.top;
      if (rel.empty() || progress.Cancelled()) continue;
      const UnderwaterCamera& camera = b ? *bottom : *top;
      const std::uint64_t noise_seed = s.albedo_seed * 0x9E3779B97F4A7C15ULL + 2 * k + (b ? 1 : 0);
      WriteImageFile((fs::path(dir) / rel).string(), camera.Render(*scene, TrueCameraPose(s, k, b), noise_seed), wo);
      const int n = ++done;
      if (n % 8 == 0 || n == total) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress.Update(static_cast<double>(n) / total,
                        "rendered image " + std::to_string(n) + " of " + std::to_string(total));
      }
    }
  });
  progress.ThrowIfCancelled();
}

}  // namespace hull
