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

}  // namespace

bool ComputeSchurCovariances(ceres::Problem& problem, const std::vector<double*>& blocks, double* model,
                             int num_threads, SchurCovariances* out, std::string* why) {
  // ---- the variables: landmarks and reduced blocks -------------------------------------
  std::unordered_map<const double*, int> landmark_of;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!problem.HasParameterBlock(blocks[i]) || problem.IsParameterBlockConstant(blocks[i]) ||
        problem.ParameterBlockTangentSize(blocks[i]) != 3 ||
        !landmark_of.emplace(blocks[i], static_cast<int>(i)).second) {
      *why = "landmark block " + std::to_string(i) + " is not a distinct variable 3-vector of the problem";
      return false;
    }
  }
  std::vector<double*> all;
  problem.GetParameterBlocks(&all);
  std::vector<ReducedBlock> reduced;
  std::unordered_map<const double*, int> reduced_of;
  for (double* p : all) {
    if (landmark_of.count(p) || problem.IsParameterBlockConstant(p)) continue;
    const int size = problem.ParameterBlockTangentSize(p);
    if (size == 0) continue;
    reduced_of.emplace(p, static_cast<int>(reduced.size()));
    reduced.push_back({p, size});
  }
  int model_block = -1;
  if (model) {
    const auto it = reduced_of.find(model);
    if (it != reduced_of.end()) model_block = it->second;
  }

  // ---- residual blocks: by landmark, or on the reduced blocks alone -------------------
  std::vector<ceres::ResidualBlockId> residuals;
  problem.GetResidualBlocks(&residuals);
  std::vector<std::vector<ceres::ResidualBlockId>> of_landmark(blocks.size());
  std::vector<ceres::ResidualBlockId> others;
  {
    std::vector<double*> params;
    for (const ceres::ResidualBlockId id : residuals) {
      params.clear();
      problem.GetParameterBlocksForResidualBlock(id, &params);
      int lm = -1;
      for (double* p : params) {
        const auto it = landmark_of.find(p);
        if (it == landmark_of.end()) continue;
        if (lm >= 0 && lm != it->second) {
          *why = "a residual block couples two landmarks (no block-diagonal H_ll)";
          return false;
        }
        lm = it->second;
      }
      if (lm >= 0) {
        of_landmark[static_cast<std::size_t>(lm)].push_back(id);
      } else {
        others.push_back(id);
      }
    }
  }

  ReducedSystem system(reduced);
  // The residual blocks without a landmark (priors, odometry, DVL).
  {
    std::vector<double*> params;
    std::vector<RowMajorMatrix> jac;
    for (const ceres::ResidualBlockId id : others) {
      params.clear();
      problem.GetParameterBlocksForResidualBlock(id, &params);
      if (!EvaluateJacobians(problem, id, params, jac)) {
        *why = "a residual block failed to evaluate";
        return false;
      }
      for (std::size_t a = 0; a < params.size(); ++a) {
        if (jac[a].size() == 0) continue;
        for (std::size_t b = 0; b <= a; ++b) {
          if (jac[b].size() == 0) continue;
          const RowMajorMatrix m = jac[a].transpose() * jac[b];
          system.Add(reduced_of.at(params[a]), reduced_of.at(params[b]), m.data(), static_cast<int>(m.cols()));
        }
      }
    }
  }
  // The landmarks, in batches: their residual blocks evaluated in order (one
  // thread: Problem::EvaluateResidualBlock updates the shared parameter
  // blocks' state), their parts in parallel, their Schur terms
  // -H_cl H_ll^-1 H_lc (and J_c^T J_c) added in landmark order.
  std::vector<LandmarkPart> parts(blocks.size());
  std::vector<char> failed(blocks.size(), 0);
  constexpr std::size_t kBatch = 2048;
  struct Evaluated {
    std::vector<double*> params;
    std::vector<RowMajorMatrix> jac;
  };
  std::vector<std::vector<Evaluated>> evaluated(kBatch);
  std::vector<RowMajorMatrix> local(kBatch);  // per landmark of the batch: J_c^T J_c - H_cl G
  for (std::size_t first = 0; first < blocks.size(); first += kBatch) {
    const std::size_t count = std::min(kBatch, blocks.size() - first);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t li = first + k;
      std::vector<Evaluated>& ev = evaluated[k];
      ev.resize(of_landmark[li].size());
      for (std::size_t r = 0; r < ev.size(); ++r) {
        ev[r].params.clear();
        problem.GetParameterBlocksForResidualBlock(of_landmark[li][r], &ev[r].params);
        if (!EvaluateJacobians(problem, of_landmark[li][r], ev[r].params, ev[r].jac)) {
          *why = "a residual block of landmark " + std::to_string(li) + " failed to evaluate";
          return false;
        }
      }
    }
    ParallelFor(count, num_threads, [&](std::size_t k) {
      const std::size_t li = first + k;
      LandmarkPart& part = parts[li];
      const std::vector<Evaluated>& ev = evaluated[k];
      for (const Evaluated& e : ev) {
        for (std::size_t a = 0; a < e.params.size(); ++a) {
          if (e.jac[a].size() == 0) continue;
          const auto it = reduced_of.find(e.params[a]);
          if (it != reduced_of.end()) part.blocks.push_back(it->second);
        }
      }
      std::sort(part.blocks.begin(), part.blocks.end());
      part.blocks.erase(std::unique(part.blocks.begin(), part.blocks.end()), part.blocks.end());
      part.offsets.assign(1, 0);
      for (int b : part.blocks) part.offsets.push_back(part.offsets.back() + reduced[static_cast<std::size_t>(b)].size);
      const int m = part.offsets.back();
      Eigen::Matrix3d hll = Eigen::Matrix3d::Zero();
      RowMajorMatrix hlc = RowMajorMatrix::Zero(3, m);
      RowMajorMatrix& hcc = local[k];
      hcc.setZero(m, m);
      std::vector<int> at;
      for (const Evaluated& e : ev) {
        const std::vector<double*>& params = e.params;
        const std::vector<RowMajorMatrix>& jac = e.jac;
        at.assign(params.size(), -1);  // local column of each variable reduced block
        std::size_t lpos = params.size();
        for (std::size_t a = 0; a < params.size(); ++a) {
          if (params[a] == blocks[li]) {
            lpos = a;
          } else if (jac[a].size() != 0) {
            const int b = reduced_of.at(params[a]);
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
            hcc.block(at[a], at[b], na, jac[b].cols()) += jac[a].transpose() * jac[b];
          }
        }
      }
      const Eigen::LLT<Eigen::Matrix3d> llt(hll);
      if (llt.info() != Eigen::Success) {
        failed[li] = 1;
        return;
      }
      part.hll_inverse = llt.solve(Eigen::Matrix3d::Identity());
      part.g = part.hll_inverse * hlc;
      hcc.noalias() -= hlc.transpose() * part.g;
    });
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t li = first + k;
      if (failed[li]) {
        *why = "landmark " + std::to_string(li) + " has a singular information block";
        return false;
      }
      const LandmarkPart& part = parts[li];
      const RowMajorMatrix& hcc = local[k];
      for (std::size_t a = 0; a < part.blocks.size(); ++a) {
        for (std::size_t b = 0; b <= a; ++b) {
          system.Add(part.blocks[a], part.blocks[b], hcc.data() + part.offsets[a] * hcc.cols() + part.offsets[b],
                     static_cast<int>(hcc.cols()));
        }
      }
    }
  }
  local.clear();

  // ---- a fill-reducing order of the reduced blocks (AMD on their graph) --------------
  const int nb = static_cast<int>(reduced.size());
  out->reduced_size = 0;
  if (nb > 0) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(2 * system.pairs().size());
    for (const auto& p : system.pairs()) {
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
      reduced[static_cast<std::size_t>(b)].column = column;
      column += reduced[static_cast<std::size_t>(b)].size;
    }
    out->reduced_size = static_cast<std::size_t>(column);
  }
  const int n = static_cast<int>(out->reduced_size);

  // ---- S (lower triangle, in that order), its factor and selected inverse ----------
  SelectedInverse z;
  if (n > 0) {
    std::vector<Eigen::Triplet<double>> t;
    for (const auto& p : system.pairs()) {
      const ReducedBlock &ra = reduced[static_cast<std::size_t>(p.a)], &rb = reduced[static_cast<std::size_t>(p.b)];
      const double* v = system.values(p);
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
    if (!z.Compute(s, why)) return false;
    out->factor_nonzeros = z.factor_nonzeros();
  }

  // Sigma_cc on the (a, b) blocks of the reduced system (row-major a x b).
  auto sigma_block = [&](int a, int b, double* dst, int ld) -> bool {
    const ReducedBlock &ra = reduced[static_cast<std::size_t>(a)], &rb = reduced[static_cast<std::size_t>(b)];
    if (a == b) {
      for (int r = 0; r < ra.size; ++r) {
        for (int c = 0; c <= r; ++c) {
          double v = 0;
          if (!z.Get(ra.column + r, ra.column + c, &v)) return false;
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
      if (!z.GetColumnRun(rows.column, rows.size, cols.column + c, run)) return false;
      for (int r = 0; r < rows.size; ++r) {
        if (below) {
          dst[r * ld + c] = run[r];
        } else {
          dst[c * ld + r] = run[r];
        }
      }
    }
    return true;
  };

  // ---- per landmark: Sigma_ll = H_ll^-1 + G Sigma_cc G^T, Sigma_lM = -G Sigma_cM ----
  out->ll.assign(blocks.size(), Eigen::Matrix3d::Zero());
  out->lm.assign(blocks.size(), RowMajorMatrix());
  out->mm.resize(0, 0);
  if (model_block >= 0) {
    const int tm = reduced[static_cast<std::size_t>(model_block)].size;
    out->mm.resize(tm, tm);
    if (!sigma_block(model_block, model_block, out->mm.data(), tm)) {
      *why = "the model pose's block is not on the factor's pattern";
      return false;
    }
  }
  std::fill(failed.begin(), failed.end(), 0);
  ParallelFor(blocks.size(), num_threads, [&](std::size_t li) {
    const LandmarkPart& part = parts[li];
    const int m = part.offsets.back();
    RowMajorMatrix sigma(m, m);
    for (std::size_t a = 0; a < part.blocks.size(); ++a) {
      for (std::size_t b = 0; b <= a; ++b) {
        double* dst = sigma.data() + part.offsets[a] * m + part.offsets[b];
        if (!sigma_block(part.blocks[a], part.blocks[b], dst, m)) {
          failed[li] = 1;
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
    const auto pos = std::lower_bound(part.blocks.begin(), part.blocks.end(), model_block) - part.blocks.begin();
    if (model_block >= 0 && pos < static_cast<std::ptrdiff_t>(part.blocks.size()) &&
        part.blocks[static_cast<std::size_t>(pos)] == model_block) {
      const int off = part.offsets[static_cast<std::size_t>(pos)];
      out->lm[li] = -gs.middleCols(off, reduced[static_cast<std::size_t>(model_block)].size);
    }
  });
  for (std::size_t li = 0; li < blocks.size(); ++li) {
    if (failed[li]) {
      *why = "landmark " + std::to_string(li) + "'s reduced blocks are not on the factor's pattern";
      return false;
    }
  }
  return true;
}

}  // namespace hull::adjust
