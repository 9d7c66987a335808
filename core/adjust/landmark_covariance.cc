#include "adjust/landmark_covariance.h"

#include <ceres/ceres.h>
#include <malloc.h>
#include <suitesparse/SuiteSparse_config.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>
#include <mutex>

#include "adjust/landmark_covariance_schur.h"
#include "adjust/landmark_jacobians.h"
#include "base/error.h"

namespace hull {
namespace {

using Clock = std::chrono::steady_clock;

// SuiteSparse's allocations on 64-byte boundaries. The dense kernels under
// SuiteSparseQR (BLAS and LAPACK, ATLAS on a stock Debian 12) pick their code
// path by the alignment of the frontal matrices, so the covariances' last
// digits followed wherever malloc happened to place them, which varies from
// run to run with the other threads' allocations (measured on the demo
// preset, one thread: 2 of 11 runs differed in sigma_h by up to 5e-16; with
// aligned allocations, or with the reference BLAS, none of 8).
constexpr std::size_t kAlign = 64;

void* AlignedMalloc(std::size_t n) {
  const std::size_t rounded = (std::max<std::size_t>(n, 1) + kAlign - 1) / kAlign * kAlign;
  return rounded < n ? nullptr : std::aligned_alloc(kAlign, rounded);
}
void* AlignedCalloc(std::size_t count, std::size_t size) {
  if (size != 0 && count > std::numeric_limits<std::size_t>::max() / size) return nullptr;
  void* p = AlignedMalloc(count * size);
  if (p) std::memset(p, 0, count * size);
  return p;
}
void* AlignedRealloc(void* old, std::size_t n) {
  if (!old) return AlignedMalloc(n);
  void* p = AlignedMalloc(n);
  if (!p) return nullptr;  // SuiteSparse keeps the old block, as with realloc
  std::memcpy(p, old, std::min(malloc_usable_size(old), n));
  std::free(old);
  return p;
}

// Installs the aligned allocator once per process (blocks SuiteSparse
// allocated before are still freed by free()).
void AlignSuiteSparseAllocations() {
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = AlignedMalloc;
    SuiteSparse_config.calloc_func = AlignedCalloc;
    SuiteSparse_config.realloc_func = AlignedRealloc;
    SuiteSparse_config.free_func = std::free;
  });
}

const Eigen::Matrix3d kUnknown = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());

// (J_l^T J_l)^-1 over the residual blocks of one landmark, other blocks fixed.
Eigen::Matrix3d Conditional(const ceres::Problem& problem, double* block) {
  Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
  adjust::ForEachLandmarkJacobian(
      problem, block, [&](ceres::ResidualBlockId, const adjust::LandmarkJacobian& J) { info += J.transpose() * J; });
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(info);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) return kUnknown;
  const Eigen::Matrix3d c = ldlt.solve(Eigen::Matrix3d::Identity());
  return 0.5 * (c + c.transpose());
}

using RowMajor = adjust::RowMajorMatrix;

// sigma_h from the joint covariance of [model, landmark] (ll, lm: 3 x tm, mm:
// tm x tm, tangent space) and the surface residual's Jacobian, normalised so
// that dh/dl is unit; NaN when it cannot be formed.
double JointSigma(const ceres::Problem& problem, double* model, double* block, ceres::ResidualBlockId surface,
                  const Eigen::Matrix3d& ll, const RowMajor& lm, const RowMajor& mm) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const int tm = problem.ParameterBlockTangentSize(model);
  if (!surface || lm.rows() != 3 || lm.cols() != tm || mm.rows() != tm || mm.cols() != tm) return kNaN;
  std::vector<double*> params;
  problem.GetParameterBlocksForResidualBlock(surface, &params);
  if (params.size() != 2 || params[0] != model || params[1] != block) return kNaN;
  // h is the first residual (scaled by 1 / sigma of the chosen label).
  const int nr = problem.GetCostFunctionForResidualBlock(surface)->num_residuals();
  RowMajor jm(nr, tm), jl(nr, 3);
  std::vector<double> residuals(static_cast<std::size_t>(nr));
  double* jacobians[2] = {jm.data(), jl.data()};
  double cost = 0;
  if (!problem.EvaluateResidualBlock(surface, false, &cost, residuals.data(), jacobians)) return kNaN;
  const double scale = jl.row(0).norm();
  if (!(scale > 0)) return kNaN;
  const Eigen::RowVector3d gl = jl.row(0) / scale;
  const Eigen::RowVectorXd gm = jm.row(0) / scale;
  const double v = gl * ll * gl.transpose() + 2.0 * (gl * lm * gm.transpose())(0, 0) + (gm * mm * gm.transpose())(0, 0);
  return v >= 0 ? std::sqrt(v) : kNaN;
}

