#include "simulate/image_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
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

namespace {

// A strobe in single precision, in M's axes about the camera centre.
struct LightF {
  float px, py, pz, ax, ay, az, intensity, beam_k;
};

// e^x for x <= 0 (clamped at -87) within a few ulp: Cephes' expf in plain
// single-precision arithmetic, so that a loop of it vectorises; the same
// result in every build (no FMA contraction in ISO C++ mode).
inline float ExpNonPositive(float x) {
  x = std::max(x, -87.0f);
  const float t = x * 1.44269504088896341f + 0.5f;
  auto n = static_cast<std::int32_t>(t);
  n -= static_cast<std::int32_t>(t < static_cast<float>(n));  // floor(t)
  const float fn = static_cast<float>(n);
  const float r = (x - fn * 0.693359375f) - fn * -2.12194440e-4f;
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  const float e = p * (r * r) + r + 1.0f;
  const std::uint32_t bits = static_cast<std::uint32_t>(n + 127) << 23;
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return e * scale;
}

// The strobe light reflected by m hit points (structure of arrays): the
// pixel's ray direction d (unit, M's axes), range t, shading normal n,
// albedo, and per strobe whether it reaches the point (lit[s * stride + i],
// 1 or 0); radiance[i] = albedo / pi * sum_s lit I_s beam max(0, n.l) / d_s^2
// exp(-c (d_s + t)).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void ShadeHits(const float* dx, const float* dy, const float* dz, const float* t, const float* nx, const float* ny,
               const float* nz, const float* albedo, const float* lit, std::size_t stride, const LightF* lights,
               std::size_t ns, float c, int m, float* radiance) {
  constexpr float kInvPi = static_cast<float>(1.0 / M_PI);
  for (int i = 0; i < m; ++i) radiance[i] = 0.0f;
  for (std::size_t s = 0; s < ns; ++s) {
    const LightF L = lights[s];
    const float* lit_s = lit + s * stride;
    for (int i = 0; i < m; ++i) {
      const float ti = t[i];
      float lx = L.px - ti * dx[i], ly = L.py - ti * dy[i], lz = L.pz - ti * dz[i];
      const float r2 = lx * lx + ly * ly + lz * lz;
      const float r = std::sqrt(r2), inv_r = 1.0f / r;
      lx *= inv_r;
      ly *= inv_r;
      lz *= inv_r;
      const float lambert = std::max(nx[i] * lx + ny[i] * ly + nz[i] * lz, 0.0f);
      const float cos_axis = lx * L.ax + ly * L.ay + lz * L.az;
      const float e = ExpNonPositive(-L.beam_k * (1.0f + cos_axis) - c * (r + ti));
      radiance[i] += lit_s[i] * L.intensity * e * lambert / r2;
    }
  }
  for (int i = 0; i < m; ++i) radiance[i] *= albedo[i] * kInvPi;
}

