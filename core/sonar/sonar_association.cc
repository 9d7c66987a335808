#include "sonar/sonar_association.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace hull {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The regularised upper incomplete gamma function Q(a, x) (series below
// a + 1, Lentz's continued fraction above; Numerical Recipes 6.2).
double GammaQ(double a, double x) {
  if (x <= 0) return 1.0;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1) {
    double term = 1 / a, sum = term;
    for (int n = 1; n < 1000 && std::abs(term) > 1e-16 * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return 1 - sum * std::exp(log_prefix);
  }
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-16) break;
  }
  return std::exp(log_prefix) * h;
}

double WrapInnovation(double a) { return std::remainder(a, 2 * M_PI); }

// The branch and bound of JCBB over predictions in `order`.
class Jcbb {
 public:
  Jcbb(const AssociationInput& in, const Eigen::MatrixXd& individual, double gate_probability, long max_nodes)
      : in_(in), max_nodes_(max_nodes) {
    const int n = static_cast<int>(individual.rows());
    compatible_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      std::vector<int>& c = compatible_[static_cast<std::size_t>(i)];
      for (int j = 0; j < individual.cols(); ++j) {
        if (std::isfinite(individual(i, j))) c.push_back(j);
      }
      std::sort(c.begin(), c.end(), [&](int a, int b) { return individual(i, a) < individual(i, b); });
      if (!c.empty()) order_.push_back(i);
    }
    // The most constrained predictions first: the bound prunes earlier.
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
      return compatible_[static_cast<std::size_t>(a)].size() < compatible_[static_cast<std::size_t>(b)].size();
    });
    for (int k = 1; k <= n; ++k) gate_.push_back(ChiSquareQuantile(gate_probability, 2 * k));
    used_.assign(in.detected.size(), false);
    best_.detection.assign(static_cast<std::size_t>(n), -1);
  }

  // False when the node budget ran out.
  bool Run() {
    Search(0, 0.0);
    return !aborted_;
  }
  Association best() const { return best_; }
  long nodes() const { return nodes_; }

 private:
  // Joint squared distance of the current pairings.
  double JointDistance() const {
    const int k = static_cast<int>(pairs_.size());
    Eigen::VectorXd nu(2 * k);
    Eigen::MatrixXd S(2 * k, 2 * k);
    for (int a = 0; a < k; ++a) {
      const auto [ia, ja] = pairs_[static_cast<std::size_t>(a)];
      nu.segment<2>(2 * a) = in_.detected[static_cast<std::size_t>(ja)] - in_.predicted.segment<2>(2 * ia);
      nu[2 * a + 1] = WrapInnovation(nu[2 * a + 1]);
      for (int b = 0; b < k; ++b) {
        const int ib = pairs_[static_cast<std::size_t>(b)].first;
        S.block<2, 2>(2 * a, 2 * b) = in_.covariance.block<2, 2>(2 * ia, 2 * ib);
      }
      S.block<2, 2>(2 * a, 2 * a) += in_.noise[static_cast<std::size_t>(ja)];
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(S);
    if (llt.info() != Eigen::Success) return kInf;
    return nu.dot(llt.solve(nu));
  }

  void Search(std::size_t level, double distance) {
    if (aborted_ || ++nodes_ > max_nodes_) {
      aborted_ = true;
      return;
    }
    const int pairs = static_cast<int>(pairs_.size());
    if (level == order_.size()) {
      if (pairs > best_.pairs || (pairs == best_.pairs && distance < best_.distance)) {
        best_.pairs = pairs;
        best_.distance = distance;
        std::fill(best_.detection.begin(), best_.detection.end(), -1);
        for (const auto& [i, j] : pairs_) best_.detection[static_cast<std::size_t>(i)] = j;
      }
      return;
    }
    const int i = order_[level];
    for (int j : compatible_[static_cast<std::size_t>(i)]) {
      if (used_[static_cast<std::size_t>(j)]) continue;
      pairs_.emplace_back(i, j);
      const double d = JointDistance();
      if (d <= gate_[pairs_.size() - 1]) {
        used_[static_cast<std::size_t>(j)] = true;
        Search(level + 1, d);
        used_[static_cast<std::size_t>(j)] = false;
      }
      pairs_.pop_back();
    }
    // Leave i unpaired only if the rest could still pair as many as the best.
    const int remaining = static_cast<int>(order_.size() - level - 1);
    if (pairs + remaining >= best_.pairs) Search(level + 1, distance);
  }

  const AssociationInput& in_;
  long max_nodes_;
  std::vector<std::vector<int>> compatible_;
  std::vector<int> order_;
  std::vector<double> gate_;  // by number of pairings - 1
  std::vector<bool> used_;
  std::vector<std::pair<int, int>> pairs_;
  Association best_;
  long nodes_ = 0;
  bool aborted_ = false;
};

}  // namespace

