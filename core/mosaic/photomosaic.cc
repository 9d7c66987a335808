#include "mosaic/photomosaic.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
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

constexpr int kMaxChannels = 3;
constexpr int kSpare = 4;   // the atlas's flat cell for untextured faces
constexpr int kChunk = 64;  // views per chunk of images

// The normalised value of a pixel sample: the albedo estimate of the rig's
// photometric model (the header's step 4), or the raw share of full scale
// without normalisation.
class PixelNormaliser {
 public:
  PixelNormaliser(const SurveyManifest& manifest, const MosaicOptions& options)
      : use_model_(options.normalisation != MosaicNormalisation::kNone) {
    if (!use_model_) return;
    top_ = MakeSurveyCamera(manifest, options.photometry, false);
    if (manifest.camera.stereo()) bottom_ = MakeSurveyCamera(manifest, options.photometry, true);
  }

  // px: the sample's ch channels, in place; rot: the view's x_Mc rotation.
  void operator()(const MosaicCamera& cam, const Eigen::Matrix3d& rot, const Eigen::Vector3d& p_c,
                  const Eigen::Vector3d& n_M, const Eigen::Vector2d& uv, float* px, int ch) const {
    if (!use_model_) return;
    Eigen::Vector3d n_c = rot.transpose() * n_M;
    if (n_c.dot(p_c) > 0) n_c = -n_c;  // the side facing the camera
    const UnderwaterCamera& u = cam.bottom() ? *bottom_ : *top_;
    const UnderwaterCamera::Response r = u.ResponseAt(p_c, n_c, uv.x(), uv.y());
    const float k = r.per_albedo > 1e-9 ? static_cast<float>(1.0 / r.per_albedo) : 0.0f;
    for (int c = 0; c < ch; ++c) px[c] = (px[c] - static_cast<float>(r.offset)) * k;
  }

 private:
  bool use_model_;
  std::unique_ptr<UnderwaterCamera> top_, bottom_;
};

// The survey's images, one pass per stage, in chunks of views in order: a
// chunk's images are read in parallel (TBB), checked in view order (every
// image the camera's size, with the first one's 1 or 3 channels; a mismatch
// names both files), then handed to the stage; decoded images are kept for
// the second pass (gains, then texturing) within the budget.
class ImageChunks {
 public:
  using Stage = std::function<void(int v0, int v1, const std::vector<cv::Mat>& images)>;

  ImageChunks(const MosaicInput& in, const std::vector<MosaicCamera>& cameras,
              const std::vector<std::size_t>& view_keyframe, const std::vector<MosaicView>& views,
              std::size_t cache_budget, tbb::task_arena& arena, Progress& progress)
      : in_(in),
        cameras_(cameras),
        view_keyframe_(view_keyframe),
        views_(views),
        nviews_(static_cast<int>(cameras.size())),
        cache_(cameras.size()),
        cache_budget_(cache_budget),
        arena_(arena),
        progress_(progress) {}

  // Runs `stage` on every chunk, reporting progress from p0 to p1.
  void ForEach(double p0, double p1, const char* what, const Stage& stage) {
    for (int v0 = 0; v0 < nviews_; v0 += kChunk) {
      progress_.ThrowIfCancelled();
      const int v1 = std::min(nviews_, v0 + kChunk);
      const std::vector<cv::Mat> images = Read(v0, v1);
      stage(v0, v1, images);
      progress_.Update(p0 + (p1 - p0) * v1 / nviews_,
                       std::string(what) + " " + std::to_string(v1) + "/" + std::to_string(nviews_));
    }
  }

  int channels() const { return channels_; }  // 0 before the first image

 private:
  std::vector<cv::Mat> Read(int v0, int v1) {
    std::vector<cv::Mat> images(static_cast<std::size_t>(v1 - v0));
    std::vector<std::exception_ptr> failed(images.size());
    arena_.execute([&] {
      tbb::parallel_for(v0, v1, [&](int vi) {
        const auto i = static_cast<std::size_t>(vi - v0);
        if (!cache_[static_cast<std::size_t>(vi)].empty()) {
          images[i] = cache_[static_cast<std::size_t>(vi)];
          return;
        }
        try {
          images[i] = in_.read_image(view_keyframe_[static_cast<std::size_t>(vi)],
                                     cameras_[static_cast<std::size_t>(vi)].bottom());
        } catch (...) {
          failed[i] = std::current_exception();
        }
      });
    });
    for (int vi = v0; vi < v1; ++vi) {
      const auto i = static_cast<std::size_t>(vi - v0);
      if (failed[i]) std::rethrow_exception(failed[i]);
      const cv::Mat& img = images[i];
      Check(img, vi);
      const std::size_t bytes = img.total() * img.elemSize();
      if (cache_[static_cast<std::size_t>(vi)].empty() && cached_bytes_ + bytes <= cache_budget_) {
        cache_[static_cast<std::size_t>(vi)] = img;
        cached_bytes_ += bytes;
      }
    }
    return images;
  }

