// Private to the initial model alignment (core/registration/model_alignment*.cc):
// the hull frame, sampling and scoring helpers, the GICP refinement with its
// degeneracy guard, point-to-plane ICP, and the coarse search.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "registration/model_alignment.h"

namespace hull::alignment_internal {

constexpr double kDeg = M_PI / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The alignment's wall-time budget (ModelAlignmentOptions::max_seconds),
// checked between the steps of every stage.
class Deadline {
 public:
  explicit Deadline(double seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  // Throws std::runtime_error naming `stage` and the budget when it is spent.
  void ThrowIfSpent(const std::string& stage) const;

 private:
  double seconds_;  // <= 0: no budget
  std::chrono::steady_clock::time_point start_;
};

// Hull axes in M, orthonormalised: forward f, up u and port p = u x f.
struct HullFrame {
  Eigen::Vector3d f, u, p;
};

struct Refined {
  Pose x_gM;
  GicpResult gicp;
  std::size_t target_points = 0;
  Vector6d observability = Vector6d::Zero();
  int constrained_directions = 0;
};

HullFrame HullFrameOf(const SurveyManifest& m);

Eigen::Matrix3d UprightRotation(const HullFrame& h, double psi);

double HeadingOf(const HullFrame& h, const Pose& x_gM);

double AngleDiff(double a, double b);

Eigen::Vector3d Centroid(const std::vector<Eigen::Vector3d>& pts);

std::vector<Eigen::Vector3d> SampleNear(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& near_M,
                                        double spacing, double margin, const Deadline& deadline);

std::vector<Eigen::Vector3d> ToModel(const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM);

double TruncatedSurfaceRms(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM,
                           double truncation);

double TruncatedSurfaceRmsParallel(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM,
                                   double truncation);

void ConstrainUpdate(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM0,
                     double min_observability, double truncation, Refined* r);

Refined Refine(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM0,
               const ModelAlignmentOptions& o, const Deadline& deadline);

Pose PointToPlaneIcp(const MeshIndex& index, const std::vector<Eigen::Vector3d>& pts_g, const Pose& x_gM,
                     int iterations, double truncation);

struct CoarseResult {
  Pose start;      // the winning placement before any refinement
  Pose candidate;  // after the coarse search's own refinement (the final GICP starts here)
};

// The coarse search (see CoarseSearchReport and ModelAlignmentOptions).
CoarseResult CoarseSearch(const SurveyBundle& bundle, const TriangleMesh& mesh, const MeshIndex& index,
                          const std::vector<DvlPoint>& returns, const std::vector<Eigen::Vector3d>& pts_g,
                          const ModelAlignmentOptions& o, Progress& progress, const Deadline& deadline,
                          CoarseSearchReport* report);

}  // namespace hull::alignment_internal
