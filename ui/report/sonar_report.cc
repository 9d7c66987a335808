#include "ui/report/sonar_report.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sonar/sonar_association.h"
#include "sonar/sonar_consistency.h"
#include "ui/report/report_blocks.h"

namespace hull::report {
namespace {

const SonarPipelineResult& Sonar(const ReportInputs& in) { return *in.sonar; }

// sqrt(trace) of a 3x3 covariance: the point's combined standard deviation (m).
double Spread(const Eigen::Matrix3d& c) { return std::sqrt(std::max(0.0, c.trace())); }

int InState(const std::vector<SonarFeatureEstimate>& f) {
  return static_cast<int>(std::count_if(f.begin(), f.end(), [](const SonarFeatureEstimate& e) { return e.in_state; }));
}

std::string Verdict(const ConsistencyCheck& c, const std::string& what) {
  if (!c.known) return what + ": not known.";
  const std::string figures = Format(
      "%s = %.4g over %d degrees of freedom (%.2f per degree; 95 %% interval %.4g to "
      "%.4g)",
      what.c_str(), c.value, c.dof, c.value / c.dof, c.low, c.high);
  if (c.consistent) return figures + ": consistent.";
  if (c.value > c.high) {
    return figures + Format(
                         ": INCONSISTENT. The errors are larger than the covariance claims (by about %.1f× in "
                         "standard deviation); the stated uncertainties are too small and must not be trusted.",
                         std::sqrt(c.value / c.dof));
  }
  return figures + ": the errors are smaller than the covariance claims (the uncertainties are conservative).";
}

Section SummarySection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"summary", "Summary", false, {}};
  const SonarRunResult& run = r.run;
  std::vector<std::pair<std::string, std::string>> facts = {
      {"Sequence", r.sequence},
      {"Features from", r.from_images ? "the acoustic images (detection, association, tracking)"
                                      : "the given measurements (measurements.csv)"},
      {"Steps", Count(static_cast<long long>(run.steps.size()))},
  };
  if (!in.results_path.empty()) facts.push_back({"Results", in.results_path});
  if (r.from_images && r.images) {
    long long detections = 0;
    for (const SonarImageStep& st : r.images->steps) detections += static_cast<long long>(st.detections.size());
    facts.push_back({"Detections", Count(detections)});
  } else {
    facts.push_back({"Measurements", Count(r.measurements)});
  }
  facts.push_back({"Features placed",
                   Format("%d in the filter's state, %d still waiting for their elevation", InState(run.final_features),
                          static_cast<int>(run.final_features.size()) - InState(run.final_features))});
  if (r.smoother) {
    const SonarSmootherResult& m = r.smoother->result;
    facts.push_back({"Smoother", Format("%d iterations, %s; %zu features", m.iterations,
                                        m.converged ? "converged" : "NOT converged", m.features.size())});
  }
  facts.push_back({"Consistency (no truth needed)", CheckSonarConsistency(run).Verdict()});
  facts.push_back({"Truth", run.has_truth ? "yes: errors and NEES in the evaluation section" : "none"});
  s.blocks.push_back(Facts(std::move(facts)));
  return s;
}

Section NotPlacedSection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"not-placed", "What the run could not place", false, {}};
  std::vector<std::string> items;
  std::vector<int> blind;
  for (std::size_t k = 0; k < r.run.steps.size(); ++k) {
    if (r.run.steps[k].estimate.measurements == 0) blind.push_back(static_cast<int>(k));
  }
  items.push_back(blind.empty()
                      ? std::string("Every step measured at least one feature.")
                      : Format("Steps without a measurement: %zu of %zu (", blind.size(), r.run.steps.size()) +
                            Ranges(blind) +
                            "); the pose there is dead reckoning corrected only by its "
                            "neighbours.");
  const int waiting = static_cast<int>(r.run.final_features.size()) - InState(r.run.final_features);
  items.push_back(Format("Features seen but never placed (their elevation still unresolved at the end): %d.", waiting));
  if (r.smoother) {
    int held = 0;
    for (const SonarSmoothedFeature& f : r.smoother->result.features) held += f.smoothed ? 0 : 1;
    items.push_back(Format("Features the smoother held out (too few views, or elevation not observable): %d.", held));
  }
  s.blocks.push_back(List(std::move(items)));
  return s;
}