double ChiSquareQuantile(double p, int dof) {
  if (!(p > 0 && p < 1) || dof < 1) throw std::invalid_argument("ChiSquareQuantile: needs 0 < p < 1 and dof >= 1");
  if (dof == 2) return -2 * std::log(1 - p);
  // P(X > x) = Q(dof / 2, x / 2), decreasing in x: bisection.
  const auto tail = [&](double x) { return GammaQ(dof / 2.0, x / 2); };
  double lo = 0, hi = dof + 10.0;
  while (tail(hi) > 1 - p) hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (tail(mid) > 1 - p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Eigen::MatrixXd IndividualDistances(const AssociationInput& in, double gate_probability) {
  const int n = static_cast<int>(in.predicted.size() / 2), m = static_cast<int>(in.detected.size());
  if (in.predicted.size() % 2 != 0 || in.covariance.rows() != 2 * n || in.covariance.cols() != 2 * n ||
      in.noise.size() != in.detected.size()) {
    throw std::invalid_argument("IndividualDistances: inconsistent sizes");
  }
  const double gate = ChiSquareQuantile(gate_probability, 2);
  Eigen::MatrixXd d(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const Eigen::Matrix2d S = in.covariance.block<2, 2>(2 * i, 2 * i) + in.noise[static_cast<std::size_t>(j)];
      Eigen::Vector2d nu = in.detected[static_cast<std::size_t>(j)] - in.predicted.segment<2>(2 * i);
      nu[1] = WrapInnovation(nu[1]);
      const Eigen::LLT<Eigen::Matrix2d> llt(S);
      const double d2 = llt.info() == Eigen::Success ? nu.dot(llt.solve(nu)) : kInf;
      d(i, j) = d2 <= gate ? d2 : kInf;
    }
  }
  return d;
}

Association JointCompatibility(const AssociationInput& in, double gate_probability, long max_nodes) {
  const Eigen::MatrixXd individual = IndividualDistances(in, gate_probability);
  Jcbb search(in, individual, gate_probability, max_nodes);
  if (search.Run()) {
    Association a = search.best();
    a.nodes = search.nodes();
    a.jcbb = true;
    return a;
  }
  // Too many hypotheses: the optimal assignment over the gated pairs.
  Association a;
  a.nodes = search.nodes();
  a.detection = OptimalAssignment(individual, ChiSquareQuantile(gate_probability, 2));
  for (std::size_t i = 0; i < a.detection.size(); ++i) {
    if (a.detection[i] < 0) continue;
    ++a.pairs;
    a.distance += individual(static_cast<Eigen::Index>(i), a.detection[i]);
  }
  return a;
}

std::vector<int> OptimalAssignment(const Eigen::MatrixXd& cost, double unpaired) {
  const int n = static_cast<int>(cost.rows()), m = static_cast<int>(cost.cols());
  std::vector<int> out(static_cast<std::size_t>(n), -1);
  if (n == 0) return out;
  // Columns m .. m + n - 1: row i's own "unpaired" column.
  const int M = m + n;
  double big = unpaired;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      if (std::isfinite(cost(i, j))) big = std::max(big, cost(i, j));
    }
  }
  big = 4 * (big + 1) * (n + 1);      // above any assignment that uses only allowed pairs
  const auto a = [&](int i, int j) {  // 1-based
    if (j <= m) return std::isfinite(cost(i - 1, j - 1)) ? cost(i - 1, j - 1) : big;
    return j - m == i ? unpaired : big;
  };
  // Hungarian method with potentials (rows 1..n, columns 1..M, n <= M).
  std::vector<double> u(static_cast<std::size_t>(n + 1), 0), v(static_cast<std::size_t>(M + 1), 0);
  std::vector<int> p(static_cast<std::size_t>(M + 1), 0), way(static_cast<std::size_t>(M + 1), 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<std::size_t>(M + 1), kInf);
    std::vector<bool> used(static_cast<std::size_t>(M + 1), false);
    do {
      used[static_cast<std::size_t>(j0)] = true;
      const int i0 = p[static_cast<std::size_t>(j0)];
      double delta = kInf;
      int j1 = 0;
      for (int j = 1; j <= M; ++j) {
        if (used[static_cast<std::size_t>(j)]) continue;
        const double cur = a(i0, j) - u[static_cast<std::size_t>(i0)] - v[static_cast<std::size_t>(j)];
        if (cur < minv[static_cast<std::size_t>(j)]) {
          minv[static_cast<std::size_t>(j)] = cur;
          way[static_cast<std::size_t>(j)] = j0;
        }
        if (minv[static_cast<std::size_t>(j)] < delta) {
          delta = minv[static_cast<std::size_t>(j)];
          j1 = j;
        }
      }
      for (int j = 0; j <= M; ++j) {
        if (used[static_cast<std::size_t>(j)]) {
          u[static_cast<std::size_t>(p[static_cast<std::size_t>(j)])] += delta;
          v[static_cast<std::size_t>(j)] -= delta;
        } else {
          minv[static_cast<std::size_t>(j)] -= delta;
        }
      }
      j0 = j1;
    } while (p[static_cast<std::size_t>(j0)] != 0);
    do {
      const int j1 = way[static_cast<std::size_t>(j0)];
      p[static_cast<std::size_t>(j0)] = p[static_cast<std::size_t>(j1)];
      j0 = j1;
    } while (j0 != 0);
  }
  for (int j = 1; j <= m; ++j) {
    const int i = p[static_cast<std::size_t>(j)];
    if (i > 0 && std::isfinite(cost(i - 1, j - 1))) out[static_cast<std::size_t>(i - 1)] = j - 1;
  }
  return out;
}

}  // namespace hull
