#include "adjust/landmark_covariance_schur.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cstdint>
#include <thread>
#include <unordered_map>

namespace hull::adjust {

// ---- the selected inverse -------------------------------------------------------------

bool SelectedInverse::Compute(const Eigen::SparseMatrix<double>& lower, std::string* why) {
  const int n = static_cast<int>(lower.cols());
  // Natural order: the caller has ordered the matrix to keep the fill small.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(lower);
  if (ldlt.info() != Eigen::Success) {
    *why = "the reduced system is singular (its LDL^T factorization failed)";
    return false;
  }
  const Eigen::VectorXd d = ldlt.vectorD();
  const Eigen::VectorXd a = lower.diagonal();
  for (int j = 0; j < n; ++j) {
    if (!(d[j] > 1e-13 * a[j])) {
      *why = "the reduced system is singular (pivot " + std::to_string(j) + " of " + std::to_string(n) + ")";
      return false;
    }
  }
  // The factor's pattern (strictly lower; Eigen's LDL^T keeps no diagonal).
  const Eigen::SparseMatrix<double>& L = ldlt.matrixL().nestedExpression();
  col_.assign(static_cast<std::size_t>(n) + 1, 0);
  row_.clear();
  std::vector<double> l;
  for (int j = 0; j < n; ++j) {
    int previous = j;
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it) {
      if (it.row() <= previous) {
        *why = "the factor's pattern is not strictly lower and sorted";
        return false;
      }
      previous = static_cast<int>(it.row());
      row_.push_back(static_cast<int>(it.row()));
      l.push_back(it.value());
    }
    col_[static_cast<std::size_t>(j) + 1] = static_cast<int>(row_.size());
  }
  // Takahashi's recursion, last column first: with I the rows of L(:, j),
  //   Z(I, j) = -Z(I, I) L(I, j),   Z(j, j) = 1 / d_j - L(I, j)^T Z(I, j),
  // where Z(I, I) lies on the pattern (the rows of a column form a clique of
  // the filled graph: {i in I, i > k} is within the rows of L(:, k)).
  value_.assign(row_.size(), 0.0);
  diag_.assign(static_cast<std::size_t>(n), 0.0);
  std::vector<int> where(static_cast<std::size_t>(n), -1);
  std::vector<double> z;
  for (int j = n - 1; j >= 0; --j) {
    const int p0 = col_[static_cast<std::size_t>(j)], p1 = col_[static_cast<std::size_t>(j) + 1];
    z.assign(static_cast<std::size_t>(p1 - p0), 0.0);
    for (int p = p0; p < p1; ++p) where[static_cast<std::size_t>(row_[static_cast<std::size_t>(p)])] = p - p0;
    for (int p = p0; p < p1; ++p) {
      const int k = row_[static_cast<std::size_t>(p)];
      const double lk = l[static_cast<std::size_t>(p)];
      double& zk = z[static_cast<std::size_t>(p - p0)];
      zk -= diag_[static_cast<std::size_t>(k)] * lk;
      for (int q = col_[static_cast<std::size_t>(k)]; q < col_[static_cast<std::size_t>(k) + 1]; ++q) {
        const int w = where[static_cast<std::size_t>(row_[static_cast<std::size_t>(q)])];
        if (w < 0) continue;
        const double zik = value_[static_cast<std::size_t>(q)];
        z[static_cast<std::size_t>(w)] -= zik * lk;                                 // Z(i, k) L(k, j) into Z(i, j)
        zk -= zik * l[static_cast<std::size_t>(p0) + static_cast<std::size_t>(w)];  // Z(k, i) L(i, j) into Z(k, j)
      }
    }
    double djj = 1.0 / d[j];
    for (int p = p0; p < p1; ++p) {
      djj -= l[static_cast<std::size_t>(p)] * z[static_cast<std::size_t>(p - p0)];
      value_[static_cast<std::size_t>(p)] = z[static_cast<std::size_t>(p - p0)];
      where[static_cast<std::size_t>(row_[static_cast<std::size_t>(p)])] = -1;
    }
    diag_[static_cast<std::size_t>(j)] = djj;
  }
  return true;
}

bool SelectedInverse::Get(int r, int c, double* value) const {
  if (r == c) {
    *value = diag_[static_cast<std::size_t>(r)];
    return true;
  }
  return GetColumnRun(std::max(r, c), 1, std::min(r, c), value);
}

