#include "ui/session/sonar_results.h"

#include <Eigen/Eigenvalues>
#include <filesystem>
#include <map>
#include <utility>

#include "base/error.h"
#include "geometry/mesh_io.h"
#include "results/file_hash.h"
#include "results/results_folder.h"
#include "results/sonar_files.h"
#include "simulate/sonar_image_simulator.h"
#include "sonar/sonar_pipeline.h"
#include "survey/sonar_image.h"

namespace hull::ui {

namespace {

// First estimates and bounds from the run's per-step records.
void Summarise(SonarRun& run) {
  std::map<std::int64_t, std::pair<Eigen::Vector3d, std::int64_t>> first;
  for (const SonarStepRecord& step : run.result.steps) {
    run.bounds.extend(step.estimate.pose.head<3>());
    run.bounds.extend(step.dead_reckoning.head<3>());
    for (const SonarFeatureEstimate& f : step.features) {
      run.bounds.extend(f.position);
      if (!first.count(f.id)) first[f.id] = {f.position, step.estimate.step};
    }
  }
  for (const auto& [id, value] : first) {
    run.feature_ids.push_back(id);
    run.initial.push_back(value.first);
    run.first_step.push_back(value.second);
  }
  if (run.sequence->truth) {
    for (const Vector6d& p : run.sequence->truth->poses) run.bounds.extend(p.head<3>());
    for (const Eigen::Vector3d& p : run.sequence->truth->features) run.bounds.extend(p);
  }
  if (run.smoother) {
    for (const Vector6d& p : run.smoother->result.poses) run.bounds.extend(p.head<3>());
    for (const SonarSmoothedFeature& f : run.smoother->result.features) run.bounds.extend(f.position);
  }
}

}  // namespace

SonarJobInput ReadSonarJobInput(const std::string& directory, const std::string& name) {
  SonarJobInput in;
  in.sequence = std::make_shared<const AcousticSequence>(ReadAcousticSequence(directory));
  in.name = name;
  in.directory = directory;
  const std::string scene = (std::filesystem::path(directory) / "truth" / "scene.ply").string();
  if (std::filesystem::exists(scene)) in.scene = std::make_shared<const TriangleMesh>(LoadMesh(scene));
  return in;
}

SonarJobInput SimulateSonarJobInput(const std::string& preset, std::uint64_t seed) {
  SonarImageSimulation sim = SimulateSonarImages(SonarImagePreset(preset, seed));
  SonarJobInput in;
  in.sequence = std::make_shared<const AcousticSequence>(std::move(sim.sequence));
  in.name = "demo: " + preset;
  in.images = std::make_shared<const std::vector<cv::Mat>>(std::move(sim.images));
  in.scene = std::make_shared<const TriangleMesh>(std::move(sim.scene.mesh));
  return in;
}

SonarRun RunSonarJob(std::shared_ptr<const SonarJobInput> shared, const SonarJobOptions& options, Progress& progress) {
  const SonarJobInput& input = *shared;
  const AcousticSequence& seq = *input.sequence;
  SonarRun run;
  run.name = input.name;
  run.scene = input.scene;
  const bool images_available = seq.image && (!input.directory.empty() || input.images);
  SonarPipelineOptions o = options.tuning;
  o.source = options.from_images && images_available ? SonarFeatureSource::kImages : SonarFeatureSource::kMeasurements;
  o.run.ekf.init = options.init;
  o.images.run.ekf.init = options.init;
  o.smoother = options.smoother;
  if (o.source == SonarFeatureSource::kMeasurements && !seq.has_measurements) {
    throw std::invalid_argument("'" + input.name +
                                "' has no measurements.csv: its features can only come from its images");
  }
  // The images the chain reads, kept for the fan view.
  std::vector<cv::Mat> kept(static_cast<std::size_t>(seq.num_steps()));
  std::function<cv::Mat(int)> read;
  if (o.source == SonarFeatureSource::kImages) {
    const SonarImageFormat format = *seq.image;
    read = [&](int k) {
      cv::Mat m = input.images ? input.images->at(static_cast<std::size_t>(k))
                               : ReadSonarImage(SonarImagePath(input.directory, k), format);
      kept[static_cast<std::size_t>(k)] = m;
      return m;
    };
  }
  SonarPipelineResult result = RunSonarPipeline(seq, input.directory, o, progress, read);
  if (!input.directory.empty()) run.pipeline = std::make_shared<const SonarPipelineResult>(result);
  run.from_images = result.from_images;
  run.result = std::move(result.run);
  if (result.images) {
    run.frames.resize(result.images->steps.size());
    for (std::size_t k = 0; k < result.images->steps.size(); ++k) {
      const SonarImageStep& s = result.images->steps[k];
      SonarFrame& f = run.frames[k];
      f.image = kept[k];
      f.detections = s.detections;
      f.predictions = s.track.predictions;
      f.feature = s.track.feature;
      f.pairing = s.track.pairing;
    }
  }
  run.smoother = std::move(result.smoother);
  run.sequence = input.sequence;
  run.input = std::move(shared);
  run.options = options;
  run.options.from_images = run.from_images;
  Summarise(run);
  return run;
}

SonarRun ReadSonarRun(const std::string& results_dir, Progress& progress) {
  progress.Update(0, "reading the sonar results");
  SonarPipelineResult saved = ReadSonarResults(results_dir);
  auto pipeline = std::make_shared<const SonarPipelineResult>(saved);
  const std::string summary = (std::filesystem::path(results_dir) / "summary.json").string();
  if (saved.sequence.empty() || !std::filesystem::exists(std::filesystem::path(saved.sequence) / "sonar.json")) {
    throw InputError({summary, 0, 0, "sequence"},
                     "the acoustic sequence the results were made from is not at '" + saved.sequence +
                         "' (the results are shown with it: its sensor, truth and images)");
  }
  if (const std::optional<ResultsManifest> m = ReadResultsManifest(results_dir)) {
    const ResultsInput* seq = m->run.Input("sequence");
    if (seq && !seq->hash.empty() && seq->hash != SequenceHash(saved.sequence)) {
      throw InputError({summary, 0, 0, "sequence"},
                       "the acoustic sequence " + saved.sequence + " changed since these results were made from it");
    }
  }
  progress.Update(0.3, "reading the acoustic sequence");
  auto input = std::make_shared<const SonarJobInput>(
      ReadSonarJobInput(saved.sequence, std::filesystem::path(saved.sequence).filename().string()));
  SonarRun run;
  run.name = input->name;
  run.scene = input->scene;
  run.sequence = input->sequence;
  run.from_images = saved.from_images;
  run.options.init = saved.run.options.init;
  run.options.from_images = saved.from_images;
  run.options.smoother = saved.smoother.has_value();
  if (saved.images) {
    const SonarImageFormat format = *input->sequence->image;
    run.frames.resize(saved.images->steps.size());
    for (std::size_t k = 0; k < run.frames.size(); ++k) {
      progress.ThrowIfCancelled();
      progress.Update(0.4 + 0.6 * static_cast<double>(k) / static_cast<double>(run.frames.size()),
                      "reading the acoustic images");
      const SonarImageStep& s = saved.images->steps[k];
      SonarFrame& f = run.frames[k];
      f.image = ReadSonarImage(SonarImagePath(saved.sequence, static_cast<long long>(k)), format);
      f.detections = s.detections;
      f.feature = s.track.feature;
      f.pairing = s.track.pairing;
    }
  }
  run.result = std::move(saved.run);
  run.smoother = std::move(saved.smoother);
  run.input = std::move(input);
  run.results_dir = std::filesystem::absolute(results_dir).lexically_normal().string();
  run.pipeline = std::move(pipeline);
  Summarise(run);
  return run;
}

SonarRun RunSonarJob(std::shared_ptr<const AcousticSequence> sequence, std::string name, SonarInit init,
                     Progress& progress) {
  auto in = std::make_shared<SonarJobInput>();
  in->sequence = std::move(sequence);
  in->name = std::move(name);
  SonarJobOptions o;
  o.init = init;
  o.from_images = false;
  return RunSonarJob(std::move(in), o, progress);
}

Ellipsoid ThreeSigmaEllipsoid(const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance) {
  Ellipsoid e;
  e.centre = mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 * (covariance + covariance.transpose()));
  e.axes = solver.eigenvectors();
  for (int i = 0; i < 3; ++i) e.radii[i] = 3.0 * std::sqrt(std::max(0.0, solver.eigenvalues()[i]));
  return e;
}

}  // namespace hull::ui
