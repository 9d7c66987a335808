#include "simulate/sonar_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "base/error.h"

namespace hull {
namespace {

// splitmix64: a fast generator for the per-pixel speckle and noise
// (deterministic on every platform).
class FastRng {
 public:
  explicit FastRng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // Uniform in (0, 1].
  double Open() { return (static_cast<double>(Next() >> 11) + 1.0) * 0x1.0p-53; }
  // Gamma(looks, 1/looks): mean 1, the intensity of `looks` averaged looks.
  double Gamma(int looks) {
    // -log of a product of uniforms, taking the log before the product underflows.
    double prod = 1.0, log_sum = 0.0;
    for (int i = 0; i < looks; ++i) {
      prod *= Open();
      if (prod < 1e-200) {
        log_sum += std::log(prod);
        prod = 1.0;
      }
    }
    return -(log_sum + std::log(prod)) / looks;
  }

 private:
  std::uint64_t state_;
};

struct RayEcho {
  bool valid = false;  // a hit inside the range limits
  double range = 0;
  double energy = 0;
  int surface = -1;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // of the face hit
  double offset = 0;                                 // normal . (hit - sonar)
};

// Range at which direction d meets the plane of an echo's face, limited to
// [0, limit] (a plane seen edge-on or behind gives the limit).
double PlaneRange(const RayEcho& h, const Eigen::Vector3d& d, double limit) {
  const double nd = h.normal.dot(d);
  if (std::abs(nd) < 1e-12) return limit;
  const double r = h.offset / nd;
  return r > 0 ? std::min(r, limit) : limit;
}

// Adds energy spread evenly over the bin coordinates [u0, u1] (bin i covers [i, i + 1)).
void DepositInterval(float* column, int stride, int rows, double u0, double u1, double energy) {
  if (u0 > u1) std::swap(u0, u1);
  const double length = u1 - u0;
  if (length < 1e-6) {
    // A point: shared between the two nearest bin centres.
    const double c = u0 - 0.5;
    const int i0 = static_cast<int>(std::floor(c));
    const double f = c - i0;
    if (i0 >= 0 && i0 < rows) column[i0 * stride] += static_cast<float>(energy * (1 - f));
    if (i0 + 1 >= 0 && i0 + 1 < rows) column[(i0 + 1) * stride] += static_cast<float>(energy * f);
    return;
  }
  const double density = energy / length;
  const int first = std::max(0, static_cast<int>(std::floor(u0)));
  const int last = std::min(rows - 1, static_cast<int>(std::floor(u1)));
  for (int i = first; i <= last; ++i) {
    const double overlap = std::min(u1, i + 1.0) - std::max(u0, static_cast<double>(i));
    if (overlap > 0) column[i * stride] += static_cast<float>(density * overlap);
  }
}

}  // namespace

bool SonarRenderOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& field, const std::string& reason) {
    if (why) *why = field + ": " + reason;
    return false;
  };
  if (elevation_rays < 2 || elevation_rays > 4096) return fail("elevation_rays", "must be between 2 and 4096");
  if (azimuth_rays < 1 || azimuth_rays > 64) return fail("azimuth_rays", "must be between 1 and 64");
  if (!(spreading_exponent >= 0 && spreading_exponent <= 8)) return fail("spreading_exponent", "must be in [0, 8]");
  if (!(absorption_db_per_m >= 0 && absorption_db_per_m < 100)) {
    return fail("absorption_db_per_m", "must be in [0, 100)");
  }
  if (!(elevation_edge_db <= 0 && elevation_edge_db > -60)) return fail("elevation_edge_db", "must be in (-60, 0]");
  if (!(null_beams > 0.1 && null_beams < 100)) return fail("null_beams", "must be in (0.1, 100)");
  if (!(sidelobe_db <= 0 && sidelobe_db > -200)) return fail("sidelobe_db", "must be in (-200, 0]");
  if (pattern_radius < 0 || pattern_radius > 1000) return fail("pattern_radius", "must be in 0..1000");
  if (speckle_looks < 1 || speckle_looks > 1000) return fail("speckle_looks", "must be between 1 and 1000");
  if (point_looks < 1 || point_looks > 1000) return fail("point_looks", "must be between 1 and 1000");
  if (!(noise_level >= 0 && noise_level < 1)) return fail("noise_level", "must be in [0, 1)");
  if (!std::isfinite(gain_db)) return fail("gain_db", "must be finite");
  if (!(dynamic_range_db > 1 && dynamic_range_db <= 200)) return fail("dynamic_range_db", "must be in (1, 200]");
  return true;
}