bool SelectedInverse::GetColumnRun(int r0, int nr, int c, double* out) const {
  const auto begin = row_.begin() + col_[static_cast<std::size_t>(c)];
  const auto end = row_.begin() + col_[static_cast<std::size_t>(c) + 1];
  auto it = std::lower_bound(begin, end, r0);
  if (end - it < nr) return false;
  for (int i = 0; i < nr; ++i) {
    if (it[i] != r0 + i) return false;
    out[i] = value_[static_cast<std::size_t>(it - row_.begin()) + static_cast<std::size_t>(i)];
  }
  return true;
}

namespace {

// A parameter block of the reduced system (a pose, a servo angle, the
// extrinsic, the model pose): its tangent size and, once ordered, its first
// column in S.
struct ReducedBlock {
  double* values;
  int size;
  int column = 0;
};

// A landmark's part of H: H_ll, H_lc and the J_c^T J_c of its residual
// blocks, over the reduced blocks it touches (ascending).
struct LandmarkPart {
  std::vector<int> blocks;   // reduced block indices
  std::vector<int> offsets;  // their first local column; back() = total
  Eigen::Matrix3d hll_inverse;
  RowMajorMatrix g;  // H_ll^-1 H_lc, 3 x total
};

// The sum over the residual blocks of J_a^T J_b per pair of reduced blocks
// (a >= b), added in a fixed order whatever the threads.
class ReducedSystem {
 public:
  explicit ReducedSystem(const std::vector<ReducedBlock>& blocks) : blocks_(blocks) {}
  // Adds m(rows of a, columns of b) (row-major, leading dimension ld).
  void Add(int a, int b, const double* m, int ld) {
    const bool swap = a < b;
    const int ra = swap ? b : a, cb = swap ? a : b;
    const int nr = blocks_[static_cast<std::size_t>(ra)].size, nc = blocks_[static_cast<std::size_t>(cb)].size;
    const std::uint64_t key = (static_cast<std::uint64_t>(ra) << 32) | static_cast<std::uint32_t>(cb);
    auto [it, inserted] = index_.emplace(key, pairs_.size());
    if (inserted) {
      pairs_.push_back({ra, cb, values_.size()});
      values_.resize(values_.size() + static_cast<std::size_t>(nr * nc), 0.0);
    }
    double* v = values_.data() + pairs_[it->second].offset;
    for (int r = 0; r < nr; ++r) {
      for (int c = 0; c < nc; ++c) {
        v[r * nc + c] += swap ? m[c * ld + r] : m[r * ld + c];
      }
    }
  }
  struct Pair {
    int a, b;
    std::size_t offset;
  };
  const std::vector<Pair>& pairs() const { return pairs_; }
  const double* values(const Pair& p) const { return values_.data() + p.offset; }

 private:
  const std::vector<ReducedBlock>& blocks_;
  std::unordered_map<std::uint64_t, std::size_t> index_;
  std::vector<Pair> pairs_;
  std::vector<double> values_;
};

// Runs f(i) for i in [0, n) on up to `threads` threads (contiguous ranges).
template <class F>
void ParallelFor(std::size_t n, int threads, const F& f) {
  const std::size_t t = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(threads), n));
  if (t <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::vector<std::thread> pool;
  for (std::size_t k = 0; k < t; ++k) {
    pool.emplace_back([&, k] {
      for (std::size_t i = n * k / t; i < n * (k + 1) / t; ++i) f(i);
    });
  }
  for (std::thread& th : pool) th.join();
}

// The Jacobians of one residual block over its variable blocks (tangent
// space, loss applied): jac[i] empty for held blocks.
bool EvaluateJacobians(const ceres::Problem& problem, ceres::ResidualBlockId id, const std::vector<double*>& params,
                       std::vector<RowMajorMatrix>& jac) {
  const int nr = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
  jac.resize(params.size());
  std::vector<double*> ptr(params.size(), nullptr);
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (problem.IsParameterBlockConstant(params[i])) {
      jac[i].resize(0, 0);
      continue;
    }
    jac[i].resize(nr, problem.ParameterBlockTangentSize(params[i]));
    ptr[i] = jac[i].data();
  }
  std::vector<double> residuals(static_cast<std::size_t>(nr));
  double cost = 0;
  return problem.EvaluateResidualBlock(id, true, &cost, residuals.data(), ptr.data());
}

