#include "mosaic/photomosaic.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "base/error.h"
#include "geometry/mesh_index.h"
#include "mosaic/mosaic_camera.h"
#include "mosaic/photomosaic_internal.h"
#include "simulate/survey_imaging.h"

namespace hull {
namespace {

using mosaic_internal::Barycentric;
using mosaic_internal::Candidate;
using mosaic_internal::Chart;
using mosaic_internal::ChooseViews;
using mosaic_internal::FaceNeighbours;
using mosaic_internal::FaceSamples;
using mosaic_internal::FeatherWeights;
using mosaic_internal::FlatChart;
using mosaic_internal::kSamples;
using mosaic_internal::PackShelves;
using mosaic_internal::Sample;
using mosaic_internal::SeenFaces;
using mosaic_internal::SplitLongEdges;
using mosaic_internal::ViewWeights;

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Nearest-rank percentile (q in [0, 1]) of a non-empty sample.
double Percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const std::size_t k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
}

}  // namespace

Eigen::Vector2f MosaicResult::Uv(int face, int corner) const {
  const Eigen::Vector2f& c = corners[static_cast<std::size_t>(face)][static_cast<std::size_t>(corner)];
  return {c.x() / static_cast<float>(atlas.cols), 1.0f - c.y() / static_cast<float>(atlas.rows)};
}