SonarRenderer::SonarRenderer(const SonarScene& scene, const SonarSensor& sensor, const SonarImageFormat& format,
                             const SonarRenderOptions& options)
    : scene_(scene), sensor_(sensor), format_(format), options_(options) {
  std::string why;
  if (!options_.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  if (format_.range_bins < 1 || format_.beams < 1) throw OptionError("format", "needs range bins and beams");
  if (scene_.face_material.size() != scene_.mesh.faces.size() ||
      scene_.face_surface.size() != scene_.mesh.faces.size() ||
      scene_.mesh.face_normals.size() != scene_.mesh.faces.size()) {
    throw std::invalid_argument("SonarRenderer: the scene needs a material, a surface and a normal per face");
  }
  index_ = std::make_unique<MeshIndex>(scene_.mesh);
  const int A = options_.azimuth_rays, E = options_.elevation_rays;
  directions_.reserve(static_cast<std::size_t>(format_.beams * A * E));
  boundaries_.reserve(static_cast<std::size_t>(format_.beams * A * (E + 1)));
  for (int j = 0; j < format_.beams; ++j) {
    for (int a = 0; a < A; ++a) {
      const double theta = format_.ColumnToAzimuth(sensor_, j - 0.5 + (a + 0.5) / A);
      for (int e = 0; e <= 2 * E; ++e) {
        // Even e: the boundaries between the rays' intervals; odd e: the rays.
        const double phi = -sensor_.elevation_fov / 2 + e * sensor_.elevation_fov / (2 * E);
        const Eigen::Vector3d d(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
        (e % 2 ? directions_ : boundaries_).push_back(d);
      }
    }
  }
  for (int e = 0; e < E; ++e) {
    const double phi = -sensor_.elevation_fov / 2 + (e + 0.5) * sensor_.elevation_fov / E;
    elevation_weight_.push_back(ElevationWeight(phi) / (E * A));
  }
  const int K = options_.pattern_radius;
  pattern_ = cv::Mat(1, 2 * K + 1, CV_32F);
  double sum = 0;
  for (int k = -K; k <= K; ++k) sum += BeamPattern(k);
  for (int k = -K; k <= K; ++k) pattern_.at<float>(0, k + K) = static_cast<float>(BeamPattern(k) / sum);
}

SonarRenderer::~SonarRenderer() = default;

double SonarRenderer::Loss(double range) const {
  return std::pow(range, -options_.spreading_exponent) * std::pow(10.0, -2 * options_.absorption_db_per_m * range / 10);
}

double SonarRenderer::ElevationWeight(double phi) const {
  const double u = phi / (sensor_.elevation_fov / 2);
  return std::pow(10.0, options_.elevation_edge_db * u * u / 10);
}

double SonarRenderer::BeamPattern(double x) const {
  const double u = M_PI * x / options_.null_beams;
  const double sinc = std::abs(u) < 1e-9 ? 1.0 : std::sin(u) / u;
  const double side = std::abs(x) >= options_.null_beams ? std::pow(10.0, options_.sidelobe_db / 10) : 1.0;
  return sinc * sinc * side;
}

bool SonarRenderer::Sees(const Vector6d& pose, const Eigen::Vector3d& p) const {
  const Eigen::Matrix3d R = RotationFromEuler(pose[3], pose[4], pose[5]);
  const Eigen::Vector3d q = R.transpose() * (p - pose.head<3>());
  const double r = q.norm();
  if (!(r >= sensor_.range_min && r <= sensor_.range_max)) return false;
  if (std::abs(std::atan2(q.y(), q.x())) > sensor_.azimuth_fov / 2) return false;
  if (std::abs(std::asin(q.z() / r)) > sensor_.elevation_fov / 2) return false;
  // Hidden when a surface lies between (a point on a surface is not hidden by it).
  return !index_->Raycast(pose.head<3>(), p - pose.head<3>(), r - 2e-3).hit;
}

cv::Mat SonarRenderer::RenderIntensity(const Vector6d& pose, std::uint64_t seed) const {
  const int rows = format_.range_bins, cols = format_.beams;
  const int A = options_.azimuth_rays, E = options_.elevation_rays;
  const Eigen::Matrix3d R = RotationFromEuler(pose[3], pose[4], pose[5]);
  const Eigen::Vector3d c = pose.head<3>();
  const double bin = format_.RangeBin(sensor_);
  cv::Mat surfaces = cv::Mat::zeros(rows, cols, CV_32F);
  const int stride = static_cast<int>(surfaces.step1());
  std::vector<RayEcho> echo(static_cast<std::size_t>(E));
  for (int j = 0; j < cols; ++j) {
    float* column = surfaces.ptr<float>(0) + j;
    for (int a = 0; a < A; ++a) {
      const Eigen::Vector3d* dirs = &directions_[static_cast<std::size_t>((j * A + a) * E)];
      for (int e = 0; e < E; ++e) {
        RayEcho& h = echo[static_cast<std::size_t>(e)];
        h = RayEcho();
        const Eigen::Vector3d d = R * dirs[e];
        const RayHit hit = index_->Raycast(c, d, sensor_.range_max);
        if (!hit.hit || hit.range < sensor_.range_min) continue;
        const auto f = static_cast<std::size_t>(hit.face);
        const SonarMaterial& m = scene_.materials[static_cast<std::size_t>(scene_.face_material[f])];
        const double cos_inc = std::abs(scene_.mesh.face_normals[f].dot(d));
        h.valid = true;
        h.range = hit.range;
        h.surface = scene_.face_surface[f];
        h.normal = scene_.mesh.face_normals[f];
        h.offset = h.normal.dot(hit.point - c);
        h.energy = m.reflectivity * std::pow(cos_inc, m.exponent) * elevation_weight_[static_cast<std::size_t>(e)] *
                   Loss(hit.range);
      }
      // Each ray stands for the elevation interval around it: half of its echo
      // goes to the segment towards each neighbour; a segment between two rays
      // on the same surface spreads over the range between their hits; at a
      // surface's edge the ray's half spreads over the range its face's plane
      // covers up to the interval's boundary.
      const Eigen::Vector3d* bounds = &boundaries_[static_cast<std::size_t>((j * A + a) * (E + 1))];
      const double limit = 1.5 * sensor_.range_max;
      for (int e = 0; e < E; ++e) {
        const RayEcho& h = echo[static_cast<std::size_t>(e)];
        if (!h.valid) continue;
        const double u = (h.range - sensor_.range_min) / bin;
        const bool joins_prev = e > 0 && echo[static_cast<std::size_t>(e - 1)].valid &&
                                echo[static_cast<std::size_t>(e - 1)].surface == h.surface;
        const bool joins_next = e + 1 < E && echo[static_cast<std::size_t>(e + 1)].valid &&
                                echo[static_cast<std::size_t>(e + 1)].surface == h.surface;
        if (!joins_prev) {
          const double rb = PlaneRange(h, R * bounds[e], limit);
          DepositInterval(column, stride, rows, u, (rb - sensor_.range_min) / bin, h.energy / 2);
        }
        if (joins_next) {
          const RayEcho& n = echo[static_cast<std::size_t>(e + 1)];
          DepositInterval(column, stride, rows, u, (n.range - sensor_.range_min) / bin, (h.energy + n.energy) / 2);
        } else {
          const double rb = PlaneRange(h, R * bounds[e + 1], limit);
          DepositInterval(column, stride, rows, u, (rb - sensor_.range_min) / bin, h.energy / 2);
        }
      }
    }
  }
  // Azimuth beam pattern along each row.
  cv::Mat image;
  cv::filter2D(surfaces, image, CV_32F, pattern_, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
  FastRng rng(seed * 0x2545F4914F6CDD1DULL + 0x632BE59BD9B4E019ULL);
  const int looks = options_.speckle_looks;
  for (int i = 0; i < rows; ++i) {
    float* row = image.ptr<float>(i);
    for (int j = 0; j < cols; ++j) {
      if (row[j] > 0) row[j] = static_cast<float>(row[j] * rng.Gamma(looks));
    }
  }
  // Point scatterers: where they lie, spread by the same beam pattern.
  const int K = options_.pattern_radius;
  for (std::size_t s = 0; s < scene_.scatterers.size(); ++s) {
    const Eigen::Vector3d& p = scene_.scatterers[s];
    if (!Sees(pose, p)) continue;
    const Eigen::Vector3d q = R.transpose() * (p - c);
    const double r = q.norm(), theta = std::atan2(q.y(), q.x()), phi = std::asin(q.z() / r);
    const double energy =
        scene_.scatterer_strength[s] * ElevationWeight(phi) * Loss(r) * rng.Gamma(options_.point_looks);
    const double x = format_.AzimuthToColumn(sensor_, theta);
    const double u = (r - sensor_.range_min) / bin;
    double norm = 0;
    for (int j = static_cast<int>(std::ceil(x - K)); j <= static_cast<int>(std::floor(x + K)); ++j) {
      norm += BeamPattern(j - x);
    }
    for (int j = std::max(0, static_cast<int>(std::ceil(x - K)));
         j <= std::min(cols - 1, static_cast<int>(std::floor(x + K))); ++j) {
      DepositInterval(image.ptr<float>(0) + j, stride, rows, u, u, energy * BeamPattern(j - x) / norm);
    }
  }
  if (options_.noise_level > 0) {
    for (int i = 0; i < rows; ++i) {
      float* row = image.ptr<float>(i);
      for (int j = 0; j < cols; ++j) row[j] += static_cast<float>(-options_.noise_level * std::log(rng.Open()));
    }
  }
  return image;
}

cv::Mat SonarRenderer::Encode(const cv::Mat& intensity) const {
  cv::Mat out(intensity.rows, intensity.cols, CV_8U);
  const double dr = options_.dynamic_range_db, gain = options_.gain_db;
  for (int i = 0; i < intensity.rows; ++i) {
    const float* in = intensity.ptr<float>(i);
    std::uint8_t* o = out.ptr<std::uint8_t>(i);
    for (int j = 0; j < intensity.cols; ++j) {
      const double db = 10 * std::log10(std::max(static_cast<double>(in[j]), 1e-30)) + gain;
      o[j] = static_cast<std::uint8_t>(std::lround(std::clamp(255 * (db + dr) / dr, 0.0, 255.0)));
    }
  }
  return out;
}

}  // namespace hull
