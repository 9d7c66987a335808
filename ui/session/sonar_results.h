// An acoustic sequence run through the sonar EKF (Mai et al.), as the sonar
// dock plays it: the core's per-step records plus what the views draw —
// each feature's first estimate (where it entered the filter), the truth
// when the sequence has it, 3-sigma ellipsoids of the covariances, and, when
// the features came from the images, every frame of the image chain (the
// polar image, its detections, the EKF's predictions and the associations);
// the batch smoother's estimates when it was run; the scene mesh when the
// sequence has one. Computed in a job (RunSonarJob), Qt- and VTK-free.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/progress.h"
#include "geometry/triangle_mesh.h"
#include "sonar/sonar_pipeline.h"
#include "sonar/sonar_pipeline_result.h"
#include "sonar/sonar_runner.h"
#include "sonar/sonar_smoother_run.h"
#include "sonar/sonar_tracker.h"
#include "survey/acoustic_sequence.h"

namespace hull::ui {

// One step of the image chain, as the fan view draws it.
struct SonarFrame {
  cv::Mat image;                             // the polar image (range_bins x beams, 8- or 16-bit)
  std::vector<SonarDetection> detections;    // the front end's (CFAR) detections
  std::vector<SonarPrediction> predictions;  // the EKF's, before the correction
  std::vector<std::int64_t> feature;         // per detection: the feature it measured or started
  std::vector<SonarPairing> pairing;         // per detection
};

// What a sonar job reads: the sequence, where its images come from (a
// folder's images/<step>.png, or in memory for a simulation) and its scene.
struct SonarJobInput {
  std::shared_ptr<const AcousticSequence> sequence;
  std::string name;
  std::string directory;                               // the sequence folder ("" : in memory)
  std::shared_ptr<const std::vector<cv::Mat>> images;  // per step, when in memory
  std::shared_ptr<const TriangleMesh> scene;
};

struct SonarJobOptions {
  SonarInit init = SonarInit::kHypotheses;
  // Features from the images (version 2) instead of measurements.csv;
  // ignored (false) when the sequence has no images.
  bool from_images = true;
  bool smoother = false;  // the batch smoother after the EKF
  // The rest of the chain's options (the parameter table's "Sonar" rows,
  // ui/session/sonar_parameters.h); source, init and smoother above win.
  SonarPipelineOptions tuning;
};

struct SonarRun {
  std::string name;  // the sequence's name, or the demo preset
  std::shared_ptr<const AcousticSequence> sequence;
  SonarRunResult result;
  // Per feature id seen: its first estimate (the initialisation).
  std::vector<std::int64_t> feature_ids;
  std::vector<Eigen::Vector3d> initial;
  std::vector<std::int64_t> first_step;
  Eigen::AlignedBox3d bounds;  // poses, truth and estimates
  // Features from the images: one frame per step (else empty).
  bool from_images = false;
  std::vector<SonarFrame> frames;
  // The batch smoother after the EKF, when it was asked for.
  std::optional<SonarSmootherRun> smoother;
  // The scene the sequence was made from (truth/scene.ply), when present.
  std::shared_ptr<const TriangleMesh> scene;
  // What it was run from (to run it again with other options), and how.
  std::shared_ptr<const SonarJobInput> input;
  SonarJobOptions options;
  // The saved results it was read from ("" : computed in this session).
  std::string results_dir;
  // The whole result as the results layer writes it (Save sonar results):
  // set by RunSonarJob and ReadSonarRun; for a sequence read from a folder
  // (a simulation in memory has no folder for the results to name).
  std::shared_ptr<const SonarPipelineResult> pipeline;

  int steps() const { return static_cast<int>(result.steps.size()); }
};

// Reads an acoustic sequence folder for a job: the sequence and, when
// present, truth/scene.ply. Throws as ReadAcousticSequence and LoadMesh.
SonarJobInput ReadSonarJobInput(const std::string& directory, const std::string& name);
// Simulates a layout ("prism", "tank", "above") with its images and scene.
SonarJobInput SimulateSonarJobInput(const std::string& preset, std::uint64_t seed);

// Runs the EKF over the sequence (every step's features kept), from the
// images or the given measurements, then the smoother when asked. Throws
// what the reading and the runs throw (InputError naming a bad image).
SonarRun RunSonarJob(std::shared_ptr<const SonarJobInput> input, const SonarJobOptions& options, Progress& progress);
// A sonar results folder saved by `hullinspect-cli sonar` or the GUI
// (results/sonar_files.h) as the dock plays it, with the sequence it was
// made from (summary.json names it): truth, scene and, for features from the
// images, every frame's image and detections (the EKF's predictions are not
// saved: the frames have none). Throws InputError naming the file: the
// results unreadable or mixed, the sequence missing, or changed since the
// results were written (its fingerprint in the results' manifest).
SonarRun ReadSonarRun(const std::string& results_dir, Progress& progress);
// The given measurements only (no images, no smoother).
SonarRun RunSonarJob(std::shared_ptr<const AcousticSequence> sequence, std::string name, SonarInit init,
                     Progress& progress);

// A 3-sigma ellipsoid of a 3x3 covariance: centre, axes as columns (unit)
// and semi-axis lengths (3 sqrt(eigenvalue)).
struct Ellipsoid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d radii = Eigen::Vector3d::Zero();
};
Ellipsoid ThreeSigmaEllipsoid(const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance);

}  // namespace hull::ui
