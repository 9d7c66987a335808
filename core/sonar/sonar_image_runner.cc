#include "sonar/sonar_image_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <set>

#include "base/error.h"
#include "sonar/acoustic_camera.h"
#include "survey/sonar_image.h"

namespace hull {
namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Feeds RunSonarSequence from the images: detect, associate, correct; and,
// with truth, labels every detection and keeps each feature's votes.
class ImageSource final : public SonarStepSource {
 public:
  ImageSource(const AcousticSequence& seq, const std::function<cv::Mat(int)>& image_of_step,
              const SonarImageRunOptions& options, SonarImageRunResult& result)
      : seq_(seq), image_of_step_(image_of_step), options_(options), result_(result), tracker_(options.tracker) {
    result_.has_truth =
        seq.truth && static_cast<int>(seq.truth->poses.size()) == seq.num_steps() && !seq.truth->features.empty();
    if (result_.has_truth && seq.has_measurements) {
      visible_.resize(static_cast<std::size_t>(seq.num_steps()));
      for (const SonarMeasurement& m : seq.measurements) visible_[static_cast<std::size_t>(m.step)].insert(m.feature);
    }
  }

  SonarStepEstimate Step(SonarEkf& ekf, const SonarControl* control, int k) override {
    auto t0 = std::chrono::steady_clock::now();
    const cv::Mat image = image_of_step_(k);
    result_.image_seconds += Seconds(t0);
    t0 = std::chrono::steady_clock::now();
    SonarImageStep step;
    step.detections = DetectSonarFeatures(image, seq_.sensor, *seq_.image, options_.detector);
    result_.detect_seconds += Seconds(t0);
    t0 = std::chrono::steady_clock::now();
    step.track = tracker_.Step(ekf, control, step.detections, *seq_.image);
    result_.track_seconds += Seconds(t0);
    if (result_.has_truth) Label(k, step);
    result_.steps.push_back(step);
    return step.track.estimate;
  }

  std::int64_t TruthId(std::int64_t feature) const override {
    auto it = votes_.find(feature);
    if (it == votes_.end()) return -1;
    std::int64_t best = -1;
    int count = 0;
    for (const auto& [label, n] : it->second) {
      if (n > count || (n == count && best < 0)) {
        best = label;
        count = n;
      }
    }
    return best;
  }

  const std::map<std::int64_t, std::map<std::int64_t, int>>& votes() const { return votes_; }

 private:
  void Label(int k, SonarImageStep& step) {
    const SonarTruth& truth = *seq_.truth;
    const Vector6d& pose = truth.poses[static_cast<std::size_t>(k)];
    const SonarImageFormat& f = *seq_.image;
    struct Projection {
      std::int64_t id;
      double row, col;
    };
    std::vector<Projection> all;
    std::vector<bool> visible;
    for (std::size_t i = 0; i < truth.features.size(); ++i) {
      const std::int64_t id = truth.feature_ids[i];
      const Eigen::Vector3d polar = SonarPolarOf(pose, truth.features[i]);
      visible.push_back(visible_.empty() ? InSonarView(seq_.sensor, polar)
                                         : visible_[static_cast<std::size_t>(k)].count(id) > 0);
      all.push_back({id, f.RangeToRow(seq_.sensor, polar[0]), f.AzimuthToColumn(seq_.sensor, polar[1])});
      step.visible += visible.back();
    }
    std::set<std::int64_t> detected;
    const double tol = options_.truth_tolerance;
    for (std::size_t j = 0; j < step.detections.size(); ++j) {
      const SonarDetection& d = step.detections[j];
      std::int64_t label = -1;
      double best = INFINITY;
      std::vector<std::int64_t> near;
      for (std::size_t i = 0; i < all.size(); ++i) {
        const Projection& p = all[i];
        if (std::abs(d.row - p.row) > tol || std::abs(d.col - p.col) > tol) continue;
        near.push_back(p.id);
        if (!visible[i]) continue;
        detected.insert(p.id);
        const double dist = std::hypot(d.row - p.row, d.col - p.col);
        if (dist < best) {
          best = dist;
          label = p.id;
        }
      }
      step.label.push_back(label);
      step.near.push_back(near);
      ++votes_[step.track.feature[j]][label];
    }
    step.visible_detected = static_cast<int>(detected.size());
  }