  std::string NameOf(int vi) const {
    const auto v = static_cast<std::size_t>(vi);
    const std::string name = in_.image_name ? in_.image_name(view_keyframe_[v], cameras_[v].bottom()) : "";
    return name.empty() ? "the " + std::string(cameras_[v].bottom() ? "bottom" : "top") + " image of keyframe " +
                              std::to_string(views_[v].keyframe)
                        : name;
  }

  void Check(const cv::Mat& img, int vi) {
    const int W = in_.manifest.camera.width, H = in_.manifest.camera.height;
    if (img.empty() || img.cols != W || img.rows != H) {
      throw InputError({NameOf(vi), 0, 0, ""}, "the image is " + std::to_string(img.cols) + "x" +
                                                   std::to_string(img.rows) + "; the camera is " + std::to_string(W) +
                                                   "x" + std::to_string(H));
    }
    if (channels_ == 0) channels_ = img.channels(), first_view_ = vi;
    if (img.channels() != 1 && img.channels() != 3) {
      throw InputError({NameOf(vi), 0, 0, ""},
                       std::to_string(img.channels()) + " channels; the photomosaic takes grey or colour (1 or 3)");
    }
    if (img.channels() != channels_) {
      throw InputError({NameOf(vi), 0, 0, ""}, std::to_string(img.channels()) + " channels, where " +
                                                   NameOf(first_view_) + " has " + std::to_string(channels_) +
                                                   ": the images mix channel counts");
    }
  }

  const MosaicInput& in_;
  const std::vector<MosaicCamera>& cameras_;
  const std::vector<std::size_t>& view_keyframe_;
  const std::vector<MosaicView>& views_;
  const int nviews_;
  std::vector<cv::Mat> cache_;
  std::size_t cached_bytes_ = 0;
  const std::size_t cache_budget_;
  tbb::task_arena& arena_;
  Progress& progress_;
  int channels_ = 0, first_view_ = -1;
};

// One observed ratio between two views of a face: ln a_fv - ln a_fw, the
// face's value in view v against its chosen view w.
struct GainPair {
  int v, w;
  double d;
};

// The ln gain per view minimising sum_pairs huber(x_v - x_w + d) with a prior
// holding each ln gain near 0 (sigma prior_sigma): five rounds of
// iteratively reweighted least squares on the sparse normal equations.
Eigen::VectorXd SolveLogGains(const std::vector<GainPair>& pairs, int nviews, double prior_sigma) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(nviews);
  const double prior = 1.0 / (prior_sigma * prior_sigma);
  constexpr double kHuber = 0.1;  // ln units: shadows and misregistered edges are outliers
  for (int irls = 0; irls < 5 && !pairs.empty(); ++irls) {
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nviews);
    for (int v = 0; v < nviews; ++v) trip.emplace_back(v, v, prior);
    for (const GainPair& p : pairs) {
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
  return x;
}

// BuildMosaic's stages (the header's steps 1-7), in the order Build runs
// them, over the state they share: the split model, the views, each face's
// candidate views and chart, and the atlas's running sums.
class MosaicBuilder {
 public:
  MosaicBuilder(const MosaicInput& in, const MosaicOptions& options, Progress& progress)
      : in_(in),
        options_(options),
        progress_(progress),
        arena_(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic) {}

