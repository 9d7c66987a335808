// Runaway detection for the adjustment (issue 14): an IterationCallback-side
// watch that ends a solve whose cost is not finite, is absurd from the start
// (values finite yet far beyond any survey's), or makes no progress over
// many iterations while still absurd; and the labels of the residual blocks
// that let the error name the likely input (the file and row whose factor
// carries the largest cost). The adjustment then throws InputError (the
// CLI's exit 3) instead of iterating on for minutes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hull {

struct CostWatchOptions {
  // An initial cost per residual beyond this ends the solve at once: the
  // whitened residuals average above 1.4e4 sigmas, which no survey whose
  // sigmas mean what they say produces.
  double max_initial_cost_per_residual = 1e8;
  // No progress: over stall_iterations iterations the cost fell by less
  // than min_progress (relative) while its cost per residual is still above
  // max_stalled_cost_per_residual (an average error above 140 sigmas); a
  // sane survey that converges slowly is never stopped.
  int stall_iterations = 10;
  double min_progress = 1e-3;
  double max_stalled_cost_per_residual = 1e4;

  void Check() const;  // throws OptionError naming the field
};

class CostWatch {
 public:
  CostWatch(const CostWatchOptions& options, std::size_t num_residuals);
  // Called with each iteration's cost (iteration 0 first); returns "" to
  // continue, else why the solve must stop (a plain sentence).
  std::string Observe(int iteration, double cost);
  // Starts over (a new solve of the same problem, e.g. after outlier rejection).
  void Reset() { costs_.clear(); }

 private:
  CostWatchOptions o_;
  double residuals_;
  std::vector<double> costs_;
};

// What a residual block measures, to name the input behind a large cost.
struct ResidualLabel {
  enum Kind : std::uint8_t {
    kGauge,         // a: keyframe (nav.csv, first row)
    kZpr,           // a: keyframe (nav.csv depth, roll_meas, pitch_meas)
    kServo,         // a: keyframe (nav.csv servo)
    kExtrinsic,     // survey.json camera.servo_to_top
    kModelPose,     // the model pose prior (the alignment or model_pose_guess)
    kOdometry,      // a -> b (odometry.csv)
    kReprojection,  // a: landmark, b: keyframe (features.csv)
    kDvl,           // a: keyframe, b: beam 1..4 (dvl.csv)
    kSurface,       // a: landmark (features.csv against the mesh)
  };
  Kind kind = kGauge;
  std::int64_t a = 0, b = 0;
  // "the odometry 12 -> 13 (odometry.csv)", ...
  std::string Describe() const;
};

}  // namespace hull