// kFullSparseQr: Ceres' Covariance. False when it fails (rank deficiency).
bool SparseQrCovariances(ceres::Problem& problem, const std::vector<double*>& blocks, bool joint, double* model,
                         const std::vector<ceres::ResidualBlockId>* surface, int num_threads,
                         LandmarkCovariances& out) {
  AlignSuiteSparseAllocations();
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::SPARSE_QR;
  co.num_threads = num_threads;
  co.apply_loss_function = true;
  ceres::Covariance covariance(co);
  std::vector<std::pair<const double*, const double*>> pairs;
  pairs.reserve(blocks.size());
  for (double* b : blocks) pairs.emplace_back(b, b);
  if (joint) {
    pairs.emplace_back(model, model);
    for (double* b : blocks) pairs.emplace_back(b, model);
  }
  if (!covariance.Compute(pairs, &problem)) return false;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c;
    if (covariance.GetCovarianceBlock(blocks[i], blocks[i], c.data())) out.covariance[i] = 0.5 * (c + c.transpose());
  }
  if (!joint) return true;
  const int tm = problem.ParameterBlockTangentSize(model);
  RowMajor mm(tm, tm), lm(3, tm);
  if (!covariance.GetCovarianceBlockInTangentSpace(model, model, mm.data())) return true;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!(*surface)[i] || !covariance.GetCovarianceBlockInTangentSpace(blocks[i], model, lm.data())) continue;
    out.sigma_h[i] = JointSigma(problem, model, blocks[i], (*surface)[i], out.covariance[i], lm, mm);
  }
  return true;
}

// kFull: the Schur complement (landmark_covariance_schur.h). False (with
// *why) when it fails.
bool SchurCovariances(ceres::Problem& problem, const std::vector<double*>& blocks, bool joint, double* model,
                      const std::vector<ceres::ResidualBlockId>* surface, int num_threads, LandmarkCovariances& out,
                      std::string* why) {
  adjust::SchurCovariances s;
  if (!adjust::ComputeSchurCovariances(problem, blocks, joint ? model : nullptr, num_threads, &s, why)) return false;
  for (std::size_t i = 0; i < blocks.size(); ++i) out.covariance[i] = s.ll[i];
  out.reduced_size = s.reduced_size;
  out.factor_nonzeros = s.factor_nonzeros;
  if (!joint) return true;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    out.sigma_h[i] = JointSigma(problem, model, blocks[i], (*surface)[i], out.covariance[i], s.lm[i], s.mm);
  }
  return true;
}

}  // namespace

const char* CovarianceMethodName(CovarianceMethod m) {
  switch (m) {
    case CovarianceMethod::kNone:
      return "none";
    case CovarianceMethod::kConditional:
      return "conditional";
    case CovarianceMethod::kFull:
      return "full";
    case CovarianceMethod::kFullSparseQr:
      return "full-qr";
  }
  return "?";
}

CovarianceMethod ParseCovarianceMethod(const std::string& name) {
  if (name == "none") return CovarianceMethod::kNone;
  if (name == "conditional") return CovarianceMethod::kConditional;
  if (name == "full") return CovarianceMethod::kFull;
  if (name == "full-qr") return CovarianceMethod::kFullSparseQr;
  throw OptionError("covariance", "expected none, conditional, full or full-qr, got '" + name + "'");
}

LandmarkCovariances ComputeLandmarkCovariances(ceres::Problem& problem, const std::vector<double*>& blocks,
                                               CovarianceMethod method, int num_threads, double* model_block,
                                               const std::vector<ceres::ResidualBlockId>* surface) {
  const auto t0 = Clock::now();
  const std::clock_t c0 = std::clock();
  LandmarkCovariances out;
  out.covariance.assign(blocks.size(), kUnknown);
  out.sigma_h.assign(blocks.size(), std::numeric_limits<double>::quiet_NaN());
  out.method = method;
  const bool joint = model_block && surface && surface->size() == blocks.size() &&
                     problem.HasParameterBlock(model_block) && !problem.IsParameterBlockConstant(model_block);
  if (method == CovarianceMethod::kFull && !blocks.empty()) {
    std::string why;
    if (!SchurCovariances(problem, blocks, joint, model_block, surface, num_threads, out, &why)) {
      std::fill(out.covariance.begin(), out.covariance.end(), kUnknown);
      std::fill(out.sigma_h.begin(), out.sigma_h.end(), std::numeric_limits<double>::quiet_NaN());
      out.method = CovarianceMethod::kConditional;
      out.note = "the full covariance failed (" + why + "); landmark-conditional covariances instead";
    }
  } else if (method == CovarianceMethod::kFullSparseQr && !blocks.empty()) {
    if (!SparseQrCovariances(problem, blocks, joint, model_block, surface, num_threads, out)) {
      out.method = CovarianceMethod::kConditional;
      out.note = "the full covariance failed (rank-deficient Jacobian); landmark-conditional covariances instead";
    }
  }
  if (out.method == CovarianceMethod::kConditional) {
    for (std::size_t i = 0; i < blocks.size(); ++i) out.covariance[i] = Conditional(problem, blocks[i]);
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  out.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  return out;
}

double DeviationSigma(const Eigen::Matrix3d& covariance, const Eigen::Vector3d& normal) {
  const double v = normal.dot(covariance * normal);
  return v >= 0 ? std::sqrt(v) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hull