MosaicResult BuildMosaic(const MosaicInput& in, const MosaicOptions& options, Progress& progress,
                         const TrueScene* truth) {
  options.Check();
  if (in.model.empty()) throw std::invalid_argument("BuildMosaic: the model has no faces");
  if (in.poses.size() != in.keyframes.size() || in.servo.size() != in.keyframes.size()) {
    throw std::invalid_argument("BuildMosaic: keyframes, poses and servo angles differ in number");
  }
  if (!in.has_image || !in.read_image) throw std::invalid_argument("BuildMosaic: no image access");
  tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
  const auto t_start = Clock::now();

  MosaicResult R;
  R.options = options;
  R.normalisation = options.normalisation;
  R.model = in.model;
  TriangleMesh& model = R.model;
  model.ComputeNormals();

  // ---- Views.
  const bool stereo = in.manifest.camera.stereo();
  std::vector<MosaicCamera> cameras;
  std::vector<std::size_t> view_keyframe;  // keyframe index of each view
  for (std::size_t k = 0; k < in.keyframes.size(); ++k) {
    for (bool b : {false, true}) {
      if (b && !stereo) continue;
      if (!in.has_image(k, b)) continue;
      cameras.emplace_back(in.manifest, in.poses[k], in.servo[k], in.x_s_cT, in.x_gM, b);
      view_keyframe.push_back(k);
      MosaicView v;
      v.keyframe = in.keyframes[k];
      v.bottom = b;
      v.x_Mc = cameras.back().x_Mc();
      R.views.push_back(v);
    }
  }
  const int nviews = static_cast<int>(cameras.size());
  if (nviews == 0) throw std::invalid_argument("the survey has no images to texture the model with");
  // Faces within max_range of the cameras' bounding box get their long edges split.
  {
    Eigen::AlignedBox3d box;
    for (const MosaicCamera& c : cameras) box.extend(c.centre());
    SplitLongEdges(model, options.max_edge, [&](int f) {
      const Face& F = model.faces[static_cast<std::size_t>(f)];
      const Eigen::Vector3d g = model.FaceCentroid(f);
      double r = 0;
      for (int i = 0; i < 3; ++i) r = std::max(r, (model.vertices[static_cast<std::size_t>(F[i])] - g).norm());
      return box.exteriorDistance(g) <= options.max_range + r;
    });
  }
  const std::size_t nf = model.num_faces(), nv = model.num_vertices();
  const MeshIndex index(model);
  const int W = in.manifest.camera.width, H = in.manifest.camera.height;
  const bool use_model = options.normalisation != MosaicNormalisation::kNone;
  std::unique_ptr<UnderwaterCamera> photo_top, photo_bottom;
  if (use_model) {
    photo_top = MakeSurveyCamera(in.manifest, options.photometry, false);
    if (stereo) photo_bottom = MakeSurveyCamera(in.manifest, options.photometry, true);
  }
  // Each view's x_Mc rotation as a matrix, made once (not per sample).
  std::vector<Eigen::Matrix3d> rotation(cameras.size());
  for (std::size_t vi = 0; vi < cameras.size(); ++vi) rotation[vi] = cameras[vi].x_Mc().rotation();
  // Normalised value of a pixel sample (rot: the view's rotation): albedo
  // estimate (model) or the raw share of full scale.
  auto normalise = [&](const MosaicCamera& cam, const Eigen::Matrix3d& rot, const Eigen::Vector3d& p_c,
                       const Eigen::Vector3d& n_M, const Eigen::Vector2d& uv, float* px, int ch) {
    if (!use_model) return;
    Eigen::Vector3d n_c = rot.transpose() * n_M;
    if (n_c.dot(p_c) > 0) n_c = -n_c;  // the side facing the camera
    const UnderwaterCamera& u = cam.bottom() ? *photo_bottom : *photo_top;
    const UnderwaterCamera::Response r = u.ResponseAt(p_c, n_c, uv.x(), uv.y());
    const float k = r.per_albedo > 1e-9 ? static_cast<float>(1.0 / r.per_albedo) : 0.0f;
    for (int c = 0; c < ch; ++c) px[c] = (px[c] - static_cast<float>(r.offset)) * k;
  };

  // ---- Candidates: visible, unoccluded, in the image, near and frontal enough.
  progress.Update(0.0, "visibility of " + std::to_string(nf) + " faces in " + std::to_string(nviews) + " images");
  const auto t_vis = Clock::now();
  mosaic_internal::Visibility vis;
  arena.execute([&] { vis = SeenFaces(model, index, cameras, W, H, options, progress); });
  std::vector<std::vector<std::pair<int, float>>>& seen = vis.seen;  // view -> (face, score)
  progress.ThrowIfCancelled();
  std::vector<std::vector<Candidate>> cand(nf);
  for (int vi = 0; vi < nviews; ++vi) {
    R.views[static_cast<std::size_t>(vi)].candidates = static_cast<int>(seen[static_cast<std::size_t>(vi)].size());
    for (const auto& [f, s] : seen[static_cast<std::size_t>(vi)])
      cand[static_cast<std::size_t>(f)].push_back({vi, s, 0});
  }
  seen.clear();
  R.summary.visibility_pairs_near = vis.near;
  R.summary.visibility_pairs_projected = vis.projected;
  R.summary.visibility_rays = vis.rays;
  R.summary.seconds.visibility = Since(t_vis);

  // ---- Labelling: best view, then Potts smoothing by iterated conditional modes.
  progress.Update(0.2, "choosing a view per face");
  const auto t_label = Clock::now();
  // Face adjacency over shared edges.
  const std::vector<std::array<int, 3>> nbr = FaceNeighbours(model);
  R.faces = ChooseViews(cand, nbr, options);
  for (std::size_t f = 0; f < nf; ++f) {
    MosaicFace& F = R.faces[f];
    if (F.view < 0) continue;
    for (const Candidate& c : cand[f]) {
      if (c.view == F.view) F.score = c.score;
    }
    ++R.views[static_cast<std::size_t>(F.view)].faces;
    for (int i = 0; i < 3; ++i) {
      const int n = nbr[f][static_cast<std::size_t>(i)];
      if (n < 0 || static_cast<std::size_t>(n) < f) continue;
      ++R.summary.interior_edges;
      const int nvw = R.faces[static_cast<std::size_t>(n)].view;
      if (nvw >= 0 && nvw != F.view) ++R.summary.seam_edges;
    }
  }
  R.summary.seconds.labelling = Since(t_label);

  // ---- Feathering weights per vertex: the views of the incident faces by
  // area, smoothed over feather_rings one-rings.
  const std::vector<ViewWeights> vw = FeatherWeights(model, R.faces, options);

  // ---- Atlas layout.
  progress.Update(0.3, "packing the atlas");
  double texel = options.texel_size;
  std::vector<Chart> charts(nf);
  std::vector<int> order;
  for (std::size_t f = 0; f < nf; ++f) {
    if (R.faces[f].view >= 0) order.push_back(static_cast<int>(f));
  }
  int atlas_w = 0, atlas_h = 0;
  constexpr int kSpare = 4;  // a flat cell for untextured faces
  for (int attempt = 0;; ++attempt) {
    double area = 0;
    int widest = kSpare;
    for (int f : order) {
      charts[static_cast<std::size_t>(f)] = FlatChart(model, f, texel);
      const Chart& c = charts[static_cast<std::size_t>(f)];
      area += static_cast<double>(c.w) * c.h;
      widest = std::max(widest, c.w);
    }
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const Chart &ca = charts[static_cast<std::size_t>(a)], &cb = charts[static_cast<std::size_t>(b)];
      return ca.h != cb.h ? ca.h > cb.h : a < b;
    });
    atlas_w = std::max(widest, static_cast<int>(std::ceil(std::sqrt(area * 1.05 + kSpare * kSpare))));
    atlas_w = (atlas_w + 3) / 4 * 4;
    atlas_h = PackShelves(charts, order, atlas_w) + kSpare;
    if (atlas_w <= options.max_atlas_size && atlas_h <= options.max_atlas_size) break;
    if (attempt > 30) throw std::runtime_error("the photomosaic atlas does not fit in max_atlas_size");
    texel *= 1.25;
  }
  R.summary.texel_size = texel;
  const int spare_y = atlas_h - kSpare;
  {
    double used = 0;
    for (int f : order)
      used += static_cast<double>(charts[static_cast<std::size_t>(f)].w) * charts[static_cast<std::size_t>(f)].h;
    R.summary.atlas_fill = used / (static_cast<double>(atlas_w) * atlas_h);
  }
  R.corners.assign(nf, {});
  for (std::size_t f = 0; f < nf; ++f) {
    if (R.faces[f].view < 0) {
      // Untextured: all corners on the spare cell's centre (filled grey).
      for (auto& c : R.corners[f]) c = Eigen::Vector2f(kSpare / 2.0f, static_cast<float>(spare_y) + kSpare / 2.0f);
      continue;
    }
    R.summary.textured_area += model.FaceArea(static_cast<int>(f));
    const Chart& c = charts[f];
    for (int i = 0; i < 3; ++i) {
      R.corners[f][static_cast<std::size_t>(i)] =
          (c.local[static_cast<std::size_t>(i)] + Eigen::Vector2d(c.x, c.y)).cast<float>();
    }
  }

  // Which faces each view textures (its own faces and those blending into it).
  std::vector<std::vector<int>> view_faces(static_cast<std::size_t>(nviews));
  std::vector<std::vector<int>> face_views(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    if (R.faces[f].view < 0) continue;
    std::vector<int> vs = {R.faces[f].view};
    for (int i = 0; i < 3 && options.feather_rings > 0; ++i) {
      for (int v : vw[static_cast<std::size_t>(model.faces[f][i])].view) {
        if (v < 0) continue;
        const bool visible =
            std::any_of(cand[f].begin(), cand[f].end(), [&](const Candidate& c) { return c.view == v; });
        if (visible && std::find(vs.begin(), vs.end(), v) == vs.end()) vs.push_back(v);
      }
    }
    for (int v : vs) view_faces[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
    face_views[f] = std::move(vs);
  }

  // ---- Images, one pass per stage, in chunks of views in order: a chunk's
  // images are read in parallel (TBB), checked in view order, then worked on
  // in parallel; decoded images are kept for the second pass (gains, then
  // texturing) within the budget.
  // Every image as the first one: its size, and 1 or 3 channels. A
  // mismatch names both files.
  int channels = 0, first_view = -1;
  const auto name_of = [&](int vi) {
    const auto v = static_cast<std::size_t>(vi);
    const std::string name = in.image_name ? in.image_name(view_keyframe[v], cameras[v].bottom()) : "";
    return name.empty() ? "the " + std::string(cameras[v].bottom() ? "bottom" : "top") + " image of keyframe " +
                              std::to_string(R.views[v].keyframe)
                        : name;
  };
  auto check_image = [&](const cv::Mat& img, int vi) {
    if (img.empty() || img.cols != W || img.rows != H) {
      throw InputError({name_of(vi), 0, 0, ""}, "the image is " + std::to_string(img.cols) + "x" +
                                                    std::to_string(img.rows) + "; the camera is " + std::to_string(W) +
                                                    "x" + std::to_string(H));
    }
    if (channels == 0) channels = img.channels(), first_view = vi;
    if (img.channels() != 1 && img.channels() != 3) {
      throw InputError({name_of(vi), 0, 0, ""},
                       std::to_string(img.channels()) + " channels; the photomosaic takes grey or colour (1 or 3)");
    }
    if (img.channels() != channels) {
      throw InputError({name_of(vi), 0, 0, ""}, std::to_string(img.channels()) + " channels, where " +
                                                    name_of(first_view) + " has " + std::to_string(channels) +
                                                    ": the images mix channel counts");
    }
  };
  std::vector<cv::Mat> cache(static_cast<std::size_t>(nviews));
  std::size_t cached_bytes = 0;
  const std::size_t cache_budget = options.normalisation == MosaicNormalisation::kModelAndGains
                                       ? static_cast<std::size_t>(options.image_cache_mb) << 20
                                       : 0;
  constexpr int kChunk = 64;  // views per chunk
  auto for_each_chunk = [&](double p0, double p1, const char* what,
                            const std::function<void(int, int, const std::vector<cv::Mat>&)>& fn) {
    for (int v0 = 0; v0 < nviews; v0 += kChunk) {
      progress.ThrowIfCancelled();
      const int v1 = std::min(nviews, v0 + kChunk);
      std::vector<cv::Mat> images(static_cast<std::size_t>(v1 - v0));
      std::vector<std::exception_ptr> failed(images.size());
      arena.execute([&] {
        tbb::parallel_for(v0, v1, [&](int vi) {
          const auto i = static_cast<std::size_t>(vi - v0);
          if (!cache[static_cast<std::size_t>(vi)].empty()) {
            images[i] = cache[static_cast<std::size_t>(vi)];
            return;
          }
          try {
            images[i] = in.read_image(view_keyframe[static_cast<std::size_t>(vi)],
                                      cameras[static_cast<std::size_t>(vi)].bottom());
          } catch (...) {
            failed[i] = std::current_exception();
          }
        });
      });
      for (int vi = v0; vi < v1; ++vi) {
        const auto i = static_cast<std::size_t>(vi - v0);
        if (failed[i]) std::rethrow_exception(failed[i]);
        const cv::Mat& img = images[i];
        check_image(img, vi);
        const std::size_t bytes = img.total() * img.elemSize();
        if (cache[static_cast<std::size_t>(vi)].empty() && cached_bytes + bytes <= cache_budget) {
          cache[static_cast<std::size_t>(vi)] = img;
          cached_bytes += bytes;
        }
      }
      fn(v0, v1, images);
      progress.Update(p0 + (p1 - p0) * v1 / nviews,
                      std::string(what) + " " + std::to_string(v1) + "/" + std::to_string(nviews));
    }
  };

  // ---- Gains: per image, from the faces several images see (robust least
  // squares on ln values, a prior holding ln gain near 0).
  const auto t_gain = Clock::now();
  if (options.normalisation == MosaicNormalisation::kModelAndGains) {
    // Per view, the faces it sees and is a candidate for (for the overlaps).
    std::vector<std::vector<std::pair<int, int>>> cand_of_view(static_cast<std::size_t>(nviews));  // (face, slot)
    for (std::size_t f = 0; f < nf; ++f) {
      if (cand[f].size() < 2) continue;
      for (std::size_t s = 0; s < cand[f].size(); ++s) {
        cand_of_view[static_cast<std::size_t>(cand[f][s].view)].emplace_back(static_cast<int>(f), static_cast<int>(s));
      }
    }
    // Every (face, slot) belongs to one view: the views of a chunk run in parallel.
    for_each_chunk(0.3, 0.6, "gains: image", [&](int v0, int v1, const std::vector<cv::Mat>& images) {
      arena.execute([&] {
        tbb::parallel_for(v0, v1, [&](int vi) {
          const cv::Mat& img = images[static_cast<std::size_t>(vi - v0)];
          const MosaicCamera& cam = cameras[static_cast<std::size_t>(vi)];
          for (const auto& [f, slot] : cand_of_view[static_cast<std::size_t>(vi)]) {
            double sum = 0;
            int n = 0;
            for (const Eigen::Vector3d& p : FaceSamples(model, f)) {
              Eigen::Vector2d uv;
              Eigen::Vector3d pc;
              float px[3];
              if (!cam.Project(p, &uv, &pc) || !Sample(img, uv.x(), uv.y(), px)) continue;
              normalise(cam, rotation[static_cast<std::size_t>(vi)], pc,
                        model.face_normals[static_cast<std::size_t>(f)], uv, px, channels);
              float lum = 0;
              for (int c = 0; c < channels; ++c) lum += px[c];
              sum += lum / channels;
              ++n;
            }
            cand[static_cast<std::size_t>(f)][static_cast<std::size_t>(slot)].value =
                n == kSamples ? static_cast<float>(sum / n) : 0.0f;
          }
        });
      });
    });
    // Residuals ln g_v + ln a_fv - ln g_w - ln a_fw against the face's chosen view w.
    struct Pair {
      int v, w;
      double d;
    };
    std::vector<Pair> pairs;
    for (std::size_t f = 0; f < nf; ++f) {
      const int w = R.faces[f].view;
      if (w < 0 || cand[f].size() < 2) continue;
      float aw = 0;
      for (const Candidate& c : cand[f]) {
        if (c.view == w) aw = c.value;
      }
      if (!(aw > 0.01f)) continue;
      for (const Candidate& c : cand[f]) {
        if (c.view != w && c.value > 0.01f) pairs.push_back({c.view, w, std::log(c.value / aw)});
      }
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(nviews);
    const double prior = 1.0 / (options.gain_prior_sigma * options.gain_prior_sigma);
    constexpr double kHuber = 0.1;  // ln units: shadows and misregistered edges are outliers
    for (int irls = 0; irls < 5 && !pairs.empty(); ++irls) {
      std::vector<Eigen::Triplet<double>> trip;
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nviews);
      for (int v = 0; v < nviews; ++v) trip.emplace_back(v, v, prior);
      for (const Pair& p : pairs) {
        const double r = x[p.v] - x[p.w] + p.d;
        const double wt = std::abs(r) <= kHuber ? 1.0 : kHuber / std::abs(r);
        trip.emplace_back(p.v, p.v, wt);
        trip.emplace_back(p.w, p.w, wt);
        trip.emplace_back(p.v, p.w, -wt);
        trip.emplace_back(p.w, p.v, -wt);
        rhs[p.v] -= wt * p.d;
        rhs[p.w] += wt * p.d;
      }
      Eigen::SparseMatrix<double> A(nviews, nviews);
      A.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
      if (solver.info() != Eigen::Success) throw std::runtime_error("gain normalisation: the normal equations failed");
      x = solver.solve(rhs);
    }
    std::vector<double> gains;
    for (int v = 0; v < nviews; ++v) {
      R.views[static_cast<std::size_t>(v)].gain = std::exp(x[v]);
      gains.push_back(R.views[static_cast<std::size_t>(v)].gain);
    }
    R.summary.gain_min = *std::min_element(gains.begin(), gains.end());
    R.summary.gain_max = *std::max_element(gains.begin(), gains.end());
    R.summary.gain_median = Percentile(gains, 0.5);
  }
  R.summary.seconds.gains = Since(t_gain);

  // ---- Texturing: every texel of every face from the views blending there.
  const auto t_tex = Clock::now();
  const double p_tex0 = options.normalisation == MosaicNormalisation::kModelAndGains ? 0.6 : 0.3;
  constexpr int kMaxChannels = 3;
  cv::Mat sum(atlas_h, atlas_w, CV_32FC4, cv::Scalar::all(0));  // channels 0..2: weighted values, 3: weight
  // The point of M and the face's barycentrics at a texel centre of face f.
  auto texel_point = [&](std::size_t f, int i, int j, bool* inside) {
    const Chart& c = charts[f];
    const Eigen::Vector3d b = Barycentric(c.local, Eigen::Vector2d(i + 0.5, j + 0.5), inside);
    const Face& F = model.faces[f];
    const Eigen::Vector3d p = b[0] * model.vertices[static_cast<std::size_t>(F[0])] +
                              b[1] * model.vertices[static_cast<std::size_t>(F[1])] +
                              b[2] * model.vertices[static_cast<std::size_t>(F[2])];
    return std::make_pair(p, b);
  };
  // A face's texels are its own (charts do not overlap): the faces of a
  // chunk run in parallel, each adding its views in view order, so every
  // texel sums its views in the same order as one view after the other.
  for_each_chunk(p_tex0, 0.9, "texturing: image", [&](int v0, int v1, const std::vector<cv::Mat>& images) {
    std::vector<std::pair<int, int>> work;  // (face, view), by face then view
    for (int vi = v0; vi < v1; ++vi) {
      for (int f : view_faces[static_cast<std::size_t>(vi)]) work.emplace_back(f, vi);
    }
    std::sort(work.begin(), work.end());
    std::vector<std::size_t> starts;  // where each face's run begins
    for (std::size_t i = 0; i < work.size(); ++i) {
      if (i == 0 || work[i].first != work[i - 1].first) starts.push_back(i);
    }
    starts.push_back(work.size());
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, starts.size() - 1, [&](std::size_t run) {
        const auto f = static_cast<std::size_t>(work[starts[run]].first);
        const Chart& c = charts[f];
        const Face& F = model.faces[f];
        const bool blend = face_views[f].size() > 1;
        // The face's views in this chunk, in view order.
        struct Use {
          const cv::Mat* img;
          const MosaicCamera* cam;
          const Eigen::Matrix3d* rot;
          float gain;
          bool own;
          float wc[3];
        };
        std::vector<Use> uses;
        for (std::size_t wi = starts[run]; wi < starts[run + 1]; ++wi) {
          const int vi = work[wi].second;
          Use u{&images[static_cast<std::size_t>(vi - v0)],
                &cameras[static_cast<std::size_t>(vi)],
                &rotation[static_cast<std::size_t>(vi)],
                static_cast<float>(R.views[static_cast<std::size_t>(vi)].gain),
                R.faces[f].view == vi,
                {}};
          for (int k = 0; k < 3; ++k) u.wc[k] = vw[static_cast<std::size_t>(F[k])].Of(vi);
          uses.push_back(u);
        }
        // Texel by texel (its point once), each view in turn: per texel the
        // same sum, in the same order, as view after view.
        for (int j = 0; j < c.h; ++j) {
          auto* row = sum.ptr<cv::Vec4f>(c.y + j) + c.x;
          for (int i = 0; i < c.w; ++i) {
            bool inside;
            const auto [p, b] = texel_point(f, i, j, &inside);
            cv::Vec4f& s = row[i];
            for (const Use& u : uses) {
              // Feathered weight; a face no other view blends into takes its own view alone.
              float w = blend ? static_cast<float>(b[0] * u.wc[0] + b[1] * u.wc[1] + b[2] * u.wc[2]) : 1.0f;
              if (u.own) w = std::max(w, 1e-3f);  // the chosen view always counts a little
              if (w <= 0) continue;
              Eigen::Vector2d uv;
              Eigen::Vector3d pc;
              float px[kMaxChannels];
              if (!u.cam->Project(p, &uv, &pc) || !Sample(*u.img, uv.x(), uv.y(), px)) continue;
              normalise(*u.cam, *u.rot, pc, model.face_normals[f], uv, px, channels);
              for (int k = 0; k < channels; ++k) s[k] += w * u.gain * px[k];
              s[3] += w;
            }
          }
        }
      });
    });
  });
  R.channels = channels > 0 ? channels : 1;
  R.atlas.create(atlas_h, atlas_w, R.channels == 3 ? CV_8UC3 : CV_8UC1);
  R.atlas.setTo(cv::Scalar::all(128));
  std::vector<float> face_value(nf * kMaxChannels, 0.0f);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, nf, [&](std::size_t f) {
      if (R.faces[f].view < 0) return;
      const Chart& c = charts[f];
      double acc[kMaxChannels] = {0, 0, 0};
      int n = 0;
      // Mean over the texels inside the triangle (for the PLY and empty texels).
      for (int j = 0; j < c.h; ++j) {
        const auto* row = sum.ptr<cv::Vec4f>(c.y + j) + c.x;
        for (int i = 0; i < c.w; ++i) {
          bool inside;
          Barycentric(c.local, Eigen::Vector2d(i + 0.5, j + 0.5), &inside);
          if (!inside || row[i][3] <= 0) continue;
          for (int k = 0; k < R.channels; ++k) acc[k] += row[i][k] / row[i][3];
          ++n;
        }
      }
      for (int k = 0; k < R.channels; ++k)
        face_value[f * kMaxChannels + static_cast<std::size_t>(k)] = n ? static_cast<float>(acc[k] / n) : 0.5f;
      float lum = 0;
      for (int k = 0; k < R.channels; ++k) lum += face_value[f * kMaxChannels + static_cast<std::size_t>(k)];
      R.faces[f].albedo = lum / static_cast<float>(R.channels);
      for (int j = 0; j < c.h; ++j) {
        const auto* row = sum.ptr<cv::Vec4f>(c.y + j) + c.x;
        std::uint8_t* out =
            R.atlas.ptr<std::uint8_t>(c.y + j) + static_cast<std::size_t>(c.x) * static_cast<std::size_t>(R.channels);
        for (int i = 0; i < c.w; ++i) {
          for (int k = 0; k < R.channels; ++k) {
            const float v =
                row[i][3] > 0 ? row[i][k] / row[i][3] : face_value[f * kMaxChannels + static_cast<std::size_t>(k)];
            out[i * R.channels + k] = static_cast<std::uint8_t>(std::clamp(v * 255.0f + 0.5f, 0.0f, 255.0f));
          }
        }
      }
    });
  });
  // Vertex values: area-weighted mean of the incident textured faces.
  R.vertex_values.assign(nv * static_cast<std::size_t>(R.channels), 0.5f);
  {
    std::vector<double> acc(nv * kMaxChannels, 0.0), wsum(nv, 0.0);
    for (std::size_t f = 0; f < nf; ++f) {
      if (R.faces[f].view < 0) continue;
      const double a = model.FaceArea(static_cast<int>(f));
      for (int i = 0; i < 3; ++i) {
        const auto v = static_cast<std::size_t>(model.faces[f][i]);
        wsum[v] += a;
        for (int k = 0; k < R.channels; ++k)
          acc[v * kMaxChannels + static_cast<std::size_t>(k)] +=
              a * face_value[f * kMaxChannels + static_cast<std::size_t>(k)];
      }
    }
    for (std::size_t v = 0; v < nv; ++v) {
      if (wsum[v] <= 0) continue;
      for (int k = 0; k < R.channels; ++k) {
        R.vertex_values[v * static_cast<std::size_t>(R.channels) + static_cast<std::size_t>(k)] =
            static_cast<float>(acc[v * kMaxChannels + static_cast<std::size_t>(k)] / wsum[v]);
      }
    }
  }
  for (const MosaicFace& F : R.faces) R.summary.faces_textured += F.view >= 0 ? 1 : 0;
  for (const MosaicView& v : R.views) R.summary.views_used += v.faces > 0 ? 1 : 0;
  R.summary.faces = nf;
  R.summary.seconds.texturing = Since(t_tex);

  // ---- Against the true albedo: the estimate (before 8-bit rounding) at up
  // to truth_samples texels inside each face.
  const auto t_score = Clock::now();
  if (truth) {
    progress.Update(0.9, "scoring against the true albedo");
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, nf, [&](std::size_t f) {
        if (R.faces[f].view < 0) return;
        const Chart& c = charts[f];
        std::vector<std::pair<int, int>> inside_texels;
        for (int j = 0; j < c.h; ++j) {
          for (int i = 0; i < c.w; ++i) {
            bool inside;
            Barycentric(c.local, Eigen::Vector2d(i + 0.5, j + 0.5), &inside);
            if (inside && sum.ptr<cv::Vec4f>(c.y + j)[c.x + i][3] > 0) inside_texels.emplace_back(i, j);
          }
        }
        if (inside_texels.empty()) return;
        const std::size_t n = std::min(inside_texels.size(), static_cast<std::size_t>(options.truth_samples));
        const MosaicCamera& cam = cameras[static_cast<std::size_t>(R.faces[f].view)];
        const double footprint =
            std::max(texel, (cam.centre() - model.FaceCentroid(static_cast<int>(f))).norm() / cam.intrinsics().fx);
        double err = 0, est_sum = 0, true_sum = 0;
        for (std::size_t s = 0; s < n; ++s) {
          const auto [i, j] = inside_texels[s * inside_texels.size() / n];
          bool inside;
          const Eigen::Vector3d p = texel_point(f, i, j, &inside).first;
          const cv::Vec4f& t = sum.ptr<cv::Vec4f>(c.y + j)[c.x + i];
          float est = 0;
          for (int k = 0; k < R.channels; ++k) est += t[k] / t[3];
          est /= static_cast<float>(R.channels);
          const float a = truth->AlbedoAt(p, footprint);
          err += std::abs(est - a);
          est_sum += est;
          true_sum += a;
        }
        R.faces[f].error = static_cast<float>(err / static_cast<double>(n));
        R.faces[f].mean_error = static_cast<float>(std::abs(est_sum - true_sum) / static_cast<double>(n));
        R.faces[f].truth = static_cast<float>(true_sum / static_cast<double>(n));
      });
    });
    std::vector<double> e, me;
    for (const MosaicFace& F : R.faces) {
      if (std::isnan(F.error)) continue;
      e.push_back(F.error);
      me.push_back(F.mean_error);
    }
    R.summary.faces_scored = e.size();
    if (!e.empty()) {
      R.summary.error_median = Percentile(e, 0.5);
      R.summary.error_p95 = Percentile(e, 0.95);
      R.summary.mean_error_median = Percentile(me, 0.5);
      R.summary.mean_error_p95 = Percentile(me, 0.95);
    }
  }
  R.summary.seconds.scoring = Since(t_score);
  R.summary.seconds.total = Since(t_start);
  progress.Update(1.0, "photomosaic done");
  return R;
}

}  // namespace hull
