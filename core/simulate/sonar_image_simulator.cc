#include "simulate/sonar_image_simulator.h"
#include "survey/survey_plausibility.h"

#include <filesystem>

#include "base/error.h"
#include "geometry/mesh_io.h"
#include "survey/sonar_image.h"

namespace hull {

bool SonarImageSimulationOptions::Check(std::string* why) const {
  if (!sequence.Check(why) || !scene.Check(why) || !render.Check(why)) return false;
  if (format.range_bins < 8 || format.range_bins > 8192 || format.beams < 8 || format.beams > 4096) {
    if (why) *why = "format: range_bins must be in 8..8192 and beams in 8..4096";
    return false;
  }
  if (std::int64_t{format.range_bins} * format.beams > plausible::kMaxSonarImagePixels) {
    if (why) *why = "format: range_bins x beams must be at most 8388608 (what a sequence may hold)";
    return false;
  }
  return true;
}

SonarImageSimulation SimulateSonarImages(const SonarImageSimulationOptions& o, Progress* progress) {
  std::string why;
  if (!o.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  const SonarLayout layout = MakeSonarLayout(o.sequence);
  SonarImageSimulation sim;
  sim.scene = MakeSonarScene(layout, o.sequence.preset, o.scene);
  SonarImageFormat format = o.format;
  format.gain_db = o.render.gain_db;
  const SonarRenderer renderer(sim.scene, o.sequence.sensor, format, o.render);
  const auto visible = [&](int k, int i) {
    return renderer.Sees(layout.poses[static_cast<std::size_t>(k)],
                         layout.object_vertices[static_cast<std::size_t>(i)]);
  };
  sim.sequence = SimulateSonarSequence(o.sequence, layout.name + "; rendered images", layout.poses,
                                       layout.object_vertices, visible);
  sim.sequence.image = format;
  const int T = static_cast<int>(layout.poses.size());
  for (int k = 0; k < T; ++k) {
    if (progress) {
      progress->ThrowIfCancelled();
      progress->Update(static_cast<double>(k) / T, "rendering sonar image " + std::to_string(k));
    }
    const std::uint64_t seed = o.sequence.seed * 1000003ULL + static_cast<std::uint64_t>(k);
    sim.images.push_back(renderer.Render(layout.poses[static_cast<std::size_t>(k)], seed));
  }
  if (progress) progress->Update(1.0, "sonar images rendered");
  return sim;
}

void WriteSonarImageSimulation(const SonarImageSimulation& sim, const std::string& dir) {
  WriteAcousticSequence(sim.sequence, dir);
  for (std::size_t k = 0; k < sim.images.size(); ++k) {
    WriteSonarImage(SonarImagePath(dir, static_cast<long long>(k)), sim.images[k]);
  }
  std::filesystem::create_directories(std::filesystem::path(dir) / "truth");
  SaveMesh(sim.scene.mesh, (std::filesystem::path(dir) / "truth" / "scene.ply").string());
}

SonarImageSimulationOptions SonarImagePreset(const std::string& preset, std::uint64_t seed) {
  SonarImageSimulationOptions o;
  o.sequence.preset = ParseSonarPreset(preset);
  o.sequence.seed = seed;
  return o;
}

}  // namespace hull