  MosaicResult Build(const TrueScene* truth) {
    const auto t_start = Clock::now();
    R_.options = options_;
    R_.normalisation = options_.normalisation;
    R_.model = in_.model;
    R_.model.ComputeNormals();
    PlaceViews();
    SplitFacesNearCameras();
    nf_ = R_.model.num_faces();
    nv_ = R_.model.num_vertices();
    FindCandidates();
    ChooseFaceViews();
    vw_ = FeatherWeights(R_.model, R_.faces, options_);
    LayOutAtlas();
    PlaceCorners();
    FindBlendingViews();
    const std::size_t cache_budget = options_.normalisation == MosaicNormalisation::kModelAndGains
                                         ? static_cast<std::size_t>(options_.image_cache_mb) << 20
                                         : 0;
    ImageChunks images(in_, cameras_, view_keyframe_, R_.views, cache_budget, arena_, progress_);
    const auto t_gain = Clock::now();
    if (options_.normalisation == MosaicNormalisation::kModelAndGains) EstimateGains(images);
    R_.summary.seconds.gains = Since(t_gain);
    const auto t_tex = Clock::now();
    AccumulateTexels(images);
    R_.channels = images.channels() > 0 ? images.channels() : 1;
    ResolveAtlas();
    AverageVertexValues();
    for (const MosaicFace& F : R_.faces) R_.summary.faces_textured += F.view >= 0 ? 1 : 0;
    for (const MosaicView& v : R_.views) R_.summary.views_used += v.faces > 0 ? 1 : 0;
    R_.summary.faces = nf_;
    R_.summary.seconds.texturing = Since(t_tex);
    const auto t_score = Clock::now();
    if (truth) ScoreAgainstTruth(*truth);
    R_.summary.seconds.scoring = Since(t_score);
    R_.summary.seconds.total = Since(t_start);
    progress_.Update(1.0, "photomosaic done");
    return std::move(R_);
  }

 private:
  // ---- 1. Views: every keyframe camera that has an image, in keyframe order.
  void PlaceViews() {
    const bool stereo = in_.manifest.camera.stereo();
    for (std::size_t k = 0; k < in_.keyframes.size(); ++k) {
      for (bool b : {false, true}) {
        if (b && !stereo) continue;
        if (!in_.has_image(k, b)) continue;
        cameras_.emplace_back(in_.manifest, in_.poses[k], in_.servo[k], in_.x_s_cT, in_.x_gM, b);
        view_keyframe_.push_back(k);
        MosaicView v;
        v.keyframe = in_.keyframes[k];
        v.bottom = b;
        v.x_Mc = cameras_.back().x_Mc();
        R_.views.push_back(v);
      }
    }
    nviews_ = static_cast<int>(cameras_.size());
    if (nviews_ == 0) throw std::invalid_argument("the survey has no images to texture the model with");
    // Each view's x_Mc rotation as a matrix, made once (not per sample).
    rotation_.resize(cameras_.size());
    for (std::size_t vi = 0; vi < cameras_.size(); ++vi) rotation_[vi] = cameras_[vi].x_Mc().rotation();
  }

  // Faces within max_range of the cameras' bounding box get their long edges split.
  void SplitFacesNearCameras() {
    TriangleMesh& model = R_.model;
    Eigen::AlignedBox3d box;
    for (const MosaicCamera& c : cameras_) box.extend(c.centre());
    SplitLongEdges(model, options_.max_edge, [&](int f) {
      const Face& F = model.faces[static_cast<std::size_t>(f)];
      const Eigen::Vector3d g = model.FaceCentroid(f);
      double r = 0;
      for (int i = 0; i < 3; ++i) r = std::max(r, (model.vertices[static_cast<std::size_t>(F[i])] - g).norm());
      return box.exteriorDistance(g) <= options_.max_range + r;
    });
  }

  // ---- 2. Candidates: visible, unoccluded, in the image, near and frontal enough.
  void FindCandidates() {
    progress_.Update(0.0, "visibility of " + std::to_string(nf_) + " faces in " + std::to_string(nviews_) + " images");
    const auto t_vis = Clock::now();
    const MeshIndex index(R_.model);
    const int W = in_.manifest.camera.width, H = in_.manifest.camera.height;
    mosaic_internal::Visibility vis;
    arena_.execute([&] { vis = SeenFaces(R_.model, index, cameras_, W, H, options_, progress_); });
    std::vector<std::vector<std::pair<int, float>>>& seen = vis.seen;  // view -> (face, score)
    progress_.ThrowIfCancelled();
    cand_.assign(nf_, {});
    for (int vi = 0; vi < nviews_; ++vi) {
      R_.views[static_cast<std::size_t>(vi)].candidates = static_cast<int>(seen[static_cast<std::size_t>(vi)].size());
      for (const auto& [f, s] : seen[static_cast<std::size_t>(vi)])
        cand_[static_cast<std::size_t>(f)].push_back({vi, s, 0});
    }
    seen.clear();
    R_.summary.visibility_pairs_near = vis.near;
    R_.summary.visibility_pairs_projected = vis.projected;
    R_.summary.visibility_rays = vis.rays;
    R_.summary.seconds.visibility = Since(t_vis);
  }

