// Acoustic sequences with images (version 2 of the contract): the layouts of
// sonar_simulator.h rendered step by step from a scene (the prism on a floor,
// or in a tank) by SonarRenderer. The truth features are all eight vertices
// of the prism (tank: the paper's A, B, C, D first); measurements.csv holds
// the vertices each image shows (in view and not occluded), with the
// contract's noise: the "given correspondences" to compare the automatic
// features against.
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "base/progress.h"
#include "simulate/sonar_renderer.h"
#include "simulate/sonar_scene.h"
#include "simulate/sonar_simulator.h"

namespace hull {

struct SonarImageSimulationOptions {
  SonarSimulationOptions sequence;  // layout, trajectory, noise and seed
  SonarSceneOptions scene;
  SonarRenderOptions render;
  SonarImageFormat format;  // range bins x beams (gain_db is taken from render)

  bool Check(std::string* why = nullptr) const;
};

struct SonarImageSimulation {
  AcousticSequence sequence;    // version 2, with truth and measurements
  SonarScene scene;             // the true scene (world frame)
  std::vector<cv::Mat> images;  // per step: 8-bit polar image
};

// Throws OptionError when options.Check() fails, hull::Cancelled when the
// progress asks to stop.
SonarImageSimulation SimulateSonarImages(const SonarImageSimulationOptions& options, Progress* progress = nullptr);

// Writes the sequence, images/<step>.png and truth/scene.ply into dir.
void WriteSonarImageSimulation(const SonarImageSimulation& simulation, const std::string& dir);

// The presets ("prism", "tank", "above") with their defaults.
SonarImageSimulationOptions SonarImagePreset(const std::string& preset, std::uint64_t seed);

}  // namespace hull
