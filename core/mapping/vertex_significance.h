// The significance mask of a fused model (M3C2's level of detection): a
// vertex's deviation h is significant where |h| > k sigma, sigma being its
// per-vertex standard deviation (the model's vertex scalar "sigma"). k is a
// display parameter: the GUI and the report recompute the mask from the model's deviation
// and sigma without re-running the adjustment or the mapping.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace hull {

// Whether the model carries a per-vertex sigma (a "sigma" scalar with at
// least one finite value).
bool HasVertexSigma(const TriangleMesh& model);

// Per vertex: the deviation where |deviation| > k sigma, NaN elsewhere
// (not significant, or sigma unknown). Empty when the model has no
// "deviation".
std::vector<double> SignificantDeviation(const TriangleMesh& model, double k);

// How many vertices are significant at k.
std::size_t CountSignificant(const TriangleMesh& model, double k);

// The largest finite per-vertex sigma (m; 0 without any).
double MaxVertexSigma(const TriangleMesh& model);

}  // namespace hull