// One residual block of a landmark, evaluated: its parameter blocks and
// their Jacobians.
struct Evaluated {
  std::vector<double*> params;
  std::vector<RowMajorMatrix> jac;
};

// The computation as stages, in the order ComputeSchurCovariances runs them:
// the variables, the residual blocks sorted by landmark, the reduced system
// S (blocks without a landmark, then each landmark's Schur term), its
// fill-reducing order, factor and selected inverse, and each landmark's
// covariance from it. A stage returns false with why_ set when it fails.
class SchurCovarianceSolver {
 public:
  SchurCovarianceSolver(ceres::Problem& problem, const std::vector<double*>& blocks, int num_threads, std::string* why)
      : problem_(problem), blocks_(blocks), num_threads_(num_threads), why_(*why), system_(reduced_) {}

  bool IndexVariables(double* model);
  bool SortResidualBlocks();
  bool AddBlocksWithoutLandmark();
  bool AddLandmarkSchurTerms();
  std::size_t OrderReducedBlocks();
  bool FactorReducedSystem(int n, std::size_t* factor_nonzeros);
  bool LandmarkCovariances(SchurCovariances* out);

 private:
  void LandmarkPartOf(std::size_t li, const std::vector<Evaluated>& ev, RowMajorMatrix* hcc);
  bool SigmaBlock(int a, int b, double* dst, int ld) const;
  void LandmarkCovariance(std::size_t li, SchurCovariances* out);

  ceres::Problem& problem_;
  const std::vector<double*>& blocks_;
  const int num_threads_;
  std::string& why_;
  std::unordered_map<const double*, int> landmark_of_;
  std::vector<ReducedBlock> reduced_;
  std::unordered_map<const double*, int> reduced_of_;
  int model_block_ = -1;
  std::vector<std::vector<ceres::ResidualBlockId>> of_landmark_;
  std::vector<ceres::ResidualBlockId> others_;  // residual blocks on the reduced blocks alone
  ReducedSystem system_;
  std::vector<LandmarkPart> parts_;
  std::vector<char> failed_;  // per landmark
  SelectedInverse z_;
};

// The variables: the landmarks (distinct 3-vectors of the problem) and the
// reduced blocks (every other variable block with a tangent space).
bool SchurCovarianceSolver::IndexVariables(double* model) {
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (!problem_.HasParameterBlock(blocks_[i]) || problem_.IsParameterBlockConstant(blocks_[i]) ||
        problem_.ParameterBlockTangentSize(blocks_[i]) != 3 ||
        !landmark_of_.emplace(blocks_[i], static_cast<int>(i)).second) {
      why_ = "landmark block " + std::to_string(i) + " is not a distinct variable 3-vector of the problem";
      return false;
    }
  }
  std::vector<double*> all;
  problem_.GetParameterBlocks(&all);
  for (double* p : all) {
    if (landmark_of_.count(p) || problem_.IsParameterBlockConstant(p)) continue;
    const int size = problem_.ParameterBlockTangentSize(p);
    if (size == 0) continue;
    reduced_of_.emplace(p, static_cast<int>(reduced_.size()));
    reduced_.push_back({p, size});
  }
  if (model) {
    const auto it = reduced_of_.find(model);
    if (it != reduced_of_.end()) model_block_ = it->second;
  }
  return true;
}

// The residual blocks: by landmark, or on the reduced blocks alone.
bool SchurCovarianceSolver::SortResidualBlocks() {
  std::vector<ceres::ResidualBlockId> residuals;
  problem_.GetResidualBlocks(&residuals);
  of_landmark_.assign(blocks_.size(), {});
  std::vector<double*> params;
  for (const ceres::ResidualBlockId id : residuals) {
    params.clear();
    problem_.GetParameterBlocksForResidualBlock(id, &params);
    int lm = -1;
    for (double* p : params) {
      const auto it = landmark_of_.find(p);
      if (it == landmark_of_.end()) continue;
      if (lm >= 0 && lm != it->second) {
        why_ = "a residual block couples two landmarks (no block-diagonal H_ll)";
        return false;
      }
      lm = it->second;
    }
    if (lm >= 0) {
      of_landmark_[static_cast<std::size_t>(lm)].push_back(id);
    } else {
      others_.push_back(id);
    }
  }
  return true;
}

