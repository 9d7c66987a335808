// The photomosaic's options (photomosaic.h builds it). Plain data, so the
// GUI's parameter table and the project reader use it without OpenCV.
#pragma once

#include "simulate/imaging_options.h"

namespace hull {

enum class MosaicNormalisation {
  kNone,           // raw pixel values (texel = image value)
  kModel,          // albedo from the photometric model
  kModelAndGains,  // ... times a per-image gain from the overlaps (default)
};
const char* MosaicNormalisationName(MosaicNormalisation n);

struct MosaicOptions {
  double texel_size = 0.004;      // m per atlas texel
  double max_edge = 0.2;          // m: longer edges near the cameras are split (a face must fit in one image)
  double max_range = 5.0;         // m: farther views are no candidates
  double max_incidence_deg = 75;  // views seeing a face more obliquely are no candidates
  double image_margin = 2;        // px: corners must lie this far inside the image
  double seam_weight = 0.5;       // Potts weight of a seam edge against -ln(score ratio)
  int label_iterations = 10;      // sweeps of iterated conditional modes (0: best view per face)
  int feather_rings = 2;          // smoothing steps of the per-vertex view weights (0: hard seams)
  MosaicNormalisation normalisation = MosaicNormalisation::kModelAndGains;
  UnderwaterImagingOptions photometry;  // the rig's strobes, water and vignetting (the renderer's model)
  double gain_prior_sigma = 0.2;        // sigma of ln(gain) around 0 (trust in the model's absolute level)
  int max_atlas_size = 16384;           // px: the texel size grows until the atlas fits
  int truth_samples = 16;               // texels per face scored against the true albedo
  int image_cache_mb = 4096;            // decoded images kept between the gain and texturing passes
  int num_threads = 0;                  // 0: all cores

  void Check() const;  // throws OptionError naming the field
};

}  // namespace hull
