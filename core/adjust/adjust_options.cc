#include "adjust/adjust_options.h"

#include <cmath>

#include "base/error.h"

namespace hull {

const char* SurfaceModelName(SurfaceModel m) {
  switch (m) {
    case SurfaceModel::kNaive:
      return "naive";
    case SurfaceModel::kAllOnSurface:
      return "all-on-surface";
    case SurfaceModel::kMaxMixture:
      return "max-mixture";
  }
  return "?";
}

SurfaceModel ParseSurfaceModel(const std::string& name) {
  if (name == "naive") return SurfaceModel::kNaive;
  if (name == "all-on-surface") return SurfaceModel::kAllOnSurface;
  if (name == "max-mixture") return SurfaceModel::kMaxMixture;
  throw OptionError("model", "unknown surface model '" + name + "' (naive, all-on-surface or max-mixture)");
}

const char* LabelRuleName(LabelRule r) {
  switch (r) {
    case LabelRule::kEstimate:
      return "estimate";
    case LabelRule::kCavity:
      return "cavity";
  }
  return "?";
}

LabelRule ParseLabelRule(const std::string& name) {
  if (name == "estimate") return LabelRule::kEstimate;
  if (name == "cavity") return LabelRule::kCavity;
  throw OptionError("labels", "unknown label rule '" + name + "' (estimate or cavity)");
}

void AdjustmentOptions::Check() const {
  if (!(sigma1 > 0)) throw OptionError("sigma1", "must be positive");
  if (!(sigma0 > sigma1)) throw OptionError("sigma0", "must be larger than sigma1");
  if (!(huber_sigmas > 0)) throw OptionError("huber_sigmas", "must be positive");
  const struct {
    const char* name;
    double value;
  } overrides[] = {{"pixel_sigma", pixel_sigma}, {"dvl_range_sigma", dvl_range_sigma},
                   {"depth_sigma", depth_sigma}, {"roll_pitch_sigma", roll_pitch_sigma},
                   {"servo_sigma", servo_sigma}, {"model_pose_sigma", model_pose_sigma}};
  for (const auto& o : overrides) {
    if (!(o.value >= 0) || !std::isfinite(o.value)) {
      throw OptionError(o.name, "must be positive, or 0 for the survey's value");
    }
  }
  if (!(gauge_sigma_xy > 0 && gauge_sigma_yaw > 0)) throw OptionError("gauge_sigma", "must be positive");
  if (!(outlier_sigmas > 0)) throw OptionError("outlier_sigmas", "must be positive");
  if (rejection_rounds < 0) throw OptionError("rejection_rounds", "must be >= 0");
  if (label_rounds < 0) throw OptionError("label_rounds", "must be >= 0");
  if (min_observations < 1) throw OptionError("min_observations", "must be at least 1");
  if (!(max_initial_deviation >= 0) || !std::isfinite(max_initial_deviation)) {
    throw OptionError("max_initial_deviation", "must be >= 0 (0: no limit)");
  }
  if (!(max_solver_seconds >= 0)) throw OptionError("max_solver_seconds", "must be >= 0 (0: no limit)");
  watch.Check();
  if (max_iterations < 1) throw OptionError("max_iterations", "must be at least 1");
  if (!(function_tolerance > 0 && gradient_tolerance > 0 && parameter_tolerance > 0)) {
    throw OptionError("tolerances", "must be positive");
  }
  if (num_threads < 0) throw OptionError("num_threads", "must be >= 0 (0: all cores)");
}

double AdjustmentOptions::DecisionBoundary() const {
  return std::sqrt(2.0 * std::log(sigma0 / sigma1) / (1.0 / (sigma1 * sigma1) - 1.0 / (sigma0 * sigma0)));
}

}  // namespace hull
