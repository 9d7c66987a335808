#include "mapping/mapping_options.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace hull {
namespace {

void Require(bool ok, const char* field, const std::string& why) {
  if (!ok) throw OptionError(field, why);
}

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

void MappingOptions::Check() const {
  Require(Finite(tau) && tau >= 0, "tau", "must be >= 0 m");
  Require(Finite(alpha) && alpha > 0, "alpha", "must be a positive radius (m)");
  Require(Finite(dbscan_eps) && dbscan_eps > 0, "dbscan_eps", "must be positive (m)");
  Require(dbscan_min_points >= 1, "dbscan_min_points", "must be at least 1");
  Require(Finite(shape_grow_height) && shape_grow_height >= 0, "shape_grow_height",
          "must be >= 0 m (a value >= tau turns the hysteresis off)");
  Require(Finite(fusion_radius) && fusion_radius > 0, "fusion_radius", "must be positive (m)");
  Require(fusion_support >= 1 && fusion_support <= 100, "fusion_support", "must be between 1 and 100");
  Require(Finite(fusion_peak_band) && fusion_peak_band >= 0 && fusion_peak_band <= 0.1, "fusion_peak_band",
          "must be between 0 and 0.1 m");
  Require(Finite(refine_edge) && refine_edge >= 0.005, "refine_edge", "must be at least 0.005 m");
  Require(Finite(refine_threshold) && refine_threshold >= 0, "refine_threshold", "must be >= 0 m");
  Require(Finite(refine_margin) && refine_margin >= 0 && refine_margin <= 2.0, "refine_margin",
          "must be between 0 and 2 m");
  Require(Finite(significance_k) && significance_k > 0, "significance_k", "must be positive");
  Require(Finite(object_min_height) && object_min_height > 0, "object_min_height", "must be positive (m)");
  Require(Finite(object_min_area) && object_min_area >= 0, "object_min_area", "must be >= 0 m^2");
  Require(object_min_features >= 0 && object_min_features <= 100000, "object_min_features",
          "must be between 0 and 100000 (0: the area test alone)");
  Require(object_min_views >= 1 && object_min_views <= 100000, "object_min_views", "must be between 1 and 100000");
  Require(stations >= 1 && stations <= 1000, "stations", "must be between 1 and 1000");
  Require(Finite(bottom_angle_deg) && bottom_angle_deg > 0 && bottom_angle_deg < 90, "bottom_angle_deg",
          "must be between 0 and 90 degrees (exclusive)");
  Require(Finite(inspection_spacing) && inspection_spacing >= 0.01, "inspection_spacing", "must be at least 0.01 m");
  Require(Finite(inspection_range) && inspection_range > 0, "inspection_range", "must be positive (m)");
  Require(num_threads >= 0, "num_threads", "must be >= 0 (0: all cores)");
}

}  // namespace hull
