// The photomosaic's atlas geometry and image sampling
// (photomosaic_internal.h): a flat chart per face, shelf packing, texel
// barycentrics, bilinear samples of the camera images.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mosaic/photomosaic_internal.h"

namespace hull {
namespace mosaic_internal {

bool Sample(const cv::Mat& img, double u, double v, float* out) {
  if (!(u >= 0 && v >= 0 && u <= img.cols - 1 && v <= img.rows - 1)) return false;
  const int x0 = std::min(static_cast<int>(u), img.cols - 2 < 0 ? 0 : img.cols - 2);
  const int y0 = std::min(static_cast<int>(v), img.rows - 2 < 0 ? 0 : img.rows - 2);
  const int x1 = std::min(x0 + 1, img.cols - 1), y1 = std::min(y0 + 1, img.rows - 1);
  const float fx = static_cast<float>(u - x0), fy = static_cast<float>(v - y0);
  const int ch = img.channels();
  const bool wide = img.depth() == CV_16U;
  const float scale = wide ? 1.0f / 65535.0f : 1.0f / 255.0f;
  auto at = [&](int y, int x, int c) -> float {
    return wide ? img.ptr<std::uint16_t>(y)[x * ch + c] : img.ptr<std::uint8_t>(y)[x * ch + c];
  };
  for (int c = 0; c < ch; ++c) {
    const float top = (1 - fx) * at(y0, x0, c) + fx * at(y0, x1, c);
    const float bot = (1 - fx) * at(y1, x0, c) + fx * at(y1, x1, c);
    out[c] = ((1 - fy) * top + fy * bot) * scale;
  }
  return true;
}

Chart FlatChart(const TriangleMesh& m, int f, double texel) {
  const Face& F = m.faces[static_cast<std::size_t>(f)];
  std::array<Eigen::Vector3d, 3> p;
  for (int i = 0; i < 3; ++i) p[static_cast<std::size_t>(i)] = m.vertices[static_cast<std::size_t>(F[i])];
  int base = 0;  // corner where the longest edge (base -> base+1) starts
  double longest = -1;
  for (int i = 0; i < 3; ++i) {
    const double l = (p[static_cast<std::size_t>((i + 1) % 3)] - p[static_cast<std::size_t>(i)]).norm();
    if (l > longest) longest = l, base = i;
  }
  const Eigen::Vector3d a = p[static_cast<std::size_t>(base)], b = p[static_cast<std::size_t>((base + 1) % 3)],
                        c = p[static_cast<std::size_t>((base + 2) % 3)];
  const double ab = std::max((b - a).norm(), 1e-12);
  const Eigen::Vector3d ex = (b - a) / ab;
  const double cx = (c - a).dot(ex), cy = ((c - a) - cx * ex).norm();
  constexpr double kBorder = 1.0;
  Chart ch;
  ch.w = static_cast<int>(std::ceil(ab / texel + 2 * kBorder)) + 1;
  ch.h = static_cast<int>(std::ceil(cy / texel + 2 * kBorder)) + 1;
  ch.local[static_cast<std::size_t>(base)] = {kBorder, kBorder};
  ch.local[static_cast<std::size_t>((base + 1) % 3)] = {kBorder + ab / texel, kBorder};
  ch.local[static_cast<std::size_t>((base + 2) % 3)] = {kBorder + cx / texel, kBorder + cy / texel};
  return ch;
}

int PackShelves(std::vector<Chart>& charts, const std::vector<int>& order, int width) {
  int x = 0, y = 0, row = 0;
  for (int f : order) {
    Chart& c = charts[static_cast<std::size_t>(f)];
    if (x + c.w > width) {
      y += row;
      x = 0;
      row = 0;
    }
    c.x = x;
    c.y = y;
    x += c.w;
    row = std::max(row, c.h);
  }
  return y + row;
}

Eigen::Vector3d Barycentric(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& q, bool* inside) {
  const Eigen::Vector2d v0 = t[1] - t[0], v1 = t[2] - t[0], v2 = q - t[0];
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
  if (std::abs(den) > 1e-18) {
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    b = {1 - v - w, v, w};
  }
  *inside = b.minCoeff() >= -1e-9;
  if (*inside) return b;
  // Closest point on the three edges; within kExtrapolate texels of the
  // triangle the plane is extended instead (the border texels a bilinear
  // lookup inside the triangle reaches continue the texture).
  constexpr double kExtrapolate = 1.5;
  double best = 1e300;
  Eigen::Vector3d out = b;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& a = t[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& e = t[static_cast<std::size_t>((i + 1) % 3)];
    const Eigen::Vector2d ae = e - a;
    const double s = std::clamp(ae.squaredNorm() > 0 ? (q - a).dot(ae) / ae.squaredNorm() : 0.0, 0.0, 1.0);
    const double d = (a + s * ae - q).squaredNorm();
    if (d < best) {
      best = d;
      out.setZero();
      out[i] = 1 - s;
      out[(i + 1) % 3] = s;
    }
  }
  return best <= kExtrapolate * kExtrapolate ? b : out;
}

}  // namespace mosaic_internal
}  // namespace hull