  // ---- 3. Labelling: best view, then Potts smoothing by iterated conditional
  // modes; counts the seams.
  void ChooseFaceViews() {
    progress_.Update(0.2, "choosing a view per face");
    const auto t_label = Clock::now();
    const std::vector<std::array<int, 3>> nbr = FaceNeighbours(R_.model);  // over shared edges
    R_.faces = ChooseViews(cand_, nbr, options_);
    for (std::size_t f = 0; f < nf_; ++f) {
      MosaicFace& F = R_.faces[f];
      if (F.view < 0) continue;
      for (const Candidate& c : cand_[f]) {
        if (c.view == F.view) F.score = c.score;
      }
      ++R_.views[static_cast<std::size_t>(F.view)].faces;
      for (int i = 0; i < 3; ++i) {
        const int n = nbr[f][static_cast<std::size_t>(i)];
        if (n < 0 || static_cast<std::size_t>(n) < f) continue;
        ++R_.summary.interior_edges;
        const int nvw = R_.faces[static_cast<std::size_t>(n)].view;
        if (nvw >= 0 && nvw != F.view) ++R_.summary.seam_edges;
      }
    }
    R_.summary.seconds.labelling = Since(t_label);
  }

  // ---- 6. Atlas: a flat chart per textured face at the texel size, shelf
  // packed; the texel grows by 1.25 until the atlas fits max_atlas_size.
  void LayOutAtlas() {
    progress_.Update(0.3, "packing the atlas");
    texel_ = options_.texel_size;
    charts_.assign(nf_, {});
    std::vector<int> order;
    for (std::size_t f = 0; f < nf_; ++f) {
      if (R_.faces[f].view >= 0) order.push_back(static_cast<int>(f));
    }
    for (int attempt = 0;; ++attempt) {
      double area = 0;
      int widest = kSpare;
      for (int f : order) {
        charts_[static_cast<std::size_t>(f)] = FlatChart(R_.model, f, texel_);
        const Chart& c = charts_[static_cast<std::size_t>(f)];
        area += static_cast<double>(c.w) * c.h;
        widest = std::max(widest, c.w);
      }
      std::sort(order.begin(), order.end(), [&](int a, int b) {
        const Chart &ca = charts_[static_cast<std::size_t>(a)], &cb = charts_[static_cast<std::size_t>(b)];
        return ca.h != cb.h ? ca.h > cb.h : a < b;
      });
      atlas_w_ = std::max(widest, static_cast<int>(std::ceil(std::sqrt(area * 1.05 + kSpare * kSpare))));
      atlas_w_ = (atlas_w_ + 3) / 4 * 4;
      atlas_h_ = PackShelves(charts_, order, atlas_w_) + kSpare;
      if (atlas_w_ <= options_.max_atlas_size && atlas_h_ <= options_.max_atlas_size) break;
      if (attempt > 30) throw std::runtime_error("the photomosaic atlas does not fit in max_atlas_size");
      texel_ *= 1.25;
    }
    R_.summary.texel_size = texel_;
    double used = 0;
    for (int f : order)
      used += static_cast<double>(charts_[static_cast<std::size_t>(f)].w) * charts_[static_cast<std::size_t>(f)].h;
    R_.summary.atlas_fill = used / (static_cast<double>(atlas_w_) * atlas_h_);
  }

  // Each face's corners in the atlas (pixels); untextured faces on the spare cell.
  void PlaceCorners() {
    const int spare_y = atlas_h_ - kSpare;
    R_.corners.assign(nf_, {});
    for (std::size_t f = 0; f < nf_; ++f) {
      if (R_.faces[f].view < 0) {
        // Untextured: all corners on the spare cell's centre (filled grey).
        for (auto& c : R_.corners[f]) c = Eigen::Vector2f(kSpare / 2.0f, static_cast<float>(spare_y) + kSpare / 2.0f);
        continue;
      }
      R_.summary.textured_area += R_.model.FaceArea(static_cast<int>(f));
      const Chart& c = charts_[f];
      for (int i = 0; i < 3; ++i) {
        R_.corners[f][static_cast<std::size_t>(i)] =
            (c.local[static_cast<std::size_t>(i)] + Eigen::Vector2d(c.x, c.y)).cast<float>();
      }
    }
  }

