// bench_sonar_images: the acoustic-image chain on one core.
//
//   bench_sonar_images [--frames N] [--seeds N] [--write-frames DIR]
//
// Speed (OpenCV's threads off; run under `taskset -c 0` for one core):
//   render   SonarRenderer::Render of a 512 x 128 frame (the sonar-prism,
//            sonar-tank and sonar-above scenes), frames/s (goal: 15, ARIS);
//   detect   DetectSonarFeatures on those frames, frames/s;
//   track    SonarTracker::Step (association + EKF) per frame, frames/s;
//   chain    detect + track, frames/s.
// Accuracy over --seeds runs per layout and initialisation: detection rate
// of the visible vertices per frame, wrong associations, and the final mean
// feature error from the images against the run with the given
// correspondences of the same sequence (the issue asks for 90 %, 1 % and 1.5x).
// --write-frames DIR writes, for every layout, the polar image and its fan
// with the true vertices (red) and the detections (green) of a few frames.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "simulate/sonar_image_simulator.h"
#include "sonar/acoustic_camera.h"
#include "sonar/sonar_fan.h"
#include "sonar/sonar_image_runner.h"

namespace {

using hull::SonarImageSimulation;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void Speed(const char* preset, int frames) {
  hull::SonarImageSimulationOptions o = hull::SonarImagePreset(preset, 1);
  const hull::SonarLayout layout = hull::MakeSonarLayout(o.sequence);
  const hull::SonarScene scene = hull::MakeSonarScene(layout, o.sequence.preset, o.scene);
  const hull::SonarRenderer renderer(scene, o.sequence.sensor, o.format, o.render);
  std::vector<cv::Mat> images;
  const auto t0 = Clock::now();
  for (int i = 0; i < frames; ++i) {
    images.push_back(renderer.Render(layout.poses[static_cast<std::size_t>(i) % layout.poses.size()],
                                     static_cast<std::uint64_t>(i)));
  }
  const double render = Since(t0);
  // The whole sequence's chain, repeated until `frames` frames were processed.
  const SonarImageSimulation sim = hull::SimulateSonarImages(o);
  double detect = 0, track = 0;
  int done = 0;
  while (done < frames) {
    hull::SonarEkfOptions eo;
    eo.confirm_views = 3;
    hull::SonarEkf ekf(sim.sequence, eo);
    hull::SonarTracker tracker;
    for (int k = 0; k < sim.sequence.num_steps() && done < frames; ++k, ++done) {
      auto t1 = Clock::now();
      const auto dets =
          hull::DetectSonarFeatures(sim.images[static_cast<std::size_t>(k)], sim.sequence.sensor, *sim.sequence.image);
      detect += Since(t1);
      t1 = Clock::now();
      tracker.Step(ekf, k ? &sim.sequence.controls[static_cast<std::size_t>(k - 1)] : nullptr, dets,
                   *sim.sequence.image);
      track += Since(t1);
    }
  }
  std::printf(
      "%-6s %4d frames  render %7.1f frames/s  detect %7.1f frames/s  track %8.1f frames/s  chain %7.1f frames/s\n",
      preset, frames, frames / render, frames / detect, frames / track, frames / (detect + track));
}

void Accuracy(const char* preset, int seeds, hull::SonarInit init) {
  double rate = 0, worst = 1, image_error = 0, given_error = 0;
  int below = 0, frames = 0, assoc = 0, wrong = 0, features = 0, truth = 0;
  std::vector<double> ratios;
  for (int seed = 1; seed <= seeds; ++seed) {
    const SonarImageSimulation sim =
        hull::SimulateSonarImages(hull::SonarImagePreset(preset, static_cast<std::uint64_t>(seed)));
    hull::SonarImageRunOptions o;
    o.run.ekf.init = init;
    o.run.keep_features = false;
    const auto r = hull::RunSonarImages(
        sim.sequence, [&](int k) { return sim.images[static_cast<std::size_t>(k)]; }, o);
    hull::SonarRunOptions g;
    g.ekf.init = init;
    g.keep_features = false;
    const auto given = hull::RunSonarSequence(sim.sequence, g);
    const hull::SonarGivenComparison c = hull::CompareWithGiven(r, given);
    const auto& e = r.evaluation;
    rate += e.mean_detection_rate;
    worst = std::min(worst, e.min_detection_rate);
    below += e.frames_below_90;
    frames += e.frames;
    assoc += e.associations;
    wrong += e.wrong_associations;
    features += e.final_features;
    truth += e.final_features_with_truth;
    image_error += e.final_mean_error;
    given_error += c.given_error;
    if (c.features > 0) ratios.push_back(e.final_mean_error / c.given_error);
  }
  std::sort(ratios.begin(), ratios.end());
  std::printf(
      "%-6s %-10s %2d seeds  detected %5.1f %% per frame (worst %3.0f %%, %3d/%4d frames < 90 %%)  wrong %2d/%5d "
      "(%.2f %%)  error %.4f m vs given %.4f m: ratio %.2f (median per run %.2f)  features %.1f (%.1f with truth)\n",
      preset, hull::SonarInitName(init), seeds, 100 * rate / seeds, 100 * worst, below, frames, wrong, assoc,
      100.0 * wrong / std::max(1, assoc), image_error / seeds, given_error / seeds, image_error / given_error,
      ratios.empty() ? 0.0 : ratios[ratios.size() / 2], static_cast<double>(features) / seeds,
      static_cast<double>(truth) / seeds);
}

void WriteFrames(const char* preset, const std::string& dir) {
  const SonarImageSimulation sim = hull::SimulateSonarImages(hull::SonarImagePreset(preset, 1));
  const hull::AcousticSequence& seq = sim.sequence;
  const hull::SonarFan fan(seq.sensor, *seq.image, 600);
  std::filesystem::create_directories(dir);
  for (int k = 0; k < seq.num_steps(); k += std::max(1, seq.num_steps() / 4)) {
    const cv::Mat& polar = sim.images[static_cast<std::size_t>(k)];
    const auto dets = hull::DetectSonarFeatures(polar, seq.sensor, *seq.image);
    cv::Mat f, p;
    cv::cvtColor(fan.Render(polar), f, cv::COLOR_GRAY2BGR);
    cv::resize(polar, p, cv::Size(polar.cols * 3, polar.rows), 0, 0, cv::INTER_NEAREST);
    cv::cvtColor(p, p, cv::COLOR_GRAY2BGR);
    for (const hull::SonarMeasurement& m : seq.measurements) {
      if (m.step != k) continue;
      const Eigen::Vector3d polar_true = hull::SonarPolarOf(seq.truth->poses[static_cast<std::size_t>(k)],
                                                            seq.truth->features[static_cast<std::size_t>(m.feature)]);
      const Eigen::Vector2d q = fan.ToPixel(polar_true[0], polar_true[1]);
      cv::circle(f, cv::Point(static_cast<int>(q.x()), static_cast<int>(q.y())), 7, cv::Scalar(0, 0, 255), 1);
      const double row = seq.image->RangeToRow(seq.sensor, polar_true[0]);
      const double col = seq.image->AzimuthToColumn(seq.sensor, polar_true[1]);
      cv::circle(p, cv::Point(static_cast<int>(3 * col + 1), static_cast<int>(row)), 7, cv::Scalar(0, 0, 255), 1);
    }
    for (const hull::SonarDetection& d : dets) {
      const Eigen::Vector2d q = fan.ToPixel(d.range, d.azimuth);
      cv::drawMarker(f, cv::Point(static_cast<int>(q.x()), static_cast<int>(q.y())), cv::Scalar(0, 255, 0),
                     cv::MARKER_CROSS, 6);
      cv::drawMarker(p, cv::Point(static_cast<int>(3 * d.col + 1), static_cast<int>(d.row)), cv::Scalar(0, 255, 0),
                     cv::MARKER_CROSS, 6);
    }
    cv::flip(p, p, 0);  // range up, as the fan
    const std::string base = dir + "/" + preset + "_" + std::to_string(k);
    cv::imwrite(base + "_fan.png", f);
    cv::imwrite(base + "_polar.png", p);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 200, seeds = 20;
  std::string write_frames;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) {
      frames = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) {
      seeds = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--write-frames") && i + 1 < argc) {
      write_frames = argv[++i];
    } else {
      std::fprintf(stderr, "usage: bench_sonar_images [--frames N] [--seeds N] [--write-frames DIR]\n");
      return 2;
    }
  }
  cv::setNumThreads(0);  // OpenCV sequential: one core
  std::printf("speed, 512 x 128 frames, one thread\n");
  for (const char* p : {"prism", "tank", "above"}) Speed(p, frames);
  if (seeds > 0) {
    std::printf("\naccuracy, images against the given correspondences of the same sequences\n");
    for (hull::SonarInit init : {hull::SonarInit::kHypotheses, hull::SonarInit::kPaper}) {
      for (const char* p : {"prism", "tank", "above"}) Accuracy(p, seeds, init);
    }
  }
  if (!write_frames.empty()) {
    for (const char* p : {"prism", "tank", "above"}) WriteFrames(p, write_frames);
    std::printf("\nframes written to %s\n", write_frames.c_str());
  }
  return 0;
}