Section MethodSection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  const SonarEkfOptions& e = r.run.options;
  Section s{"method", "Method", false, {}};
  s.blocks.push_back(Paragraph(
      "An extended Kalman filter over the vehicle pose and the point features of the imaging sonar (Mai et al.): "
      "each feature is measured in range and azimuth; its elevation, which the sonar does not measure, is "
      "resolved over several views. " +
      std::string(r.from_images ? "Features were detected in each acoustic image and associated with the filter's "
                                  "predictions (joint compatibility, JCBB) before the update."
                                : "The features' correspondences were given with the sequence.") +
      (r.smoother ? " A batch smoother (Ceres) then re-estimated every pose and feature from all measurements." : "")));
  std::vector<std::pair<std::string, std::string>> facts = {
      {"Elevation initialisation",
       std::string(SonarInitName(e.init)) + (e.init == SonarInit::kHypotheses
                                                 ? Format(" (%d hypotheses)", e.hypotheses)
                                                 : Format(" (σ = %.2f of the fan)", e.paper_elevation_sigma_fraction))},
      {"Views before a feature enters", Format("%d", e.confirm_views)},
      {"Covariance update", e.joseph ? "Joseph form" : "short form"},
  };
  if (r.from_images) {
    const SonarDetectorOptions& d = r.image_options.detector;
    facts.push_back({"Detector", Format("contrast ≥ %.0f levels, prominence ≥ %.0f, at most %d per image",
                                        d.min_contrast, d.min_prominence, d.max_detections)});
  }
  s.blocks.push_back(Facts(std::move(facts)));
  return s;
}

Section TrajectorySection(const std::vector<FigureRef>& figures) {
  Section s{"trajectory", "Trajectory and features", true, {}};
  for (const FigureRef& f : figures) s.blocks.push_back(FigureBlock(f));
  return s;
}

Table FeatureTable(const SonarPipelineResult& r) {
  Table t = MakeTable({{"feature"},
                       {"x (m)", true},
                       {"y (m)", true},
                       {"z (m)", true},
                       {"σ (m)", true},
                       {"views", true},
                       {"first step", true},
                       {"state"}});
  if (r.run.has_truth) AddColumn(t, {"error (m)", true});
  for (std::size_t i = 0; i < r.run.final_features.size(); ++i) {
    const SonarFeatureEstimate& f = r.run.final_features[i];
    std::vector<std::string> row = {std::to_string(f.id),         Num(f.position.x(), 3),
                                    Num(f.position.y(), 3),       Num(f.position.z(), 3),
                                    Num(Spread(f.covariance), 3), std::to_string(f.observations),
                                    std::to_string(f.first_step), f.in_state ? "placed" : "waiting"};
    if (r.run.has_truth) {
      row.push_back(i < r.run.final_feature_errors.size() ? Num(r.run.final_feature_errors[i], 3) : "–");
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

Section FeaturesSection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"features", "Features", true, {}};
  if (r.run.final_features.empty()) {
    s.blocks.push_back(Paragraph("The run placed no feature."));
    return s;
  }
  s.blocks.push_back(
      Paragraph("The filter's features at the last step, in the world frame; σ is the square root of "
                "the trace of each point's covariance."));
  s.blocks.push_back(TableBlock(FeatureTable(r)));
  return s;
}

Section ConsistencySection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"consistency", "Consistency of the estimate", false, {}};
  s.blocks.push_back(Paragraph(
      "An estimate is only useful with an honest uncertainty. Without truth, the filter's normalised innovations "
      "(NIS) must follow their chi-square distribution; with truth, so must the normalised estimation errors (NEES) "
      "of the pose and features."));
  const SonarConsistency nis = CheckSonarConsistency(r.run);
  std::vector<std::string> items = {"Filter, its innovations (NIS, over all updates and windows of " +
                                    std::to_string(nis.window) + " steps): " + nis.Verdict() + "."};
  if (!r.run.steps.empty() && r.run.steps.back().errors) {
    const SonarStepErrors& e = *r.run.steps.back().errors;
    items.push_back(Verdict(CheckConsistency(e.joint_nees, e.joint_nees_dof), "Filter, joint NEES at the last step"));
  }
  if (r.smoother && r.smoother->errors) {
    const SonarSmootherErrors& e = *r.smoother->errors;
    items.push_back(Verdict(CheckConsistency(e.joint_nees, e.joint_nees_dof), "Smoother, joint NEES"));
  }
  s.blocks.push_back(List(std::move(items)));
  for (const std::string& line : s.blocks.back().items) {
    if (line.find("INCONSISTENT") != std::string::npos || line.find("must not be trusted") != std::string::npos) {
      s.blocks.push_back(Note("At least one check fails: treat the features' σ in this report as optimistic."));
      break;
    }
  }
  return s;
}

