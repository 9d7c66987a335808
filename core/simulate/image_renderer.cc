#include "simulate/image_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>

#include "base/error.h"
#include "simulate/random.h"

namespace hull {
namespace {

constexpr int kVeilStep = 8;      // pixels between veil-table nodes
constexpr int kVeilSamples = 64;  // ranges per node, denser near the camera
constexpr int kVeilSubsteps = 6;  // integration steps between two ranges

// 4096 standard normal values: sensor noise draws one per pixel, indexed by a
// hash of (seed, pixel), so that an image is the same on every machine and
// whatever the thread schedule.
const std::array<float, 4096>& NormalTable() {
  static const std::array<float, 4096> table = [] {
    std::array<float, 4096> t{};
    Rng rng(0x6A09E667F3BCC908ULL);
    for (float& v : t) v = static_cast<float>(rng.Gaussian());
    return t;
  }();
  return table;
}

inline std::uint64_t Mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ULL;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBULL;
  x ^= x >> 31;
  return x;
}

}  // namespace

std::vector<Strobe> StrobesInCamera(const std::vector<Strobe>& strobes_cT, const Pose& x_cT_c) {
  const Pose x_c_cT = x_cT_c.Inverse();
  std::vector<Strobe> out = strobes_cT;
  for (Strobe& s : out) {
    s.position = x_c_cT * s.position;
    s.axis = x_c_cT.Rotate(s.axis);
  }
  return out;
}

UnderwaterCamera::UnderwaterCamera(const PinholeIntrinsics& intrinsics, int width, int height,
                                   std::vector<Strobe> strobes_c, const UnderwaterImagingOptions& options)
    : intrinsics_(intrinsics), width_(width), height_(height), options_(options) {
  options_.strobes = strobes_c;
  options_.Check();
  if (width <= 0 || height <= 0) throw OptionError("image size", "must be positive");
  for (const Strobe& s : strobes_c) {
    // beam = exp(-k (1 - cos angle)): 1/2 at the half-power angle.
    const double k = std::log(2.0) / (1.0 - std::cos(s.half_power_angle_deg * M_PI / 180.0));
    lights_.push_back({s.position, s.axis.normalized(), s.intensity, k});
  }
  // The gain: albedo 0.5 facing the camera on its axis at exposure_range.
  const double c = options_.attenuation;
  const Eigen::Vector3d p(0, 0, options_.exposure_range), n(0, 0, -1);
  double e = 0;
  for (const Light& l : lights_) e += l.Irradiance(p, n, c);
  const double radiance = 0.5 / M_PI * e * std::exp(-c * options_.exposure_range);
  if (!(radiance > 0)) throw OptionError("strobes", "no strobe lights the camera's axis at exposure_range");
  gain_ = options_.exposure_level / radiance;
  BuildVeil();
}

double UnderwaterCamera::Light::Irradiance(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double c) const {
  Eigen::Vector3d l = position - p;
  const double r = l.norm();
  if (!(r > 1e-6)) return 0;
  l /= r;
  const double lambert = n.dot(l);
  if (lambert <= 0) return 0;
  // The angle off the beam axis is that of the direction strobe -> p (= -l).
  const double beam = std::exp(-beam_k * (1.0 + l.dot(axis)));
  return intensity * beam * lambert / (r * r) * std::exp(-c * r);
}

