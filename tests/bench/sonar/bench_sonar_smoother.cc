// bench_sonar_smoother: the batch smoother after the sonar EKF (issue 11).
//
//   bench_sonar_smoother [--seeds N] [--layouts prism,tank,above] [--no-accuracy] [--no-timing]
//                        [--images] [--accuracy-steps T] [--steps T1,T2] [--extra-features N]
//
// Accuracy (N seeded sequences per layout, default 20): the final mean
// feature error of the EKF with the paper's initialisation (--init paper),
// of the EKF with elevation hypotheses (the default) and of the smoother
// started from the latter, medians and ranges; the smoother's consistency:
// the joint NEES of the last pose and the points and the points' own NEES,
// summed over the runs and divided by the summed degrees of freedom, with
// the two-sided chi-square 95 % interval of that ratio, and the pose NEES
// over every step. --accuracy-steps T: trajectories of T steps instead of
// the presets' (prism and above: the same sweep, sampled more densely).
// Timing: the smoother (solve and covariances) on the prism trajectory with
// T = 21 and 500 steps (8 vertices plus --extra-features random points), one
// thread. --images: also the image chain (rendered images, detection,
// association, EKF) and the smoother over its associations, per layout.
// --extra-features N: N random points near the prism in both.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "simulate/sonar_image_simulator.h"
#include "simulate/sonar_simulator.h"
#include "sonar/sonar_runner.h"
#include "sonar/sonar_smoother_run.h"