Section ImagesSection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"images", "Acoustic images", false, {}};
  if (!r.from_images || !r.images) {
    s.blocks.push_back(Paragraph("The features came from given measurements; no image was read."));
    return s;
  }
  std::vector<double> per_step;
  int at_cap = 0;
  for (const SonarImageStep& st : r.images->steps) {
    per_step.push_back(static_cast<double>(st.detections.size()));
    at_cap += static_cast<int>(st.detections.size()) >= r.image_options.detector.max_detections ? 1 : 0;
  }
  std::vector<std::pair<std::string, std::string>> facts = {
      {"Images", Count(static_cast<long long>(per_step.size()))},
      {"Detections per image (median, 90 %)", Quantile(per_step, 0.5, 0) + ", " + Quantile(per_step, 0.9, 0)},
      {"Images with the detector at its cap", Format("%d", at_cap)},
  };
  const double seconds = r.images->image_seconds + r.images->detect_seconds + r.images->track_seconds;
  if (seconds > 0) facts.push_back({"Time", Duration(seconds)});
  if (r.images->has_truth) {
    const SonarImageEvaluation& e = r.images->evaluation;
    facts.push_back(
        {"Detection rate (mean, worst frame)", Percent(e.mean_detection_rate) + ", " + Percent(e.min_detection_rate)});
    facts.push_back({"Clutter per frame", Num(e.clutter_per_frame, 2)});
    facts.push_back(
        {"Wrong associations", Format("%d of %d (in the state: %d of %d)", e.wrong_associations, e.associations,
                                      e.wrong_in_state_associations, e.in_state_associations)});
    facts.push_back({"Features on a true feature", Format("%d of %d (%d duplicates)", e.final_features_with_truth,
                                                          e.final_features, e.duplicate_features)});
  }
  s.blocks.push_back(Facts(std::move(facts)));
  return s;
}

Section SmootherSection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"smoother", "Smoother", false, {}};
  if (!r.smoother) {
    s.blocks.push_back(Paragraph("The smoother did not run (hullinspect-cli sonar --smoother)."));
    return s;
  }
  const SonarSmootherResult& m = r.smoother->result;
  s.blocks.push_back(Facts({
      {"Iterations", Format("%d, %s", m.iterations, m.converged ? "converged" : "NOT converged")},
      {"Cost", Num(m.initial_cost, 4) + " → " + Num(m.final_cost, 4)},
      {"Measurements used", Count(m.measurements_used)},
      {"Covariance", m.covariance_ok ? "computed" : "FAILED: the smoothed points have no uncertainty"},
      {"Time", Duration(m.solve_seconds + m.covariance_seconds)},
  }));
  return s;
}

