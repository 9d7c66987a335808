#include "mapping/vertex_significance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hull {

bool HasVertexSigma(const TriangleMesh& model) {
  const std::vector<double>* sigma = model.FindScalar("sigma");
  return sigma && std::any_of(sigma->begin(), sigma->end(), [](double s) { return std::isfinite(s); });
}

std::vector<double> SignificantDeviation(const TriangleMesh& model, double k) {
  const std::vector<double>* deviation = model.FindScalar("deviation");
  const std::vector<double>* sigma = model.FindScalar("sigma");
  if (!deviation) return {};
  std::vector<double> out(deviation->size(), std::numeric_limits<double>::quiet_NaN());
  if (!sigma || sigma->size() != deviation->size()) return out;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double h = (*deviation)[i], s = (*sigma)[i];
    if (std::isfinite(s) && std::abs(h) > k * s) out[i] = h;
  }
  return out;
}

std::size_t CountSignificant(const TriangleMesh& model, double k) {
  const std::vector<double> d = SignificantDeviation(model, k);
  return static_cast<std::size_t>(std::count_if(d.begin(), d.end(), [](double h) { return !std::isnan(h); }));
}

double MaxVertexSigma(const TriangleMesh& model) {
  const std::vector<double>* sigma = model.FindScalar("sigma");
  double m = 0;
  if (sigma) {
    for (const double s : *sigma) {
      if (std::isfinite(s)) m = std::max(m, s);
    }
  }
  return m;
}

}  // namespace hull
