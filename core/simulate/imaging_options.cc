#include "simulate/imaging_options.h"

#include "base/error.h"

namespace hull {

void UnderwaterImagingOptions::Check() const {
  if (!(attenuation >= 0 && attenuation < 10)) throw OptionError("attenuation", "must be in [0, 10) per metre");
  if (!(backscatter >= 0 && backscatter < 1)) throw OptionError("backscatter", "must be in [0, 1)");
  if (strobes.empty()) throw OptionError("strobes", "at least one strobe lights the scene");
  for (const Strobe& s : strobes) {
    if (!(s.intensity > 0)) throw OptionError("strobes.intensity", "must be positive");
    if (!(s.axis.norm() > 0)) throw OptionError("strobes.axis", "must be a non-zero direction");
    if (!(s.half_power_angle_deg > 1 && s.half_power_angle_deg < 90)) {
      throw OptionError("strobes.half_power_angle_deg", "must be in (1, 90) degrees");
    }
  }
  if (!(exposure_level > 0 && exposure_level <= 1)) throw OptionError("exposure_level", "must be in (0, 1]");
  if (!(exposure_range > 0.1)) throw OptionError("exposure_range", "must exceed 0.1 m");
  if (!(vignetting >= 0)) throw OptionError("vignetting", "must be >= 0");
  if (!(full_well >= 100)) throw OptionError("full_well", "must be at least 100 electrons");
  if (!(read_noise >= 0)) throw OptionError("read_noise", "must be >= 0");
  if (!(max_range > exposure_range)) throw OptionError("max_range", "must exceed exposure_range");
  if (!(image_dropout >= 0 && image_dropout < 1)) throw OptionError("image_dropout", "must be in [0, 1)");
  if (png_compression < 0 || png_compression > 9) throw OptionError("png_compression", "must be in 0..9");
}

}  // namespace hull
