// The landmark blocks of the inverse information matrix by the Schur
// complement (landmark_covariance.h, CovarianceMethod::kFull).
//
// With H = J^T J (J from the residual blocks at the solution, robust losses
// applied, in the tangent spaces; held parameter blocks are not variables)
// split into the landmarks l (3 x 3 diagonal blocks H_ll) and the rest c
// (poses, servo angles, extrinsic, model pose):
//   S     = H_cc - H_cl H_ll^-1 H_lc          (the reduced camera system)
//   Sig_cc = S^-1, only on the pattern of S's sparse LDL^T factor
//            (Takahashi's recursion: the selected inverse)
//   Sig_lc = -G Sig_cc,  G = H_ll^-1 H_lc
//   Sig_ll = H_ll^-1 + G Sig_cc G^T
// Each landmark needs Sig_cc only on the blocks of the parameters it
// touches, all within S's pattern, so no dense inverse is formed.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace ceres {
class Problem;
}

namespace hull::adjust {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A sparse symmetric positive definite matrix (lower triangle, compressed
// columns, rows sorted), its LDL^T factor in the given order and the entries
// of its inverse on the factor's pattern.
class SelectedInverse {
 public:
  // lower: n x n, column-major; entries above the diagonal are ignored.
  // Returns false (with *why) when the matrix is not numerically positive
  // definite (a pivot <= 1e-13 x its diagonal entry).
  bool Compute(const Eigen::SparseMatrix<double>& lower, std::string* why);
  // (A^-1)(r, c); false when (r, c) is not on the factor's pattern.
  bool Get(int r, int c, double* value) const;
  // (A^-1)(r0 .. r0+nr-1, c) for rows on the pattern (contiguous there);
  // false otherwise.
  bool GetColumnRun(int r0, int nr, int c, double* out) const;
  int size() const { return static_cast<int>(diag_.size()); }
  std::size_t factor_nonzeros() const { return row_.size(); }

 private:
  std::vector<int> col_;       // n + 1
  std::vector<int> row_;       // strictly lower pattern of L, sorted per column
  std::vector<double> value_;  // inverse entries on that pattern
  std::vector<double> diag_;   // inverse diagonal
};

struct SchurCovariances {
  std::vector<Eigen::Matrix3d> ll;  // per landmark block
  std::vector<RowMajorMatrix> lm;   // per landmark block, 3 x tm (empty where the landmark does not touch the model)
  RowMajorMatrix mm;                // tm x tm (empty without a model block)
  std::size_t reduced_size = 0;     // columns of S
  std::size_t factor_nonzeros = 0;  // strictly lower entries of its factor
};

// blocks: the landmark parameter blocks (3 doubles each, not held); model:
// the model pose block (not held) or null. Returns false with *why when the
// information matrix is singular or the problem does not have the structure
// the Schur complement needs (a residual block on two landmarks). The result
// does not depend on num_threads.
bool ComputeSchurCovariances(ceres::Problem& problem, const std::vector<double*>& blocks, double* model,
                             int num_threads, SchurCovariances* out, std::string* why);

}  // namespace hull::adjust
