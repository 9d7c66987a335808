#include <string>

#include "base/error.h"
#include "sonar/sonar_ekf_types.h"

namespace hull {

const char* SonarInitName(SonarInit init) { return init == SonarInit::kPaper ? "paper" : "hypotheses"; }

SonarInit ParseSonarInit(const std::string& name) {
  if (name == "paper") return SonarInit::kPaper;
  if (name == "hypotheses") return SonarInit::kHypotheses;
  throw OptionError("init", "unknown initialisation '" + name + "'; expected 'paper' or 'hypotheses'");
}

bool SonarEkfOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& field, const std::string& reason) {
    if (why) *why = field + ": " + reason;
    return false;
  };
  if (!(paper_elevation_sigma_fraction > 0 && paper_elevation_sigma_fraction <= 1)) {
    return fail("paper_elevation_sigma_fraction", "must be in (0, 1]");
  }
  if (hypotheses < 3 || hypotheses > 1000) return fail("hypotheses", "must be between 3 and 1000");
  if (!(collapse_probability > 0.5 && collapse_probability < 1)) {
    return fail("collapse_probability", "must be in (0.5, 1)");
  }
  if (min_extra_views < 1) return fail("min_extra_views", "must be at least 1 (a second view)");
  if (max_delay_steps < 1) return fail("max_delay_steps", "must be at least 1");
  if (!(prune_ratio >= 0 && prune_ratio < 1)) return fail("prune_ratio", "must be in [0, 1)");
  if (confirm_views < 1 || confirm_views > 1000) return fail("confirm_views", "must be between 1 and 1000");
  if (update_block < 1) return fail("update_block", "must be at least 1");
  return true;
}

}  // namespace hull
