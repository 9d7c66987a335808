#include "cli/sonar_image_output.h"

#include "base/csv.h"
#include "base/file_io.h"

namespace hull::cli {
namespace {

const char* PairingName(SonarPairing p) {
  switch (p) {
    case SonarPairing::kInState:
      return "in_state";
    case SonarPairing::kWaiting:
      return "waiting";
    case SonarPairing::kNew:
      return "new";
  }
  return "?";
}

}  // namespace

void WriteSonarDetections(const SonarImageRunResult& r, const std::string& path) {
  std::vector<std::string> head = {"step",     "detection", "row",         "col",           "range",   "azimuth",
                                   "strength", "contrast",  "range_sigma", "azimuth_sigma", "feature", "pairing"};
  if (r.has_truth) head.push_back("truth_feature");
  CsvWriter csv(head);
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const SonarImageStep& s = r.steps[k];
    for (std::size_t j = 0; j < s.detections.size(); ++j) {
      const SonarDetection& d = s.detections[j];
      csv.Add(static_cast<std::int64_t>(k)).Add(static_cast<std::int64_t>(j)).Add(d.row).Add(d.col);
      csv.Add(d.range).Add(d.azimuth).Add(d.strength).Add(d.contrast);
      csv.Add(std::sqrt(d.covariance(0, 0))).Add(std::sqrt(d.covariance(1, 1)));
      csv.Add(s.track.feature[j]).Add(PairingName(s.track.pairing[j]));
      if (r.has_truth) {
        if (s.label[j] >= 0) {
          csv.Add(s.label[j]);
        } else {
          csv.AddEmpty();
        }
      }
      csv.EndRow();
    }
  }
  WriteFileAtomic(path, csv.text());
}

Json SonarImageSummary(const SonarImageRunResult& r) {
  Json o = Json::Object();
  std::int64_t detections = 0, in_state = 0, waiting = 0, started = 0, dropped = 0, fallbacks = 0;
  for (const SonarImageStep& s : r.steps) {
    detections += static_cast<std::int64_t>(s.detections.size());
    in_state += s.track.paired_in_state;
    waiting += s.track.paired_waiting;
    started += s.track.started;
    dropped += static_cast<std::int64_t>(s.track.dropped.size());
    fallbacks += s.track.jcbb_gave_up;
  }
  o.Set("detections", Json(detections));
  o.Set("paired_in_state", Json(in_state));
  o.Set("paired_waiting", Json(waiting));
  o.Set("features_started", Json(started));
  o.Set("features_dropped", Json(dropped));
  o.Set("jcbb_gave_up_steps", Json(fallbacks));
  o.Set("image_seconds", Json(r.image_seconds));
  o.Set("detect_seconds", Json(r.detect_seconds));
  o.Set("track_seconds", Json(r.track_seconds));
  if (r.has_truth) {
    const SonarImageEvaluation& e = r.evaluation;
    Json t = Json::Object();
    t.Set("frames_with_visible_features", Json(e.frames));
    t.Set("mean_detection_rate", Json(e.mean_detection_rate));
    t.Set("min_detection_rate", Json(e.min_detection_rate));
    t.Set("frames_below_90_percent", Json(e.frames_below_90));
    t.Set("clutter_per_frame", Json(e.clutter_per_frame));
    t.Set("associations", Json(e.associations));
    t.Set("wrong_associations", Json(e.wrong_associations));
    t.Set("in_state_associations", Json(e.in_state_associations));
    t.Set("wrong_in_state_associations", Json(e.wrong_in_state_associations));
    t.Set("final_features", Json(e.final_features));
    t.Set("final_features_with_truth", Json(e.final_features_with_truth));
    t.Set("duplicate_features", Json(e.duplicate_features));
    t.Set("final_mean_error", Json(e.final_mean_error));
    Json map = Json::Array();
    for (const auto& [feature, truth] : r.truth_of) {
      if (truth < 0) continue;
      Json f = Json::Object();
      f.Set("feature", Json(feature));
      f.Set("truth_feature", Json(truth));
      map.Push(std::move(f));
    }
    t.Set("truth_of_features", std::move(map));
    o.Set("truth", std::move(t));
  }
  return o;
}

}  // namespace hull::cli