// J^T J of the residual blocks without a landmark (priors, odometry, DVL) into S.
bool SchurCovarianceSolver::AddBlocksWithoutLandmark() {
  std::vector<double*> params;
  std::vector<RowMajorMatrix> jac;
  for (const ceres::ResidualBlockId id : others_) {
    params.clear();
    problem_.GetParameterBlocksForResidualBlock(id, &params);
    if (!EvaluateJacobians(problem_, id, params, jac)) {
      why_ = "a residual block failed to evaluate";
      return false;
    }
    for (std::size_t a = 0; a < params.size(); ++a) {
      if (jac[a].size() == 0) continue;
      for (std::size_t b = 0; b <= a; ++b) {
        if (jac[b].size() == 0) continue;
        const RowMajorMatrix m = jac[a].transpose() * jac[b];
        system_.Add(reduced_of_.at(params[a]), reduced_of_.at(params[b]), m.data(), static_cast<int>(m.cols()));
      }
    }
  }
  return true;
}

// Landmark li's part (H_ll^-1, G) from its evaluated residual blocks, and
// *hcc = J_c^T J_c - H_cl G over the reduced blocks it touches; failed_[li]
// when H_ll is singular.
void SchurCovarianceSolver::LandmarkPartOf(std::size_t li, const std::vector<Evaluated>& ev, RowMajorMatrix* hcc) {
  LandmarkPart& part = parts_[li];
  for (const Evaluated& e : ev) {
    for (std::size_t a = 0; a < e.params.size(); ++a) {
      if (e.jac[a].size() == 0) continue;
      const auto it = reduced_of_.find(e.params[a]);
      if (it != reduced_of_.end()) part.blocks.push_back(it->second);
    }
  }
  std::sort(part.blocks.begin(), part.blocks.end());
  part.blocks.erase(std::unique(part.blocks.begin(), part.blocks.end()), part.blocks.end());
  part.offsets.assign(1, 0);
  for (int b : part.blocks) part.offsets.push_back(part.offsets.back() + reduced_[static_cast<std::size_t>(b)].size);
  const int m = part.offsets.back();
  Eigen::Matrix3d hll = Eigen::Matrix3d::Zero();
  RowMajorMatrix hlc = RowMajorMatrix::Zero(3, m);
  hcc->setZero(m, m);
  std::vector<int> at;
  for (const Evaluated& e : ev) {
    const std::vector<double*>& params = e.params;
    const std::vector<RowMajorMatrix>& jac = e.jac;
    at.assign(params.size(), -1);  // local column of each variable reduced block
    std::size_t lpos = params.size();
    for (std::size_t a = 0; a < params.size(); ++a) {
      if (params[a] == blocks_[li]) {
        lpos = a;
      } else if (jac[a].size() != 0) {
        const int b = reduced_of_.at(params[a]);
        const auto pos = std::lower_bound(part.blocks.begin(), part.blocks.end(), b) - part.blocks.begin();
        at[a] = part.offsets[static_cast<std::size_t>(pos)];
      }
    }
    const RowMajorMatrix& jl = jac[lpos];
    hll += jl.transpose() * jl;
    for (std::size_t a = 0; a < params.size(); ++a) {
      if (at[a] < 0) continue;
      const int na = static_cast<int>(jac[a].cols());
      hlc.middleCols(at[a], na) += jl.transpose() * jac[a];
      for (std::size_t b = 0; b < params.size(); ++b) {
        if (at[b] < 0) continue;
        hcc->block(at[a], at[b], na, jac[b].cols()) += jac[a].transpose() * jac[b];
      }
    }
  }
  const Eigen::LLT<Eigen::Matrix3d> llt(hll);
  if (llt.info() != Eigen::Success) {
    failed_[li] = 1;
    return;
  }
  part.hll_inverse = llt.solve(Eigen::Matrix3d::Identity());
  part.g = part.hll_inverse * hlc;
  hcc->noalias() -= hlc.transpose() * part.g;
}

