#include "sonar/sonar_consistency.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "sonar/sonar_association.h"

namespace hull {

SonarConsistency CheckSonarConsistency(const SonarRunResult& run, int window) {
  SonarConsistency c;
  c.window = window;
  std::vector<std::pair<double, int>> updates;  // per step with an update: NIS, dof
  for (const SonarStepRecord& s : run.steps) {
    if (s.estimate.nis_dof <= 0 || !std::isfinite(s.estimate.nis)) continue;
    updates.emplace_back(s.estimate.nis, s.estimate.nis_dof);
    c.nis += s.estimate.nis;
    c.dof += s.estimate.nis_dof;
  }
  if (c.dof == 0) return c;
  c.known = true;
  c.low = ChiSquareQuantile(0.025, c.dof);
  c.high = ChiSquareQuantile(0.975, c.dof);
  for (std::size_t i = 0; window > 0 && i + static_cast<std::size_t>(window) <= updates.size(); ++i) {
    double nis = 0;
    int dof = 0;
    for (std::size_t j = i; j < i + static_cast<std::size_t>(window); ++j)
      nis += updates[j].first, dof += updates[j].second;
    ++c.windows;
    c.windows_high += nis > ChiSquareQuantile(0.99, dof);
  }
  const bool sum_high = c.nis > ChiSquareQuantile(0.999, c.dof) && c.ratio() > SonarConsistency::kMaterialRatio;
  c.inconsistent = sum_high || (c.windows > 0 && 4 * c.windows_high > c.windows);
  c.conservative = !c.inconsistent && c.nis < c.low;
  return c;
}

std::string SonarConsistency::Verdict() const {
  if (!known) return "not known (no update used a measurement)";
  char text[400];
  if (inconsistent) {
    std::snprintf(text, sizeof text,
                  "INCONSISTENT: the innovations are %.1f times larger than their covariance says (NIS %.2f per "
                  "degree of freedom over %d; %d of %d windows of %d steps above their 99 %% bound): the features' "
                  "sigma understate their error about %.1f times and must not be trusted",
                  std::sqrt(ratio()), ratio(), dof, windows_high, windows, window, std::sqrt(ratio()));
  } else if (conservative) {
    std::snprintf(text, sizeof text,
                  "consistent, conservative (NIS %.2f per degree of freedom over %d, below its 95 %% interval: the "
                  "covariance claims less accuracy than the run has)",
                  ratio(), dof);
  } else {
    std::snprintf(text, sizeof text, "consistent (NIS %.2f per degree of freedom over %d; %d of %d windows high)",
                  ratio(), dof, windows_high, windows);
  }
  return text;
}

}  // namespace hull
