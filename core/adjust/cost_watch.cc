#include "adjust/cost_watch.h"

#include <cmath>
#include <cstdio>

#include "base/error.h"

namespace hull {
namespace {

std::string G(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g", v);
  return buf;
}

}  // namespace

void CostWatchOptions::Check() const {
  if (!(max_initial_cost_per_residual > 0)) throw OptionError("max_initial_cost_per_residual", "must be > 0");
  if (stall_iterations < 1) throw OptionError("stall_iterations", "must be >= 1");
  if (!(min_progress >= 0 && min_progress < 1)) throw OptionError("min_progress", "must be in [0, 1)");
  if (!(max_stalled_cost_per_residual > 0)) throw OptionError("max_stalled_cost_per_residual", "must be > 0");
}

CostWatch::CostWatch(const CostWatchOptions& options, std::size_t num_residuals)
    : o_(options), residuals_(num_residuals > 0 ? static_cast<double>(num_residuals) : 1.0) {
  o_.Check();
}

std::string CostWatch::Observe(int iteration, double cost) {
  if (!std::isfinite(cost)) return "the cost became " + G(cost) + " at iteration " + std::to_string(iteration);
  const double per = cost / residuals_;
  // The average whitened error: cost = 0.5 sum r^2.
  const std::string sigmas = G(std::sqrt(2 * per)) + " sigmas";
  if (costs_.empty() && per > o_.max_initial_cost_per_residual) {
    costs_.push_back(cost);
    return "the initial cost " + G(cost) + " (" + G(per) + " per residual, an average error of " + sigmas +
           ") is beyond any survey's: some input is far from consistent with the rest";
  }
  costs_.push_back(cost);
  const std::size_t n = costs_.size();
  const auto window = static_cast<std::size_t>(o_.stall_iterations);
  if (n > window && per > o_.max_stalled_cost_per_residual) {
    const double then = costs_[n - 1 - window];
    if (then - cost < o_.min_progress * then) {
      return "no progress over " + std::to_string(o_.stall_iterations) + " iterations (cost " + G(then) + " -> " +
             G(cost) + ") while the cost is still " + G(per) + " per residual (an average error of " + sigmas + ")";
    }
  }
  return "";
}

std::string ResidualLabel::Describe() const {
  const std::string A = std::to_string(a), B = std::to_string(b);
  switch (kind) {
    case kGauge:
      return "the gauge prior on keyframe " + A + " (nav.csv, the first pose)";
    case kZpr:
      return "the depth, roll and pitch of keyframe " + A + " (nav.csv: depth, roll_meas, pitch_meas against x, y, z)";
    case kServo:
      return "the servo angle of keyframe " + A + " (nav.csv: servo)";
    case kExtrinsic:
      return "the camera extrinsic prior (survey.json: camera.servo_to_top and noise.servo_to_top_sigma)";
    case kModelPose:
      return "the model pose prior (the alignment or survey.json: model_pose_guess, noise.model_pose_sigma)";
    case kOdometry:
      return "the odometry " + A + " -> " + B + " (odometry.csv against nav.csv)";
    case kReprojection:
      return "the reprojection of landmark " + A + " in keyframe " + B + " (features.csv and the camera intrinsics)";
    case kDvl:
      return "DVL beam " + B + " of keyframe " + A + " (dvl.csv against the mesh)";
    case kSurface:
      return "the surface constraint of landmark " + A + " (features.csv against the mesh)";
  }
  return "a residual";
}

}  // namespace hull