// The landmarks, in batches: their residual blocks evaluated in order (one
// thread: Problem::EvaluateResidualBlock updates the shared parameter
// blocks' state), their parts in parallel, their Schur terms
// -H_cl H_ll^-1 H_lc (and J_c^T J_c) added to S in landmark order.
bool SchurCovarianceSolver::AddLandmarkSchurTerms() {
  parts_.resize(blocks_.size());
  failed_.assign(blocks_.size(), 0);
  constexpr std::size_t kBatch = 2048;
  std::vector<std::vector<Evaluated>> evaluated(kBatch);
  std::vector<RowMajorMatrix> local(kBatch);  // per landmark of the batch: J_c^T J_c - H_cl G
  for (std::size_t first = 0; first < blocks_.size(); first += kBatch) {
    const std::size_t count = std::min(kBatch, blocks_.size() - first);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t li = first + k;
      std::vector<Evaluated>& ev = evaluated[k];
      ev.resize(of_landmark_[li].size());
      for (std::size_t r = 0; r < ev.size(); ++r) {
        ev[r].params.clear();
        problem_.GetParameterBlocksForResidualBlock(of_landmark_[li][r], &ev[r].params);
        if (!EvaluateJacobians(problem_, of_landmark_[li][r], ev[r].params, ev[r].jac)) {
          why_ = "a residual block of landmark " + std::to_string(li) + " failed to evaluate";
          return false;
        }
      }
    }
    ParallelFor(count, num_threads_, [&](std::size_t k) { LandmarkPartOf(first + k, evaluated[k], &local[k]); });
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t li = first + k;
      if (failed_[li]) {
        why_ = "landmark " + std::to_string(li) + " has a singular information block";
        return false;
      }
      const LandmarkPart& part = parts_[li];
      const RowMajorMatrix& hcc = local[k];
      for (std::size_t a = 0; a < part.blocks.size(); ++a) {
        for (std::size_t b = 0; b <= a; ++b) {
          system_.Add(part.blocks[a], part.blocks[b], hcc.data() + part.offsets[a] * hcc.cols() + part.offsets[b],
                      static_cast<int>(hcc.cols()));
        }
      }
    }
  }
  return true;
}