  const AcousticSequence& seq_;
  const std::function<cv::Mat(int)>& image_of_step_;
  const SonarImageRunOptions& options_;
  SonarImageRunResult& result_;
  SonarTracker tracker_;
  std::vector<std::set<std::int64_t>> visible_;                // per step, from measurements.csv
  std::map<std::int64_t, std::map<std::int64_t, int>> votes_;  // feature -> label -> detections
};

void Evaluate(const AcousticSequence& seq, SonarImageRunResult& r) {
  SonarImageEvaluation& e = r.evaluation;
  e.min_detection_rate = 1;
  int clutter = 0;
  for (const SonarImageStep& s : r.steps) {
    for (std::size_t j = 0; j < s.detections.size(); ++j) {
      clutter += s.label[j] < 0;
      if (s.track.pairing[j] == SonarPairing::kNew) continue;
      // Right when the detection lies on the feature's true feature (two true
      // features closer than the tolerance share their detections).
      const std::int64_t t = r.truth_of.at(s.track.feature[j]);
      const std::vector<std::int64_t>& near = s.near[j];
      const bool wrong = t < 0 ? s.label[j] >= 0 : std::find(near.begin(), near.end(), t) == near.end();
      ++e.associations;
      e.wrong_associations += wrong;
      if (s.track.pairing[j] == SonarPairing::kInState) {
        ++e.in_state_associations;
        e.wrong_in_state_associations += wrong;
      }
    }
    if (s.visible == 0) continue;
    ++e.frames;
    const double rate = static_cast<double>(s.visible_detected) / s.visible;
    e.mean_detection_rate += rate;
    e.min_detection_rate = std::min(e.min_detection_rate, rate);
    e.frames_below_90 += rate < 0.9;
  }
  if (e.frames > 0) e.mean_detection_rate /= e.frames;
  e.clutter_per_frame = r.steps.empty() ? 0 : static_cast<double>(clutter) / static_cast<double>(r.steps.size());
  std::set<std::int64_t> covered;
  std::map<std::int64_t, Eigen::Vector3d> truth;
  for (std::size_t i = 0; i < seq.truth->features.size(); ++i)
    truth[seq.truth->feature_ids[i]] = seq.truth->features[i];
  for (const SonarFeatureEstimate& f : r.run.final_features) {
    if (!f.in_state) continue;
    ++e.final_features;
    auto it = r.truth_of.find(f.id);
    if (it == r.truth_of.end() || it->second < 0) continue;
    ++e.final_features_with_truth;
    if (!covered.insert(it->second).second) ++e.duplicate_features;
    e.final_mean_error += (f.position - truth.at(it->second)).norm();
  }
  if (e.final_features_with_truth > 0) e.final_mean_error /= e.final_features_with_truth;
}

}  // namespace

bool SonarImageRunOptions::Check(std::string* why) const {
  if (!run.Check(why) || !detector.Check(why) || !tracker.Check(why)) return false;
  if (!(truth_tolerance > 0)) {
    if (why) *why = "truth_tolerance: must be positive";
    return false;
  }
  return true;
}

SonarImageRunResult RunSonarImages(const AcousticSequence& seq, const std::function<cv::Mat(int)>& image_of_step,
                                   const SonarImageRunOptions& options, Progress* progress) {
  std::string why;
  if (!options.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  if (!seq.image) throw std::invalid_argument("RunSonarImages: the sequence has no image block (version 1)");
  SonarImageRunResult result;
  ImageSource source(seq, image_of_step, options, result);
  result.run = RunSonarSequence(seq, options.run, source, progress);
  for (const auto& [feature, labels] : source.votes()) result.truth_of[feature] = source.TruthId(feature);
  if (result.has_truth) Evaluate(seq, result);
  return result;
}

SonarGivenComparison CompareWithGiven(const SonarImageRunResult& images, const SonarRunResult& given) {
  std::map<std::int64_t, double> error;  // true feature -> the given run's final error
  for (std::size_t i = 0; i < given.final_features.size(); ++i) {
    if (given.final_features[i].in_state) error[given.final_features[i].id] = given.final_feature_errors[i];
  }
  SonarGivenComparison c;
  for (const SonarFeatureEstimate& f : images.run.final_features) {
    const auto it = images.truth_of.find(f.id);
    if (!f.in_state || it == images.truth_of.end() || !error.count(it->second)) continue;
    c.given_error += error[it->second];
    ++c.features;
  }
  if (c.features > 0) c.given_error /= c.features;
  return c;
}

SonarImageRunResult RunSonarImages(const AcousticSequence& seq, const std::string& dir,
                                   const SonarImageRunOptions& options, Progress* progress) {
  if (!seq.image) {
    throw InputError({(std::filesystem::path(dir) / "sonar.json").string(), 0, 0, "version"},
                     "a version 1 acoustic sequence has no images; features from images need version 2");
  }
  const SonarImageFormat format = *seq.image;
  const std::function<cv::Mat(int)> read = [&](int k) { return ReadSonarImage(SonarImagePath(dir, k), format); };
  return RunSonarImages(seq, read, options, progress);
}

}  // namespace hull
