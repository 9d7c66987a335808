// Does the filter's uncertainty match what it saw? The normalised
// innovations squared of the EKF's updates (NIS: each step's innovations
// weighed by their predicted covariance, chi-square with 2 degrees of
// freedom per measurement used when the filter is consistent) need no
// truth, so they hold on real data (Bar-Shalom, Li and Kirubarajan,
// "Estimation with Applications to Tracking and Navigation", 5.4). Checked
// over the whole run and over windows of a few steps: a run whose
// innovations are materially larger than their covariance says -- its
// features' sigma then claim an accuracy the run does not have -- is called
// inconsistent, in the CLI's output, summary.json, the GUI and the report.
#pragma once

#include <string>

#include "sonar/sonar_runner.h"

namespace hull {

struct SonarConsistency {
  // Summed over every step with an update.
  double nis = 0;
  int dof = 0;
  double low = 0, high = 0;  // its two-sided 95 % chi-square interval
  // Windows of `window` consecutive steps with updates, and those whose
  // summed NIS lies above its 99 % quantile.
  int window = 0;
  int windows = 0, windows_high = 0;
  // Over-confident: the summed NIS above its 99.9 % quantile and more than
  // kMaterialRatio per degree of freedom (a mismatch that matters, not the
  // last digit of a very long run), or more than a quarter of the windows
  // high. False without any update (then `known` is false too).
  bool inconsistent = false;
  bool conservative = false;  // below the interval: the covariance claims less than the run does
  bool known = false;
  static constexpr double kMaterialRatio = 1.5;

  double ratio() const { return dof > 0 ? nis / dof : 0; }
  // One sentence for the user: "consistent (NIS 0.31 per degree of freedom
  // over 192)" or "INCONSISTENT: the innovations are 2.6 times ...".
  std::string Verdict() const;
};

SonarConsistency CheckSonarConsistency(const SonarRunResult& run, int window = 5);

}  // namespace hull