  // ---- 5. Which views texture each face: its own and, with feathering, the
  // views weighted at its corners that also see it.
  void FindBlendingViews() {
    view_faces_.assign(static_cast<std::size_t>(nviews_), {});
    face_views_.assign(nf_, {});
    for (std::size_t f = 0; f < nf_; ++f) {
      if (R_.faces[f].view < 0) continue;
      std::vector<int> vs = {R_.faces[f].view};
      for (int i = 0; i < 3 && options_.feather_rings > 0; ++i) {
        for (int v : vw_[static_cast<std::size_t>(R_.model.faces[f][i])].view) {
          if (v < 0) continue;
          const bool visible =
              std::any_of(cand_[f].begin(), cand_[f].end(), [&](const Candidate& c) { return c.view == v; });
          if (visible && std::find(vs.begin(), vs.end(), v) == vs.end()) vs.push_back(v);
        }
      }
      for (int v : vs) view_faces_[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
      face_views_[f] = std::move(vs);
    }
  }

  // ---- 4. Gains: per image, from the faces several images see (robust
  // least squares on ln values, a prior holding ln gain near 0).
  void EstimateGains(ImageChunks& images) {
    MeasureCandidateValues(images);
    std::vector<GainPair> pairs;  // residuals ln g_v + ln a_fv - ln g_w - ln a_fw against the chosen view w
    for (std::size_t f = 0; f < nf_; ++f) {
      const int w = R_.faces[f].view;
      if (w < 0 || cand_[f].size() < 2) continue;
      float aw = 0;
      for (const Candidate& c : cand_[f]) {
        if (c.view == w) aw = c.value;
      }
      if (!(aw > 0.01f)) continue;
      for (const Candidate& c : cand_[f]) {
        if (c.view != w && c.value > 0.01f) pairs.push_back({c.view, w, std::log(c.value / aw)});
      }
    }
    const Eigen::VectorXd x = SolveLogGains(pairs, nviews_, options_.gain_prior_sigma);
    std::vector<double> gains;
    for (int v = 0; v < nviews_; ++v) {
      R_.views[static_cast<std::size_t>(v)].gain = std::exp(x[v]);
      gains.push_back(R_.views[static_cast<std::size_t>(v)].gain);
    }
    R_.summary.gain_min = *std::min_element(gains.begin(), gains.end());
    R_.summary.gain_max = *std::max_element(gains.begin(), gains.end());
    R_.summary.gain_median = Percentile(gains, 0.5);
  }

  // The mean normalised value of every face several views see, in each of
  // them (Candidate::value; 0 when a sample falls outside the image).
  void MeasureCandidateValues(ImageChunks& images) {
    // Per view, the faces it sees and is a candidate for (for the overlaps).
    std::vector<std::vector<std::pair<int, int>>> cand_of_view(static_cast<std::size_t>(nviews_));  // (face, slot)
    for (std::size_t f = 0; f < nf_; ++f) {
      if (cand_[f].size() < 2) continue;
      for (std::size_t s = 0; s < cand_[f].size(); ++s) {
        cand_of_view[static_cast<std::size_t>(cand_[f][s].view)].emplace_back(static_cast<int>(f), static_cast<int>(s));
      }
    }
    const TriangleMesh& model = R_.model;
    // Every (face, slot) belongs to one view: the views of a chunk run in parallel.
    images.ForEach(0.3, 0.6, "gains: image", [&](int v0, int v1, const std::vector<cv::Mat>& chunk) {
      const int channels = images.channels();
      arena_.execute([&] {
        tbb::parallel_for(v0, v1, [&](int vi) {
          const cv::Mat& img = chunk[static_cast<std::size_t>(vi - v0)];
          const MosaicCamera& cam = cameras_[static_cast<std::size_t>(vi)];
          for (const auto& [f, slot] : cand_of_view[static_cast<std::size_t>(vi)]) {
            double sum = 0;
            int n = 0;
            for (const Eigen::Vector3d& p : FaceSamples(model, f)) {
              Eigen::Vector2d uv;
              Eigen::Vector3d pc;
              float px[3];
              if (!cam.Project(p, &uv, &pc) || !Sample(img, uv.x(), uv.y(), px)) continue;
              normalise_(cam, rotation_[static_cast<std::size_t>(vi)], pc,
                         model.face_normals[static_cast<std::size_t>(f)], uv, px, channels);
              float lum = 0;
              for (int c = 0; c < channels; ++c) lum += px[c];
              sum += lum / channels;
              ++n;
            }
            cand_[static_cast<std::size_t>(f)][static_cast<std::size_t>(slot)].value =
                n == kSamples ? static_cast<float>(sum / n) : 0.0f;
          }
        });
      });
    });
  }

  // The point of M and the face's barycentrics at a texel centre of face f.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> TexelPoint(std::size_t f, int i, int j, bool* inside) const {
    const Chart& c = charts_[f];
    const Eigen::Vector3d b = Barycentric(c.local, Eigen::Vector2d(i + 0.5, j + 0.5), inside);
    const TriangleMesh& model = R_.model;
    const Face& F = model.faces[f];
    const Eigen::Vector3d p = b[0] * model.vertices[static_cast<std::size_t>(F[0])] +
                              b[1] * model.vertices[static_cast<std::size_t>(F[1])] +
                              b[2] * model.vertices[static_cast<std::size_t>(F[2])];
    return std::make_pair(p, b);
  }