namespace {

using namespace hull;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Chi-square quantile (Wilson-Hilferty; exact enough above a few dof).
double ChiSquareQuantile(double dof, double z) {
  const double c = 2.0 / (9.0 * dof);
  return dof * std::pow(1 - c + z * std::sqrt(c), 3);
}

struct Ratio {
  double sum = 0, dof = 0;
  void Add(double nees, double d) {
    if (!std::isfinite(nees)) return;
    sum += nees;
    dof += d;
  }
  void Print(const char* what) const {
    if (dof <= 0) {
      std::printf("  %-34s not computed (no joint covariance above max_joint_features)\n", what);
      return;
    }
    const double lo = ChiSquareQuantile(dof, -1.959964) / dof, hi = ChiSquareQuantile(dof, 1.959964) / dof;
    const double r = sum / dof;
    std::printf("  %-34s %.3f  (95 %% interval [%.3f, %.3f], %.0f dof): %s\n", what, r, lo, hi, dof,
                r < lo   ? "below (conservative)"
                : r > hi ? "ABOVE (overconfident)"
                         : "inside");
  }
};

Eigen::Vector3d TruthOf(const AcousticSequence& seq, std::int64_t id) {
  for (std::size_t i = 0; i < seq.truth->feature_ids.size(); ++i) {
    if (seq.truth->feature_ids[i] == id) return seq.truth->features[i];
  }
  return Eigen::Vector3d::Constant(NAN);
}

double EkfShapeError(const AcousticSequence& seq, const SonarRunResult& r) {
  std::vector<Eigen::Vector3d> est, tru;
  for (const SonarFeatureEstimate& f : r.final_features) {
    if (!f.in_state) continue;
    est.push_back(f.position);
    tru.push_back(TruthOf(seq, f.id));
  }
  return MeanAlignedError(est, tru);
}

void Accuracy(SonarPreset preset, int seeds, int steps, int extra) {
  std::vector<double> paper, hyp, smooth, smooth_from_paper, smooth_from_truth, iterations, seconds;
  std::vector<double> shape_paper, shape_hyp, shape_smooth, predicted, ekf_track, smooth_track;
  Ratio joint, points, poses, ekf_joint;
  for (int s = 1; s <= seeds; ++s) {
    SonarSimulationOptions so;
    so.preset = preset;
    so.seed = static_cast<std::uint64_t>(s);
    so.num_steps = steps;
    so.extra_features = extra;
    so.extra_box = Eigen::Vector3d(0.5, 0.6, 0.3);  // inside the fan along the whole trajectory
    const AcousticSequence seq = SimulateSonar(so);
    SonarRunOptions po;
    po.ekf.init = SonarInit::kPaper;
    const SonarRunResult ekf_paper = RunSonarSequence(seq, po);
    paper.push_back(ekf_paper.steps.back().errors->mean_feature_error);
    const SonarRunResult ekf = RunSonarSequence(seq);
    const SonarStepErrors& fe = *ekf.steps.back().errors;
    hyp.push_back(fe.mean_feature_error);
    ekf_joint.Add(fe.joint_nees, fe.joint_nees_dof);
    const SonarSmootherRun sm = RunSonarSmoother(seq, ekf, seq.measurements);
    const SonarSmootherErrors& e = *sm.errors;
    smooth.push_back(e.mean_feature_error);
    smooth_from_paper.push_back(RunSonarSmoother(seq, ekf_paper, seq.measurements).errors->mean_feature_error);
    shape_smooth.push_back(e.shape_error);
    double track = 0;
    for (const SonarStepRecord& st : ekf.steps) track += st.errors->position / static_cast<double>(ekf.steps.size());
    ekf_track.push_back(track);
    smooth_track.push_back(e.mean_position);
    predicted.push_back(e.predicted_error);
    shape_paper.push_back(EkfShapeError(seq, ekf_paper));
    shape_hyp.push_back(EkfShapeError(seq, ekf));
    // From the truth: what the adjustment reaches when its start is perfect.
    SonarRunResult perfect = ekf;
    for (std::size_t k = 0; k < perfect.steps.size(); ++k) perfect.steps[k].estimate.pose = seq.truth->poses[k];
    for (SonarFeatureEstimate& f : perfect.final_features) f.position = TruthOf(seq, f.id);
    smooth_from_truth.push_back(RunSonarSmoother(seq, perfect, seq.measurements).errors->mean_feature_error);
    iterations.push_back(sm.result.iterations);
    seconds.push_back(sm.result.solve_seconds + sm.result.covariance_seconds);
    joint.Add(e.joint_nees, e.joint_nees_dof);
    points.Add(e.mean_point_nees * e.features, 3.0 * e.features);
    for (double n : sm.pose_nees) poses.Add(n, 6);
  }
  const auto range = [](const std::vector<double>& v) {
    char b[64];
    std::snprintf(b, sizeof(b), "%.4f (%.4f..%.4f)", Median(v), *std::min_element(v.begin(), v.end()),
                  *std::max_element(v.begin(), v.end()));
    return std::string(b);
  };
  std::printf("%s, T = %s, %d extra features, %d seeds: final mean feature error, median (range)\n",
              SonarPresetName(preset), steps > 0 ? std::to_string(steps).c_str() : "the preset's", extra, seeds);
  std::printf("  EKF, --init paper                  %s m\n", range(paper).c_str());
  std::printf("  EKF, --init hypotheses             %s m\n", range(hyp).c_str());
  std::printf("  smoother (from the hypotheses EKF) %s m   = %.2f x the paper's filter\n", range(smooth).c_str(),
              Median(smooth) / Median(paper));
  std::printf("  smoother (from the paper's EKF)    %s m\n", range(smooth_from_paper).c_str());
  std::printf("  smoother (from the truth)          %s m\n", range(smooth_from_truth).c_str());
  std::printf("  smoother's predicted error, mean sqrt(trace P) %s m\n", range(predicted).c_str());
  std::printf("  shape error (after the best rigid alignment): EKF paper %.4f, EKF hypotheses %.4f, smoother %.4f m\n",
              Median(shape_paper), Median(shape_hyp), Median(shape_smooth));
  std::printf("  position error over every step, mean: EKF (filtered) %s m, smoother %s m\n", range(ekf_track).c_str(),
              range(smooth_track).c_str());
  std::printf("  smoother iterations %.0f, time %.1f ms (medians)\n", Median(iterations), 1e3 * Median(seconds));
  // Only the first row is a chi-square test proper: one independent draw of
  // 6 + 3n dof per run. The poses of one run (and its points) share the map
  // frame's error, so their sums are not chi-square with the summed dof.
  std::printf("  consistency, summed NEES / summed dof (rows 2-3: correlated within a run, indicative):\n");
  joint.Print("smoother: last pose + points");
  points.Print("smoother: each point (3 dof)");
  poses.Print("smoother: every pose (6 dof)");
  ekf_joint.Print("EKF hypotheses: last pose + points");
  std::fflush(stdout);
}

// From rendered images: the image chain (detection, JCBB, tracking, EKF with
// hypotheses) and the smoother over its associations (detections with the
// feature each measured or started, the detections' own sigmas).
void ImageAccuracy(SonarPreset preset, int seeds) {
  std::vector<double> paper, chain, smooth;
  Ratio joint, ekf_joint;
  int held_out = 0, features = 0;
  for (int s = 1; s <= seeds; ++s) {
    const SonarImageSimulation sim =
        SimulateSonarImages(SonarImagePreset(SonarPresetName(preset), static_cast<std::uint64_t>(s)));
    SonarRunOptions po;
    po.ekf.init = SonarInit::kPaper;
    paper.push_back(RunSonarSequence(sim.sequence, po).steps.back().errors->mean_feature_error);
    const SonarImageRunResult r = RunSonarImages(
        sim.sequence, [&](int k) { return sim.images[static_cast<std::size_t>(k)]; }, SonarImageRunOptions{});
    chain.push_back(r.evaluation.final_mean_error);
    const SonarStepErrors& fe = *r.run.steps.back().errors;
    ekf_joint.Add(fe.joint_nees, fe.joint_nees_dof);
    const SonarSmootherRun sm = RunSonarSmoother(sim.sequence, r.run, AssociatedMeasurements(r), {}, &r.truth_of);
    smooth.push_back(sm.errors->mean_feature_error);
    joint.Add(sm.errors->joint_nees, sm.errors->joint_nees_dof);
    for (const SonarSmoothedFeature& f : sm.result.features) held_out += !f.smoothed;
    features += static_cast<int>(sm.result.features.size());
  }
  std::printf("%s from images, %d seeds: final mean feature error, median\n", SonarPresetName(preset), seeds);
  std::printf("  EKF --init paper, given measurements %.4f m\n", Median(paper));
  std::printf("  image chain (EKF hypotheses)         %.4f m\n", Median(chain));
  std::printf(
      "  smoother over its associations       %.4f m   = %.2f x the paper's filter; %d of %d features held out\n",
      Median(smooth), Median(smooth) / Median(paper), held_out, features);
  joint.Print("smoother: last pose + points");
  ekf_joint.Print("image chain's EKF: last pose + points");
  std::fflush(stdout);
}

void Timing(int steps, int extra) {
  SonarSimulationOptions so;
  so.seed = 17;
  so.num_steps = steps;
  so.extra_features = extra;
  so.extra_box = Eigen::Vector3d(0.5, 0.6, 0.3);  // inside the fan along the whole trajectory
  const AcousticSequence seq = SimulateSonar(so);
  SonarRunOptions ro;
  ro.keep_features = false;
  const SonarRunResult ekf = RunSonarSequence(seq, ro);
  const SonarSmootherRun sm = RunSonarSmoother(seq, ekf, seq.measurements);
  const SonarSmootherResult& r = sm.result;
  std::printf(
      "T = %4d, %3zu features, %6zu measurements: EKF %8.1f ms; smoother %3d iterations, solve %8.1f ms, "
      "covariances %8.1f ms (%s); error EKF %.4f m, smoother %.4f m\n",
      steps, r.features.size(), seq.measurements.size(), 1e3 * ekf.filter_seconds, r.iterations, 1e3 * r.solve_seconds,
      1e3 * r.covariance_seconds, r.covariance_ok ? "ok" : "FAILED", ekf.steps.back().errors->mean_feature_error,
      sm.errors->mean_feature_error);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 20, extra = 0, accuracy_steps = 0;
  bool accuracy = true, timing = true, images = false;
  std::string layouts = "prism,tank,above", steps = "21,500";
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--seeds") && has_value) {
      seeds = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--layouts") && has_value) {
      layouts = argv[++i];
    } else if (!std::strcmp(argv[i], "--steps") && has_value) {
      steps = argv[++i];
    } else if (!std::strcmp(argv[i], "--accuracy-steps") && has_value) {
      accuracy_steps = std::max(0, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--extra-features") && has_value) {
      extra = std::max(0, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--no-accuracy")) {
      accuracy = false;
    } else if (!std::strcmp(argv[i], "--images")) {
      images = true;
    } else if (!std::strcmp(argv[i], "--no-timing")) {
      timing = false;
    } else {
      std::fprintf(stderr, "bench_sonar_smoother: unknown argument '%s'\n", argv[i]);
      return 2;
    }
  }
  std::string item;
  if (accuracy) {
    std::istringstream in(layouts);
    while (std::getline(in, item, ',')) Accuracy(ParseSonarPreset(item), seeds, accuracy_steps, extra);
  }
  if (images) {
    std::istringstream in(layouts);
    while (std::getline(in, item, ',')) ImageAccuracy(ParseSonarPreset(item), seeds);
  }
  if (timing) {
    std::printf("Smoother time, prism trajectory, one thread\n");
    std::istringstream in(steps);
    while (std::getline(in, item, ',')) Timing(std::max(2, std::atoi(item.c_str())), extra);
  }
  return 0;
}
