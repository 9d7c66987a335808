#include "sonar/sonar_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/error.h"
#include "sonar/acoustic_camera.h"
#include "sonar/sonar_association.h"

namespace hull {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Inside the image's range and azimuth limits, `bins` bins and `beams` beams in from the borders.
bool InsideImage(const SonarSensor& s, const SonarImageFormat& f, double range, double azimuth, double bins,
                 double beams) {
  const double row = f.RangeToRow(s, range), col = f.AzimuthToColumn(s, azimuth);
  return row >= -0.5 + bins && row <= f.range_bins - 0.5 - bins && col >= -0.5 + beams && col <= f.beams - 0.5 - beams;
}

}  // namespace

bool SonarTrackerOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& field, const std::string& reason) {
    if (why) *why = field + ": " + reason;
    return false;
  };
  if (!(gate_probability > 0.5 && gate_probability < 1)) return fail("gate_probability", "must be in (0.5, 1)");
  if (max_jcbb_nodes < 1) return fail("max_jcbb_nodes", "must be at least 1");
  if (tentative_misses < 1) return fail("tentative_misses", "must be at least 1");
  if (drop_misses < 1) return fail("drop_misses", "must be at least 1");
  if (!(view_margin >= 0 && view_margin < 1)) return fail("view_margin", "must be in [0, 1)");
  if (first_id < 0) return fail("first_id", "must not be negative");
  return true;
}