  // One view as it textures one face.
  struct ViewUse {
    const cv::Mat* img;
    const MosaicCamera* cam;
    const Eigen::Matrix3d* rot;
    float gain;
    bool own;     // the face's chosen view
    float wc[3];  // its feathering weight at the face's corners
  };

  // ---- Texturing: every texel of every face sums the views blending there
  // (weighted values in channels 0..2 of sum_, the weight in 3). A face's
  // texels are its own (charts do not overlap): the faces of a chunk run in
  // parallel, each adding its views in view order, so every texel sums its
  // views in the same order as one view after the other.
  void AccumulateTexels(ImageChunks& images) {
    const double p_tex0 = options_.normalisation == MosaicNormalisation::kModelAndGains ? 0.6 : 0.3;
    sum_ = cv::Mat(atlas_h_, atlas_w_, CV_32FC4, cv::Scalar::all(0));
    images.ForEach(p_tex0, 0.9, "texturing: image", [&](int v0, int v1, const std::vector<cv::Mat>& chunk) {
      std::vector<std::pair<int, int>> work;  // (face, view), by face then view
      for (int vi = v0; vi < v1; ++vi) {
        for (int f : view_faces_[static_cast<std::size_t>(vi)]) work.emplace_back(f, vi);
      }
      std::sort(work.begin(), work.end());
      std::vector<std::size_t> starts;  // where each face's run begins
      for (std::size_t i = 0; i < work.size(); ++i) {
        if (i == 0 || work[i].first != work[i - 1].first) starts.push_back(i);
      }
      starts.push_back(work.size());
      const int channels = images.channels();
      arena_.execute([&] {
        tbb::parallel_for(std::size_t{0}, starts.size() - 1, [&](std::size_t run) {
          const auto f = static_cast<std::size_t>(work[starts[run]].first);
          const Face& F = R_.model.faces[f];
          std::vector<ViewUse> uses;  // the face's views in this chunk, in view order
          for (std::size_t wi = starts[run]; wi < starts[run + 1]; ++wi) {
            const int vi = work[wi].second;
            ViewUse u{&chunk[static_cast<std::size_t>(vi - v0)],
                      &cameras_[static_cast<std::size_t>(vi)],
                      &rotation_[static_cast<std::size_t>(vi)],
                      static_cast<float>(R_.views[static_cast<std::size_t>(vi)].gain),
                      R_.faces[f].view == vi,
                      {}};
            for (int k = 0; k < 3; ++k) u.wc[k] = vw_[static_cast<std::size_t>(F[k])].Of(vi);
            uses.push_back(u);
          }
          AccumulateFace(f, uses, channels);
        });
      });
    });
  }

