#include "mosaic/mosaic_options.h"

#include "base/error.h"

namespace hull {

const char* MosaicNormalisationName(MosaicNormalisation n) {
  switch (n) {
    case MosaicNormalisation::kNone:
      return "none";
    case MosaicNormalisation::kModel:
      return "model";
    case MosaicNormalisation::kModelAndGains:
      return "model+gains";
  }
  return "?";
}

void MosaicOptions::Check() const {
  auto require = [](bool ok, const char* field, const char* why) {
    if (!ok) throw OptionError(field, why);
  };
  require(texel_size > 0 && texel_size < 1, "texel_size", "must be in (0, 1) m");
  require(max_edge > 0, "max_edge", "must be positive");
  require(max_range > 0, "max_range", "must be positive");
  require(max_incidence_deg > 0 && max_incidence_deg < 90, "max_incidence_deg", "must be in (0, 90) degrees");
  require(image_margin >= 0, "image_margin", "must be >= 0");
  require(seam_weight >= 0, "seam_weight", "must be >= 0");
  require(label_iterations >= 0, "label_iterations", "must be >= 0");
  require(feather_rings >= 0 && feather_rings <= 50, "feather_rings", "must be in 0..50");
  require(gain_prior_sigma > 0, "gain_prior_sigma", "must be positive");
  require(max_atlas_size >= 256 && max_atlas_size <= 65535, "max_atlas_size", "must be in 256..65535");
  require(truth_samples >= 1, "truth_samples", "must be >= 1");
  require(num_threads >= 0, "num_threads", "must be >= 0 (0: all cores)");
  require(image_cache_mb >= 0, "image_cache_mb", "must be >= 0");
  photometry.Check();
}

}  // namespace hull