// The sensor on one image row of w pixels: the backscatter veil up to each
// pixel's range t (bilinear in the table's nodes veil0 (the row above, nu
// nodes of kVeilSamples + 1) and the next row (fv of the way down), linear
// in sqrt(t / max_range)), plus the strobe light, times vignetting and the
// gain: the exposure (signal, if not null); shot and read noise drawn from
// the normal table by a hash of (seed, pixel0 + u); 8-bit grey. scratch
// holds 3 w floats.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void SensorRow(int w, const float* t, const float* radiance, const float* vignette, const float* veil0, int nu,
               float fv, float max_range, float gain, float full_well, float read2, const float* normal,
               std::uint64_t seed, std::uint64_t pixel0, float* signal, float* scratch, std::uint8_t* out) {
  constexpr std::size_t kStride = kVeilSamples + 1;
  const float* veil1 = veil0 + static_cast<std::size_t>(nu) * kStride;
  float* electrons = scratch;
  float* spread = scratch + w;
  float* grey = scratch + 2 * w;
  for (int u = 0; u < w; ++u) {
    const float gu = static_cast<float>(u) / kVeilStep;
    const int i = std::min(static_cast<int>(gu), nu - 2);
    const float fu = gu - static_cast<float>(i);
    const float gk = std::sqrt(std::clamp(t[u] / max_range, 0.0f, 1.0f)) * kVeilSamples;
    const int k = std::min(static_cast<int>(gk), kVeilSamples - 1);
    const float fk = gk - static_cast<float>(k);
    const std::size_t o0 = static_cast<std::size_t>(i) * kStride + static_cast<std::size_t>(k), o1 = o0 + kStride;
    const float a00 = veil0[o0] + fk * (veil0[o0 + 1] - veil0[o0]);
    const float a10 = veil0[o1] + fk * (veil0[o1 + 1] - veil0[o1]);
    const float a01 = veil1[o0] + fk * (veil1[o0 + 1] - veil1[o0]);
    const float a11 = veil1[o1] + fk * (veil1[o1 + 1] - veil1[o1]);
    const float veil = (1 - fv) * ((1 - fu) * a00 + fu * a10) + fv * ((1 - fu) * a01 + fu * a11);
    electrons[u] = std::max(0.0f, gain * (veil + radiance[u]) * vignette[u]);
  }
  if (signal) std::copy(electrons, electrons + w, signal);
  for (int u = 0; u < w; ++u) {
    electrons[u] *= full_well;
    spread[u] = std::sqrt(electrons[u] + read2);
  }
  for (int u = 0; u < w; ++u) {
    const std::uint64_t key = Mix64(seed ^ (pixel0 + static_cast<std::uint64_t>(u)));
    grey[u] = spread[u] * normal[key & 4095u];
  }
  const float to_grey = 255.0f / full_well;
  for (int u = 0; u < w; ++u) {
    const float noisy = electrons[u] + grey[u];
    out[u] = static_cast<std::uint8_t>(std::min(std::max(noisy * to_grey, 0.0f), 255.0f) + 0.5f);
  }
}
}  // namespace

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
  std::vector<LightF> lights_f;
  for (const Light& l : lights_m) {
    const Eigen::Vector3f pos = (l.position - origin).cast<float>(), axis = l.axis.cast<float>();
    lights_f.push_back({pos.x(), pos.y(), pos.z(), axis.x(), axis.y(), axis.z(), static_cast<float>(l.intensity),
                        static_cast<float>(l.beam_k)});
  }
  const auto& normal = NormalTable();
  const float c = static_cast<float>(options_.attenuation);
  const float max_range = static_cast<float>(options_.max_range);
  const float inv_fx = static_cast<float>(1.0 / intrinsics_.fx);
  const float full_well = static_cast<float>(options_.full_well);
  const float read2 = static_cast<float>(options_.read_noise * options_.read_noise);
  const float gain = static_cast<float>(gain_);
  const bool cos4 = options_.vignetting == 1.0;
  const float vignetting = static_cast<float>(options_.vignetting);
  const std::uint64_t seed = Mix64(noise_seed + 0x9E3779B97F4A7C15ULL);
  // The pinhole's x = (u - cx) / fx of every column.
  std::vector<double> xs(static_cast<std::size_t>(width_));
  for (int u = 0; u < width_; ++u) xs[static_cast<std::size_t>(u)] = (u - intrinsics_.cx) / intrinsics_.fx;

  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 4), [&](const tbb::blocked_range<int>& rows) {
    const int w = width_;
    const std::size_t W = static_cast<std::size_t>(w);
    std::vector<Eigen::Vector3f> dirs(W);
    std::vector<RayHit> hits(W);
    std::vector<float> vignette(W), radiance(W), trange(W), scratch(3 * W);
    std::vector<Eigen::Vector3d> points;
    std::unique_ptr<bool[]> blocked(new bool[W]);
    // The hit pixels of a row, structure of arrays.
    std::vector<int> hit_u(W);
    std::vector<float> hdx(W), hdy(W), hdz(W), ht(W), hnx(W), hny(W), hnz(W), halbedo(W), hlit(W * ns), hrad(W);
    std::vector<int> hull_hits(W), object_hits(W);
    std::vector<const TrueObject*> objects(W);
    std::vector<float> ox(W), oy(W), oz(W), onx(W), ony(W), onz(W), ofp(W);
    std::vector<float> bx(W), by(W), bz(W), bnx(W), bny(W), bnz(W), bfp(W), batch_out(W);
    for (int v = rows.begin(); v != rows.end(); ++v) {
      const double y = (v - intrinsics_.cy) / intrinsics_.fy;
      const Eigen::Vector3d row_base = R.col(1) * y + R.col(2);
      for (int u = 0; u < w; ++u) {
        const double x = xs[static_cast<std::size_t>(u)];
        const double q = 1.0 / (x * x + y * y + 1.0);  // cos^2 of the angle off the axis
        dirs[static_cast<std::size_t>(u)] = ((R.col(0) * x + row_base) * std::sqrt(q)).cast<float>();
        const float cos2 = static_cast<float>(q);
        vignette[static_cast<std::size_t>(u)] = cos4 ? cos2 * cos2 : std::pow(cos2 * cos2, vignetting);
      }
      scene.index().RaycastFan(origin, dirs.data(), w, options_.max_range, hits.data());
      int m = 0;
      for (int u = 0; u < w; ++u) {
        if (hits[static_cast<std::size_t>(u)].hit) hit_u[static_cast<std::size_t>(m++)] = u;
      }
      const std::size_t M = static_cast<std::size_t>(m);
      // Shadows: which hit points each strobe reaches.
      std::fill(hlit.begin(), hlit.begin() + static_cast<std::ptrdiff_t>(M * ns), 1.0f);
      if (options_.shadows && m > 0) {
        points.resize(M);
        for (std::size_t i = 0; i < M; ++i) points[i] = hits[static_cast<std::size_t>(hit_u[i])].point;
        for (std::size_t s = 0; s < ns; ++s) {
          scene.index().OccludedToward(points.data(), m, lights_m[s].position, 1e-3, blocked.get());
          for (std::size_t i = 0; i < M; ++i) {
            if (blocked[i]) hlit[s * M + i] = 0.0f;
          }
        }
      }
      // Geometry of the hits; albedo: hull pixels in one batch along the row,
      // object pixels in another (both vectorised).
      int nb = 0, no = 0;  // hull and object hits in the albedo batches
      for (std::size_t i = 0; i < M; ++i) {
        const std::size_t u = static_cast<std::size_t>(hit_u[i]);
        const RayHit& h = hits[u];
        const Eigen::Vector3f& d = dirs[u];
        Eigen::Vector3f n = scene.ShadingNormal(h.face, h.point);
        if (n.dot(d) > 0) n = -n;  // seen from behind: shade the side facing the camera
        const float facing = std::max(-n.dot(d), 0.05f);
        const float t = static_cast<float>(h.range);
        const float footprint = t * inv_fx / std::sqrt(facing);
        const Eigen::Vector3f p = h.point.cast<float>();
        hdx[i] = d.x();
        hdy[i] = d.y();
        hdz[i] = d.z();
        ht[i] = t;
        hnx[i] = n.x();
        hny[i] = n.y();
        hnz[i] = n.z();
        if (const TrueObject* object = scene.ObjectOfFace(h.face)) {
          const std::size_t o = static_cast<std::size_t>(no++);
          object_hits[o] = static_cast<int>(i);
          objects[o] = object;
          ox[o] = p.x();
          oy[o] = p.y();
          oz[o] = p.z();
          onx[o] = n.x();
          ony[o] = n.y();
          onz[o] = n.z();
          ofp[o] = footprint;
          continue;
        }
        const std::size_t b = static_cast<std::size_t>(nb++);
        hull_hits[b] = static_cast<int>(i);
        bx[b] = p.x();
        by[b] = p.y();
        bz[b] = p.z();
        bnx[b] = n.x();
        bny[b] = n.y();
        bnz[b] = n.z();
        bfp[b] = footprint;
      }
      scene.albedo().HullRow(bx.data(), by.data(), bz.data(), bnx.data(), bny.data(), bnz.data(), bfp.data(), nb,
                             batch_out.data());
      for (std::size_t k = 0; k < static_cast<std::size_t>(nb); ++k) {
        halbedo[static_cast<std::size_t>(hull_hits[k])] = batch_out[k];
      }
      scene.albedo().ObjectBatch(objects.data(), ox.data(), oy.data(), oz.data(), onx.data(), ony.data(), onz.data(),
                                 ofp.data(), no, batch_out.data());
      for (std::size_t k = 0; k < static_cast<std::size_t>(no); ++k) {
        halbedo[static_cast<std::size_t>(object_hits[k])] = batch_out[k];
      }
      // Strobe light, in single precision relative to the camera centre.
      ShadeHits(hdx.data(), hdy.data(), hdz.data(), ht.data(), hnx.data(), hny.data(), hnz.data(), halbedo.data(),
                hlit.data(), M, lights_f.data(), ns, c, m, hrad.data());
      std::fill(radiance.begin(), radiance.end(), 0.0f);
      for (std::size_t i = 0; i < M; ++i) radiance[static_cast<std::size_t>(hit_u[i])] = hrad[i];

      // Ranges (max_range where nothing is hit).
      float* range_row = range ? range->ptr<float>(v) : nullptr;
      std::fill(trange.begin(), trange.end(), max_range);
      for (std::size_t i = 0; i < M; ++i) trange[static_cast<std::size_t>(hit_u[i])] = ht[i];
      if (range_row) {
        for (int u = 0; u < w; ++u) range_row[u] = hits[static_cast<std::size_t>(u)].hit ? trange[u] : 0.0f;
      }
      // The veil table's rows above and below the image row.
      const float gv = static_cast<float>(v) / kVeilStep;
      const int j = std::min(static_cast<int>(gv), veil_nv_ - 2);
      const float* veil0 =
          &veil_[static_cast<std::size_t>(j) * static_cast<std::size_t>(veil_nu_) * (kVeilSamples + 1)];
      SensorRow(w, trange.data(), radiance.data(), vignette.data(), veil0, veil_nu_, gv - static_cast<float>(j),
                max_range, gain, full_well, read2, normal.data(), seed, static_cast<std::uint64_t>(v) * W,
                signal ? signal->ptr<float>(v) : nullptr, scratch.data(), image.ptr<std::uint8_t>(v));
    }
  });
  return image;
}

}  // namespace hull