  // Texel by texel (its point once), each view in turn: per texel the same
  // sum, in the same order, as view after view.
  void AccumulateFace(std::size_t f, const std::vector<ViewUse>& uses, int channels) {
    const Chart& c = charts_[f];
    const bool blend = face_views_[f].size() > 1;
    for (int j = 0; j < c.h; ++j) {
      auto* row = sum_.ptr<cv::Vec4f>(c.y + j) + c.x;
      for (int i = 0; i < c.w; ++i) {
        bool inside;
        const auto [p, b] = TexelPoint(f, i, j, &inside);
        cv::Vec4f& s = row[i];
        for (const ViewUse& u : uses) {
          // Feathered weight; a face no other view blends into takes its own view alone.
          float w = blend ? static_cast<float>(b[0] * u.wc[0] + b[1] * u.wc[1] + b[2] * u.wc[2]) : 1.0f;
          if (u.own) w = std::max(w, 1e-3f);  // the chosen view always counts a little
          if (w <= 0) continue;
          Eigen::Vector2d uv;
          Eigen::Vector3d pc;
          float px[kMaxChannels];
          if (!u.cam->Project(p, &uv, &pc) || !Sample(*u.img, uv.x(), uv.y(), px)) continue;
          normalise_(*u.cam, *u.rot, pc, R_.model.face_normals[f], uv, px, channels);
          for (int k = 0; k < channels; ++k) s[k] += w * u.gain * px[k];
          s[3] += w;
        }
      }
    }
  }

  // The atlas (8-bit, mid grey where nothing is) from the sums, and each
  // face's mean over the texels inside its triangle (its albedo, the value
  // of its empty texels and of the PLY's vertices).
  void ResolveAtlas() {
    const int channels = R_.channels;
    R_.atlas.create(atlas_h_, atlas_w_, channels == 3 ? CV_8UC3 : CV_8UC1);
    R_.atlas.setTo(cv::Scalar::all(128));
    face_value_.assign(nf_ * kMaxChannels, 0.0f);
    arena_.execute([&] {
      tbb::parallel_for(std::size_t{0}, nf_, [&](std::size_t f) {
        if (R_.faces[f].view < 0) return;
        const Chart& c = charts_[f];
        float* value = &face_value_[f * kMaxChannels];
        double acc[kMaxChannels] = {0, 0, 0};
        int n = 0;
        for (int j = 0; j < c.h; ++j) {
          const auto* row = sum_.ptr<cv::Vec4f>(c.y + j) + c.x;
          for (int i = 0; i < c.w; ++i) {
            bool inside;
            Barycentric(c.local, Eigen::Vector2d(i + 0.5, j + 0.5), &inside);
            if (!inside || row[i][3] <= 0) continue;
            for (int k = 0; k < channels; ++k) acc[k] += row[i][k] / row[i][3];
            ++n;
          }
        }
        for (int k = 0; k < channels; ++k) value[k] = n ? static_cast<float>(acc[k] / n) : 0.5f;
        float lum = 0;
        for (int k = 0; k < channels; ++k) lum += value[k];
        R_.faces[f].albedo = lum / static_cast<float>(channels);
        for (int j = 0; j < c.h; ++j) {
          const auto* row = sum_.ptr<cv::Vec4f>(c.y + j) + c.x;
          std::uint8_t* out =
              R_.atlas.ptr<std::uint8_t>(c.y + j) + static_cast<std::size_t>(c.x) * static_cast<std::size_t>(channels);
          for (int i = 0; i < c.w; ++i) {
            for (int k = 0; k < channels; ++k) {
              const float v = row[i][3] > 0 ? row[i][k] / row[i][3] : value[k];
              out[i * channels + k] = static_cast<std::uint8_t>(std::clamp(v * 255.0f + 0.5f, 0.0f, 255.0f));
            }
          }
        }
      });
    });
  }

  // Vertex values: area-weighted mean of the incident textured faces.
  void AverageVertexValues() {
    const auto channels = static_cast<std::size_t>(R_.channels);
    R_.vertex_values.assign(nv_ * channels, 0.5f);
    std::vector<double> acc(nv_ * kMaxChannels, 0.0), wsum(nv_, 0.0);
    for (std::size_t f = 0; f < nf_; ++f) {
      if (R_.faces[f].view < 0) continue;
      const double a = R_.model.FaceArea(static_cast<int>(f));
      for (int i = 0; i < 3; ++i) {
        const auto v = static_cast<std::size_t>(R_.model.faces[f][i]);
        wsum[v] += a;
        for (std::size_t k = 0; k < channels; ++k) acc[v * kMaxChannels + k] += a * face_value_[f * kMaxChannels + k];
      }
    }
    for (std::size_t v = 0; v < nv_; ++v) {
      if (wsum[v] <= 0) continue;
      for (std::size_t k = 0; k < channels; ++k) {
        R_.vertex_values[v * channels + k] = static_cast<float>(acc[v * kMaxChannels + k] / wsum[v]);
      }
    }
  }