void UnderwaterCamera::BuildVeil() {
  veil_nu_ = (width_ - 1) / kVeilStep + 2;
  veil_nv_ = (height_ - 1) / kVeilStep + 2;
  veil_.assign(static_cast<std::size_t>(veil_nu_) * veil_nv_ * (kVeilSamples + 1), 0.0f);
  const double c = options_.attenuation, tmax = options_.max_range;
  tbb::parallel_for(0, veil_nv_, [&](int j) {
    for (int i = 0; i < veil_nu_; ++i) {
      const Eigen::Vector3d d = Ray(i * kVeilStep, j * kVeilStep);
      float* cum = &veil_[(static_cast<std::size_t>(j) * veil_nu_ + i) * (kVeilSamples + 1)];
      double sum = 0, t_prev = 0;
      for (int k = 1; k <= kVeilSamples; ++k) {
        const double t_next = tmax * std::pow(double(k) / kVeilSamples, 2.0);
        const double dt = (t_next - t_prev) / kVeilSubsteps;
        for (int m = 0; m < kVeilSubsteps; ++m) {
          const double t = t_prev + (m + 0.5) * dt;
          const Eigen::Vector3d x = t * d;
          double e = 0;
          for (const Light& light : lights_) {
            const Eigen::Vector3d l = x - light.position;
            const double r2 = l.squaredNorm(), r = std::sqrt(r2);
            const double beam = std::exp(-light.beam_k * (1.0 - l.dot(light.axis) / r));
            e += light.intensity * beam / (r2 + 1e-2) * std::exp(-c * r);
          }
          sum += options_.backscatter * e * std::exp(-c * t) * dt;
        }
        cum[k] = static_cast<float>(sum);
        t_prev = t_next;
      }
    }
  });
}