Section EvaluationSection(const ReportInputs& in) {
  const SonarPipelineResult& r = Sonar(in);
  Section s{"evaluation", "Evaluation against truth", false, {}};
  if (!r.run.has_truth || r.run.steps.empty() || !r.run.steps.back().errors) {
    s.blocks.push_back(Paragraph("The sequence has no truth: no error can be given."));
    return s;
  }
  const SonarStepErrors& e = *r.run.steps.back().errors;
  std::vector<std::pair<std::string, std::string>> facts = {
      {"Last pose, filter", Metres(e.position, 4) + Format(", %.3f°", e.rotation * 180 / M_PI)},
      {"Last pose, dead reckoning", Metres(e.dr_position, 4) + Format(", %.3f°", e.dr_rotation * 180 / M_PI)},
  };
  if (e.features > 0) {
    facts.push_back({"Features, filter (mean, max)", Metres(e.mean_feature_error, 4) + ", " +
                                                         Metres(e.max_feature_error, 4) +
                                                         Format(" over %d features with truth", e.features)});
  } else {
    facts.push_back({"Features, filter", "no feature in the state stands for a true one"});
  }
  if (r.smoother && r.smoother->errors && r.smoother->errors->features > 0) {
    const SonarSmootherErrors& m = *r.smoother->errors;
    facts.push_back(
        {"Features, smoother (mean, max)", Metres(m.mean_feature_error, 4) + ", " + Metres(m.max_feature_error, 4) +
                                               Format(" over %d; predicted %.4f m", m.features, m.predicted_error)});
    facts.push_back({"Last pose, smoother", Metres(m.position, 4)});
  }
  s.blocks.push_back(Facts(std::move(facts)));
  return s;
}

}  // namespace

ConsistencyCheck CheckConsistency(double value, int dof) {
  ConsistencyCheck c;
  c.value = value;
  c.dof = dof;
  c.known = std::isfinite(value) && dof >= 1;
  if (!c.known) return c;
  c.low = ChiSquareQuantile(0.025, dof);
  c.high = ChiSquareQuantile(0.975, dof);
  c.consistent = value >= c.low && value <= c.high;
  return c;
}

std::vector<std::string> SonarSectionIds() {
  return {"summary",     "not-placed", "method",   "trajectory", "features",
          "consistency", "images",     "smoother", "evaluation"};
}

std::vector<FigureRef> PlanSonarFigures(const ReportInputs& in) {
  std::vector<FigureRef> out;
  FigureRef plan;
  plan.id = "sonar-plan";
  plan.kind = FigureKind::kSonarPlan;
  plan.title = "Trajectory and features, plan view";
  plan.caption =
      "The vehicle's path seen from above (x right, y up, world frame): the filter's estimate, dead reckoning from "
      "the controls alone" +
      std::string(Sonar(in).smoother ? ", the smoother's estimate" : "") +
      ", and the features placed with their 2σ ellipses in x and y.";
  out.push_back(plan);
  if (Sonar(in).run.has_truth) {
    FigureRef err;
    err.id = "sonar-errors";
    err.kind = FigureKind::kSonarErrors;
    err.title = "Errors against truth per step";
    err.caption = "Position error of the filter, of dead reckoning" +
                  std::string(Sonar(in).smoother ? " and of the smoother" : "") +
                  ", and the filter's mean feature error over its features with truth, per step.";
    out.push_back(err);
  }
  return out;
}

ReportDocument BuildSonarReportDocument(const ReportInputs& in, const ReportOptions& options,
                                        const std::vector<FigureRef>& figures, const std::string& generated) {
  ReportDocument d;
  d.title = options.title.empty() ? "Imaging-sonar report" : options.title;
  d.subtitle = Sonar(in).sequence;
  d.generated = generated;
  d.sections.push_back(SummarySection(in));
  d.sections.push_back(NotPlacedSection(in));
  d.sections.push_back(MethodSection(in));
  d.sections.push_back(TrajectorySection(figures));
  d.sections.push_back(FeaturesSection(in));
  d.sections.push_back(ConsistencySection(in));
  d.sections.push_back(ImagesSection(in));
  d.sections.push_back(SmootherSection(in));
  d.sections.push_back(EvaluationSection(in));
  return d;
}

}  // namespace hull::report