  // ---- 7. Against the true albedo: the estimate (before 8-bit rounding) at
  // up to truth_samples texels inside each face.
  void ScoreAgainstTruth(const TrueScene& truth) {
    progress_.Update(0.9, "scoring against the true albedo");
    arena_.execute([&] {
      tbb::parallel_for(std::size_t{0}, nf_, [&](std::size_t f) {
        if (R_.faces[f].view >= 0) ScoreFace(f, truth);
      });
    });
    std::vector<double> e, me;
    for (const MosaicFace& F : R_.faces) {
      if (std::isnan(F.error)) continue;
      e.push_back(F.error);
      me.push_back(F.mean_error);
    }
    R_.summary.faces_scored = e.size();
    if (!e.empty()) {
      R_.summary.error_median = Percentile(e, 0.5);
      R_.summary.error_p95 = Percentile(e, 0.95);
      R_.summary.mean_error_median = Percentile(me, 0.5);
      R_.summary.mean_error_p95 = Percentile(me, 0.95);
    }
  }

  void ScoreFace(std::size_t f, const TrueScene& truth) {
    const Chart& c = charts_[f];
    std::vector<std::pair<int, int>> inside_texels;
    for (int j = 0; j < c.h; ++j) {
      for (int i = 0; i < c.w; ++i) {
        bool inside;
        Barycentric(c.local, Eigen::Vector2d(i + 0.5, j + 0.5), &inside);
        if (inside && sum_.ptr<cv::Vec4f>(c.y + j)[c.x + i][3] > 0) inside_texels.emplace_back(i, j);
      }
    }
    if (inside_texels.empty()) return;
    const std::size_t n = std::min(inside_texels.size(), static_cast<std::size_t>(options_.truth_samples));
    const MosaicCamera& cam = cameras_[static_cast<std::size_t>(R_.faces[f].view)];
    const double footprint =
        std::max(texel_, (cam.centre() - R_.model.FaceCentroid(static_cast<int>(f))).norm() / cam.intrinsics().fx);
    double err = 0, est_sum = 0, true_sum = 0;
    for (std::size_t s = 0; s < n; ++s) {
      const auto [i, j] = inside_texels[s * inside_texels.size() / n];
      bool inside;
      const Eigen::Vector3d p = TexelPoint(f, i, j, &inside).first;
      const cv::Vec4f& t = sum_.ptr<cv::Vec4f>(c.y + j)[c.x + i];
      float est = 0;
      for (int k = 0; k < R_.channels; ++k) est += t[k] / t[3];
      est /= static_cast<float>(R_.channels);
      const float a = truth.AlbedoAt(p, footprint);
      err += std::abs(est - a);
      est_sum += est;
      true_sum += a;
    }
    R_.faces[f].error = static_cast<float>(err / static_cast<double>(n));
    R_.faces[f].mean_error = static_cast<float>(std::abs(est_sum - true_sum) / static_cast<double>(n));
    R_.faces[f].truth = static_cast<float>(true_sum / static_cast<double>(n));
  }

  const MosaicInput& in_;
  const MosaicOptions& options_;
  Progress& progress_;
  tbb::task_arena arena_;
  const PixelNormaliser normalise_{in_.manifest, options_};
  MosaicResult R_;
  // Views: cameras, the keyframe index of each, their rotations x_Mc.
  std::vector<MosaicCamera> cameras_;
  std::vector<std::size_t> view_keyframe_;
  std::vector<Eigen::Matrix3d> rotation_;
  int nviews_ = 0;
  std::size_t nf_ = 0, nv_ = 0;               // faces and vertices of the split model
  std::vector<std::vector<Candidate>> cand_;  // per face: the views that see it
  std::vector<ViewWeights> vw_;               // per vertex: feathering weights
  // Atlas layout: a chart per face, the texel size that fits, the size.
  std::vector<Chart> charts_;
  double texel_ = 0;
  int atlas_w_ = 0, atlas_h_ = 0;
  std::vector<std::vector<int>> view_faces_;  // per view: the faces it textures
  std::vector<std::vector<int>> face_views_;  // per face: the views blending there
  cv::Mat sum_;                               // CV_32FC4: weighted values, weight
  std::vector<float> face_value_;             // per face, kMaxChannels: the mean value
};

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
  return MosaicBuilder(in, options, progress).Build(truth);
}

}  // namespace hull