float UnderwaterCamera::Veil(int u, int v, float range) const {
  const float gu = static_cast<float>(u) / kVeilStep, gv = static_cast<float>(v) / kVeilStep;
  const int i = std::min(static_cast<int>(gu), veil_nu_ - 2), j = std::min(static_cast<int>(gv), veil_nv_ - 2);
  const float fu = gu - i, fv = gv - j;
  const float gk = std::sqrt(std::clamp(range / static_cast<float>(options_.max_range), 0.0f, 1.0f)) * kVeilSamples;
  const int k = std::min(static_cast<int>(gk), kVeilSamples - 1);
  const float fk = gk - k;
  auto at = [&](int ii, int jj) {
    const float* cum = &veil_[(static_cast<std::size_t>(jj) * veil_nu_ + ii) * (kVeilSamples + 1)];
    return cum[k] + fk * (cum[k + 1] - cum[k]);
  };
  return (1 - fv) * ((1 - fu) * at(i, j) + fu * at(i + 1, j)) + fv * ((1 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
}

RayHit UnderwaterCamera::SurfaceAt(const TrueScene& scene, const Pose& x_Mc, double u, double v) const {
  return scene.index().Raycast(x_Mc.translation(), x_Mc.Rotate(Ray(u, v)), options_.max_range);
}

UnderwaterCamera::Response UnderwaterCamera::ResponseAt(const Eigen::Vector3d& p_c, const Eigen::Vector3d& n_c,
                                                        double u, double v) const {
  const double c = options_.attenuation, t = p_c.norm();
  double e = 0;
  for (const Light& l : lights_) e += l.Irradiance(p_c, n_c, c);
  const double x = (u - intrinsics_.cx) / intrinsics_.fx, y = (v - intrinsics_.cy) / intrinsics_.fy;
  const double cos2 = 1.0 / (1.0 + x * x + y * y);
  const double vignette = std::pow(cos2 * cos2, options_.vignetting);
  const int iu = std::clamp(static_cast<int>(std::lround(u)), 0, width_ - 1);
  const int iv = std::clamp(static_cast<int>(std::lround(v)), 0, height_ - 1);
  Response r;
  r.per_albedo = gain_ * vignette * e / M_PI * std::exp(-c * t);
  r.offset = gain_ * vignette * Veil(iu, iv, static_cast<float>(t));
  return r;
}

cv::Mat UnderwaterCamera::Render(const TrueScene& scene, const Pose& x_Mc, std::uint64_t noise_seed, cv::Mat* range,
                                 cv::Mat* signal) const {
  cv::Mat image(height_, width_, CV_8UC1);
  if (range) range->create(height_, width_, CV_32FC1);
  if (signal) signal->create(height_, width_, CV_32FC1);
  const Eigen::Matrix3d R = x_Mc.rotation();
  const Eigen::Vector3d origin = x_Mc.translation();
  const std::size_t ns = lights_.size();
  std::vector<Light> lights_m;
  for (const Light& l : lights_) lights_m.push_back(l.InFrame(x_Mc));
  // The same in single precision, in M's axes about the camera centre.
  struct LightF {
    Eigen::Vector3f position, axis;
    float intensity, beam_k;
  };
  std::vector<LightF> lights_f;
  for (const Light& l : lights_m) {
    lights_f.push_back({(l.position - x_Mc.translation()).cast<float>(), l.axis.cast<float>(),
                        static_cast<float>(l.intensity), static_cast<float>(l.beam_k)});
  }
  constexpr float kInvPi = static_cast<float>(1.0 / M_PI);
  const auto& normal = NormalTable();
  const float c = static_cast<float>(options_.attenuation);
  const float inv_fx = static_cast<float>(1.0 / intrinsics_.fx);
  const float full_well = static_cast<float>(options_.full_well);
  const float read2 = static_cast<float>(options_.read_noise * options_.read_noise);
  const std::uint64_t seed = Mix64(noise_seed + 0x9E3779B97F4A7C15ULL);

  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 4), [&](const tbb::blocked_range<int>& rows) {
    const int w = width_;
    std::vector<Eigen::Vector3f> dirs(static_cast<std::size_t>(w));
    std::vector<RayHit> hits(static_cast<std::size_t>(w));
    std::vector<Eigen::Vector3d> points;
    std::vector<int> lit_pixel;
    std::unique_ptr<bool[]> blocked(new bool[static_cast<std::size_t>(w)]);
    std::vector<float> shade(static_cast<std::size_t>(w) * ns);
    std::vector<Eigen::Vector3f> normals(static_cast<std::size_t>(w));
    std::vector<float> albedo(static_cast<std::size_t>(w)), bx, by, bz, bnx, bny, bnz, bfp, batch_out;
    std::vector<int> hull_pixels;
    for (int v = rows.begin(); v != rows.end(); ++v) {
      for (int u = 0; u < w; ++u) dirs[static_cast<std::size_t>(u)] = (R * Ray(u, v)).cast<float>();
      scene.index().RaycastFan(origin, dirs.data(), w, options_.max_range, hits.data());
      // Shadows: which hit points each strobe reaches.
      std::fill(shade.begin(), shade.end(), 1.0f);
      if (options_.shadows) {
        points.clear();
        lit_pixel.clear();
        for (int u = 0; u < w; ++u) {
          if (!hits[static_cast<std::size_t>(u)].hit) continue;
          points.push_back(hits[static_cast<std::size_t>(u)].point);
          lit_pixel.push_back(u);
        }
        for (std::size_t s = 0; s < ns; ++s) {
          scene.index().OccludedToward(points.data(), static_cast<int>(points.size()), lights_m[s].position, 1e-3,
                                       blocked.get());
          for (std::size_t i = 0; i < points.size(); ++i) {
            if (blocked[i]) shade[static_cast<std::size_t>(lit_pixel[i]) * ns + s] = 0.0f;
          }
        }
      }
      // Albedo: hull pixels in one batch (vectorised), object pixels one by one.
      hull_pixels.clear();
      for (auto* a : {&bx, &by, &bz, &bnx, &bny, &bnz, &bfp}) a->clear();
      for (int u = 0; u < w; ++u) {
        const RayHit& h = hits[static_cast<std::size_t>(u)];
        if (!h.hit) continue;
        const Eigen::Vector3f& d = dirs[static_cast<std::size_t>(u)];
        Eigen::Vector3f n = scene.ShadingNormal(h.face, h.point);
        if (n.dot(d) > 0) n = -n;  // seen from behind: shade the side facing the camera
        normals[static_cast<std::size_t>(u)] = n;
        const float facing = std::max(-n.dot(d), 0.05f);
        const float footprint = static_cast<float>(h.range) * inv_fx / std::sqrt(facing);
        const Eigen::Vector3f p = h.point.cast<float>();
        if (const TrueObject* object = scene.ObjectOfFace(h.face)) {
          albedo[static_cast<std::size_t>(u)] = scene.albedo().OnObject(*object, p, n, footprint);
          continue;
        }
        hull_pixels.push_back(u);
        bx.push_back(p.x());
        by.push_back(p.y());
        bz.push_back(p.z());
        bnx.push_back(n.x());
        bny.push_back(n.y());
        bnz.push_back(n.z());
        bfp.push_back(footprint);
      }
      batch_out.resize(hull_pixels.size());
      scene.albedo().HullBatch(bx.data(), by.data(), bz.data(), bnx.data(), bny.data(), bnz.data(), bfp.data(),
                               static_cast<int>(hull_pixels.size()), batch_out.data());
      for (std::size_t i = 0; i < hull_pixels.size(); ++i) {
        albedo[static_cast<std::size_t>(hull_pixels[i])] = batch_out[i];
      }

      std::uint8_t* out = image.ptr<std::uint8_t>(v);
      float* range_row = range ? range->ptr<float>(v) : nullptr;
      float* signal_row = signal ? signal->ptr<float>(v) : nullptr;
      const float y = static_cast<float>((v - intrinsics_.cy) / intrinsics_.fy);
      for (int u = 0; u < w; ++u) {
        const RayHit& h = hits[static_cast<std::size_t>(u)];
        const float t = h.hit ? static_cast<float>(h.range) : static_cast<float>(options_.max_range);
        float radiance = Veil(u, v, t);
        if (h.hit) {
          // Strobe light in single precision, relative to the camera centre.
          const Eigen::Vector3f& n = normals[static_cast<std::size_t>(u)];
          const Eigen::Vector3f p = t * dirs[static_cast<std::size_t>(u)];
          float e = 0;
          for (std::size_t s = 0; s < ns; ++s) {
            if (shade[static_cast<std::size_t>(u) * ns + s] == 0) continue;
            const LightF& light = lights_f[s];
            Eigen::Vector3f l = light.position - p;
            const float r2 = l.squaredNorm(), inv_r = 1.0f / std::sqrt(r2);
            l *= inv_r;
            const float lambert = n.dot(l);
            if (lambert <= 0) continue;
            e += light.intensity * std::exp(-light.beam_k * (1.0f + l.dot(light.axis)) - c / inv_r) * lambert / r2;
          }
          radiance += albedo[static_cast<std::size_t>(u)] * kInvPi * e * std::exp(-c * t);
        }
        if (range_row) range_row[u] = h.hit ? t : 0.0f;
        // Natural vignetting: cos^4 of the angle off the axis.
        const float x = static_cast<float>((u - intrinsics_.cx) / intrinsics_.fx);
        const float cos2 = 1.0f / (1.0f + x * x + y * y);
        const float vignette =
            options_.vignetting == 1.0 ? cos2 * cos2 : std::pow(cos2 * cos2, static_cast<float>(options_.vignetting));
        const float exposure = std::max(0.0f, static_cast<float>(gain_) * radiance * vignette);
        if (signal_row) signal_row[u] = exposure;
        const float electrons = exposure * full_well;
        const std::uint64_t k = Mix64(seed ^ (static_cast<std::uint64_t>(v) * static_cast<std::uint64_t>(w) + u));
        const float noisy = electrons + std::sqrt(electrons + read2) * normal[k & 4095u];
        out[u] = static_cast<std::uint8_t>(std::min(std::max(noisy / full_well * 255.0f, 0.0f), 255.0f) + 0.5f);
      }
    }
  });
  return image;
}

}  // namespace hull