SonarTracker::SonarTracker(const SonarTrackerOptions& options) : options_(options), next_id_(options.first_id) {
  std::string why;
  if (!options_.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
}

SonarTrackStep SonarTracker::Step(SonarEkf& ekf, const SonarControl* control,
                                  const std::vector<SonarDetection>& detections, const SonarImageFormat& image) {
  const SonarSensor& sensor = ekf.sensor();
  ekf.Predict(control);
  const std::int64_t step = ekf.step();
  const std::size_t m = detections.size();
  SonarTrackStep out;
  out.feature.assign(m, -1);
  out.pairing.assign(m, SonarPairing::kNew);
  std::vector<bool> taken(m, false);

  // 1. Features in the state predicted inside the image: JCBB.
  std::vector<std::int64_t> candidates, well_inside;
  for (std::int64_t id : ekf.FeatureIds()) {
    const Eigen::Vector3d polar = SonarPolarOf(ekf.pose(), ekf.Feature(id)->position);
    if (!InsideImage(sensor, image, polar[0], polar[1], 0, 0)) continue;
    if (std::abs(polar[2]) > sensor.elevation_fov / 2 * (1 + options_.view_margin)) continue;
    candidates.push_back(id);
    if (std::abs(polar[2]) <= sensor.elevation_fov / 2 * (1 - options_.view_margin) &&
        InsideImage(sensor, image, polar[0], polar[1], 2, 2)) {
      well_inside.push_back(id);
    }
  }
  out.candidates = static_cast<int>(candidates.size());
  AssociationInput in;
  for (const SonarDetection& d : detections) {
    in.detected.emplace_back(d.range, d.azimuth);
    in.noise.push_back(d.covariance);
  }
  std::vector<int> paired(candidates.size(), -1);
  if (!candidates.empty()) ekf.PredictMeasurements(candidates, &in.predicted, &in.covariance);
  if (!candidates.empty() && m > 0) {
    if (options_.joint_compatibility) {
      const Association a = JointCompatibility(in, options_.gate_probability, options_.max_jcbb_nodes);
      paired = a.detection;
      out.jcbb_nodes = a.nodes;
      out.jcbb_gave_up = !a.jcbb;
    } else {
      paired = OptimalAssignment(IndividualDistances(in, options_.gate_probability),
                                 ChiSquareQuantile(options_.gate_probability, 2));
    }
  }
  std::vector<SonarMeasurement> measurements;
  const auto measure = [&](std::size_t j, std::int64_t id, SonarPairing how) {
    const SonarDetection& d = detections[j];
    SonarMeasurement z;
    z.step = step;
    z.feature = id;
    z.range = d.range;
    z.azimuth = d.azimuth;
    z.range_sigma = std::sqrt(d.covariance(0, 0));
    z.azimuth_sigma = std::sqrt(d.covariance(1, 1));
    measurements.push_back(z);
    taken[j] = true;
    out.feature[j] = id;
    out.pairing[j] = how;
  };
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    SonarPrediction p;
    p.id = candidates[i];
    const auto k = static_cast<Eigen::Index>(2 * i);
    p.z = in.predicted.segment<2>(k);
    p.covariance = in.covariance.block<2, 2>(k, k);
    p.detection = paired[i];
    out.predictions.push_back(p);
  }
  std::unordered_map<std::int64_t, bool> seen;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (paired[i] < 0) continue;
    measure(static_cast<std::size_t>(paired[i]), candidates[i], SonarPairing::kInState);
    seen[candidates[i]] = true;
    ++out.paired_in_state;
  }

  // 2. Tentative features: optimal assignment of the remaining detections,
  // each pair's distance that of the feature's best elevation hypothesis.
  const std::vector<std::int64_t> waiting = ekf.PendingIds();
  std::vector<int> waiting_prediction(waiting.size(), -1);  // index into out.predictions
  for (std::size_t w = 0; w < waiting.size(); ++w) {
    const std::vector<SonarEkf::HypothesisPrediction> hs = ekf.PredictPending(waiting[w]);
    const auto best =
        std::max_element(hs.begin(), hs.end(), [](const auto& a, const auto& b) { return a.weight < b.weight; });
    if (best == hs.end() || !InsideImage(sensor, image, best->z[0], best->z[1], 0, 0)) continue;
    SonarPrediction p;
    p.id = waiting[w];
    p.z = best->z;
    p.covariance = best->S;
    p.waiting = true;
    waiting_prediction[w] = static_cast<int>(out.predictions.size());
    out.predictions.push_back(p);
  }
  if (!waiting.empty() && m > 0) {
    const double gate = ChiSquareQuantile(options_.gate_probability, 2);
    Eigen::MatrixXd cost =
        Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(waiting.size()), static_cast<Eigen::Index>(m), kInf);
    for (std::size_t w = 0; w < waiting.size(); ++w) {
      for (const SonarEkf::HypothesisPrediction& h : ekf.PredictPending(waiting[w])) {
        for (std::size_t j = 0; j < m; ++j) {
          if (taken[j]) continue;
          const Eigen::Matrix2d S = h.S + detections[j].covariance;
          Eigen::Vector2d nu = in.detected[j] - h.z;
          nu[1] = std::remainder(nu[1], 2 * M_PI);
          const double d2 = nu.dot(S.ldlt().solve(nu));
          auto& c = cost(static_cast<Eigen::Index>(w), static_cast<Eigen::Index>(j));
          if (d2 <= gate && d2 < c) c = d2;
        }
      }
    }
    const std::vector<int> assigned = OptimalAssignment(cost, gate);
    for (std::size_t w = 0; w < waiting.size(); ++w) {
      if (assigned[w] < 0) continue;
      measure(static_cast<std::size_t>(assigned[w]), waiting[w], SonarPairing::kWaiting);
      if (waiting_prediction[w] >= 0)
        out.predictions[static_cast<std::size_t>(waiting_prediction[w])].detection = assigned[w];
      seen[waiting[w]] = true;
      ++out.paired_waiting;
    }
  }

  // 3. New tentative features from the rest.
  for (std::size_t j = 0; j < m; ++j) {
    if (taken[j]) continue;
    measure(j, next_id_++, SonarPairing::kNew);
    ++out.started;
  }
  out.estimate = ekf.Correct(measurements);

  // 4. Misses and drops.
  for (std::int64_t id : well_inside) {
    if (seen.count(id)) continue;
    if (++misses_[id] >= options_.drop_misses) out.dropped.push_back(id);
  }
  const std::vector<std::int64_t> still_waiting = ekf.PendingIds();  // sorted
  for (std::int64_t id : waiting) {
    if (seen.count(id) || !std::binary_search(still_waiting.begin(), still_waiting.end(), id)) continue;
    if (++misses_[id] >= options_.tentative_misses) out.dropped.push_back(id);
  }
  for (const auto& [id, yes] : seen) misses_[id] = 0;
  for (std::int64_t id : out.dropped) {
    ekf.DropFeature(id);
    misses_.erase(id);
  }
  out.estimate.pending = ekf.num_pending();
  return out;
}

}  // namespace hull