// A fill-reducing order of the reduced blocks (AMD on their graph): sets
// each block's first column and returns the columns of S.
std::size_t SchurCovarianceSolver::OrderReducedBlocks() {
  const int nb = static_cast<int>(reduced_.size());
  if (nb == 0) return 0;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(2 * system_.pairs().size());
  for (const auto& p : system_.pairs()) {
    t.emplace_back(p.a, p.b, 1.0);
    if (p.a != p.b) t.emplace_back(p.b, p.a, 1.0);
  }
  Eigen::SparseMatrix<double> graph(nb, nb);
  graph.setFromTriplets(t.begin(), t.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(graph, order);  // order.indices()[new] = old
  int column = 0;
  for (int k = 0; k < nb; ++k) {
    const int b = order.indices()[k];
    reduced_[static_cast<std::size_t>(b)].column = column;
    column += reduced_[static_cast<std::size_t>(b)].size;
  }
  return static_cast<std::size_t>(column);
}

// S (lower triangle, in that order), its factor and selected inverse.
bool SchurCovarianceSolver::FactorReducedSystem(int n, std::size_t* factor_nonzeros) {
  if (n == 0) return true;
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& p : system_.pairs()) {
    const ReducedBlock &ra = reduced_[static_cast<std::size_t>(p.a)], &rb = reduced_[static_cast<std::size_t>(p.b)];
    const double* v = system_.values(p);
    const bool below = ra.column > rb.column;
    for (int r = 0; r < ra.size; ++r) {
      for (int c = 0; c < rb.size; ++c) {
        if (p.a == p.b && c > r) continue;
        const int row = ra.column + r, col = rb.column + c;
        if (below || p.a == p.b) {
          t.emplace_back(row, col, v[r * rb.size + c]);
        } else {
          t.emplace_back(col, row, v[r * rb.size + c]);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> s(n, n);
  s.setFromTriplets(t.begin(), t.end());
  t = {};
  if (!z_.Compute(s, &why_)) return false;
  *factor_nonzeros = z_.factor_nonzeros();
  return true;
}

// Sigma_cc on the (a, b) blocks of the reduced system (row-major a x b).
bool SchurCovarianceSolver::SigmaBlock(int a, int b, double* dst, int ld) const {
  const ReducedBlock &ra = reduced_[static_cast<std::size_t>(a)], &rb = reduced_[static_cast<std::size_t>(b)];
  if (a == b) {
    for (int r = 0; r < ra.size; ++r) {
      for (int c = 0; c <= r; ++c) {
        double v = 0;
        if (!z_.Get(ra.column + r, ra.column + c, &v)) return false;
        dst[r * ld + c] = dst[c * ld + r] = v;
      }
    }
    return true;
  }
  const bool below = ra.column > rb.column;  // stored: rows of the later block, columns of the earlier
  const ReducedBlock& rows = below ? ra : rb;
  const ReducedBlock& cols = below ? rb : ra;
  double run[16];
  if (rows.size > 16) return false;
  for (int c = 0; c < cols.size; ++c) {
    if (!z_.GetColumnRun(rows.column, rows.size, cols.column + c, run)) return false;
    for (int r = 0; r < rows.size; ++r) {
      if (below) {
        dst[r * ld + c] = run[r];
      } else {
        dst[c * ld + r] = run[r];
      }
    }
  }
  return true;
}

// Landmark li: Sigma_ll = H_ll^-1 + G Sigma_cc G^T, Sigma_lM = -G Sigma_cM;
// failed_[li] when a block it needs is off the factor's pattern.
void SchurCovarianceSolver::LandmarkCovariance(std::size_t li, SchurCovariances* out) {
  const LandmarkPart& part = parts_[li];
  const int m = part.offsets.back();
  RowMajorMatrix sigma(m, m);
  for (std::size_t a = 0; a < part.blocks.size(); ++a) {
    for (std::size_t b = 0; b <= a; ++b) {
      double* dst = sigma.data() + part.offsets[a] * m + part.offsets[b];
      if (!SigmaBlock(part.blocks[a], part.blocks[b], dst, m)) {
        failed_[li] = 1;
        return;
      }
      if (a == b) continue;
      const int na = part.offsets[a + 1] - part.offsets[a], nbk = part.offsets[b + 1] - part.offsets[b];
      sigma.block(part.offsets[b], part.offsets[a], nbk, na) =
          sigma.block(part.offsets[a], part.offsets[b], na, nbk).transpose();
    }
  }
  const RowMajorMatrix gs = part.g * sigma;  // G Sigma_cc = -Sigma_lc
  const Eigen::Matrix3d ll = part.hll_inverse + gs * part.g.transpose();
  out->ll[li] = 0.5 * (ll + ll.transpose());
  const auto pos = std::lower_bound(part.blocks.begin(), part.blocks.end(), model_block_) - part.blocks.begin();
  if (model_block_ >= 0 && pos < static_cast<std::ptrdiff_t>(part.blocks.size()) &&
      part.blocks[static_cast<std::size_t>(pos)] == model_block_) {
    const int off = part.offsets[static_cast<std::size_t>(pos)];
    out->lm[li] = -gs.middleCols(off, reduced_[static_cast<std::size_t>(model_block_)].size);
  }
}

// The model pose's own block, then every landmark's covariances (in parallel).
bool SchurCovarianceSolver::LandmarkCovariances(SchurCovariances* out) {
  out->ll.assign(blocks_.size(), Eigen::Matrix3d::Zero());
  out->lm.assign(blocks_.size(), RowMajorMatrix());
  out->mm.resize(0, 0);
  if (model_block_ >= 0) {
    const int tm = reduced_[static_cast<std::size_t>(model_block_)].size;
    out->mm.resize(tm, tm);
    if (!SigmaBlock(model_block_, model_block_, out->mm.data(), tm)) {
      why_ = "the model pose's block is not on the factor's pattern";
      return false;
    }
  }
  std::fill(failed_.begin(), failed_.end(), 0);
  ParallelFor(blocks_.size(), num_threads_, [&](std::size_t li) { LandmarkCovariance(li, out); });
  for (std::size_t li = 0; li < blocks_.size(); ++li) {
    if (failed_[li]) {
      why_ = "landmark " + std::to_string(li) + "'s reduced blocks are not on the factor's pattern";
      return false;
    }
  }
  return true;
}

}  // namespace

bool ComputeSchurCovariances(ceres::Problem& problem, const std::vector<double*>& blocks, double* model,
                             int num_threads, SchurCovariances* out, std::string* why) {
  SchurCovarianceSolver solver(problem, blocks, num_threads, why);
  if (!solver.IndexVariables(model) || !solver.SortResidualBlocks() || !solver.AddBlocksWithoutLandmark() ||
      !solver.AddLandmarkSchurTerms()) {
    return false;
  }
  out->reduced_size = solver.OrderReducedBlocks();
  if (!solver.FactorReducedSystem(static_cast<int>(out->reduced_size), &out->factor_nonzeros)) return false;
  return solver.LandmarkCovariances(out);
}

}  // namespace hull::adjust
