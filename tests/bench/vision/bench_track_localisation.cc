// How well the front end's feature pixels of one track correspond, on a
// rendered survey with truth. For each track of a bundle's features.csv
// (made by the front end), its first observation's pixel is cast from the
// TRUE camera onto the true scene; that point, projected into each other
// member's true camera, is where that member's feature should lie. The
// difference is the pair's relative localisation error (a wrong match shows
// as tens of pixels; a right one as the detector's sub-pixel noise), split
// into the component along the pair's epipolar line (what moves a two-view
// point in depth) and across it. Two-view tracks are triangulated with the
// true cameras: their distance to the true surface is what that error does.
//
//   bench_track_localisation BUNDLE [--max-error PX] [--refine none|translation|affine] [--radius R]
// --max-error: pairs with a larger error count as wrong matches (default 4 px).
// --refine: first aligns every member's patch with the first member's
// (vision/patch_alignment.h; radius R px, default 7) and scores the aligned
// pixels; an alignment that does not converge, or moves more than 3 px,
// keeps the detector's pixel.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/mesh_index.h"
#include "simulate/image_track_truth.h"
#include "simulate/true_scene.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"
#include "vision/camera_geometry.h"
#include "vision/patch_alignment.h"

namespace {
using namespace hull;

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

void PrintQuantiles(const char* what, const std::vector<double>& v) {
  std::printf("  %-44s n %7zu: 50 %% %.3f, 90 %% %.3f, 99 %% %.3f, 99.9 %% %.3f, max %.3f\n", what, v.size(),
              Quantile(v, 0.5), Quantile(v, 0.9), Quantile(v, 0.99), Quantile(v, 0.999), Quantile(v, 1.0));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_track_localisation BUNDLE [--max-error PX]\n");
    return 2;
  }
  double max_error = 4;
  std::string refine = "none";
  int radius = 7;
  bool prior_warp = false;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--max-error") {
      max_error = std::atof(argv[i + 1]);
    } else if (a == "--refine") {
      refine = argv[i + 1];
    } else if (a == "--warp") {
      prior_warp = std::string(argv[i + 1]) == "prior";
    } else if (a == "--radius") {
      radius = std::atoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  SurveyBundle b = ReadSurveyBundle(argv[1]);
  if (!b.truth || b.features.empty()) {
    std::fprintf(stderr, "%s: needs truth and features.csv\n", argv[1]);
    return 1;
  }
  const auto scene = TrueScene::Load(b);
  const PinholeIntrinsics& k = b.manifest.camera.top;
  const Eigen::Matrix3d K = CameraMatrix(k);
  std::unordered_map<std::int64_t, std::size_t> pose_of;
  for (std::size_t i = 0; i < b.truth->poses.size(); ++i) pose_of[b.truth->poses[i].keyframe] = i;
  std::unordered_map<std::int64_t, Pose> cams;  // true top camera in M per keyframe
  for (const auto& [kf, i] : pose_of) cams[kf] = TrueCameraPoseFromTruth(b, i, false);
  std::map<std::int64_t, std::vector<FeatureObservation*>> tracks;
  for (FeatureObservation& f : b.features) tracks[f.landmark].push_back(&f);
  if (refine != "none") {
    // References: the first member's patch; then each keyframe's members aligned.
    std::map<std::int64_t, std::vector<std::int64_t>> refs_in;  // keyframe -> landmarks whose reference it holds
    for (const auto& [id, obs] : tracks) refs_in[obs.front()->keyframe].push_back(id);
    std::unordered_map<std::int64_t, std::vector<float>> patch;
    for (const auto& [kf, ids] : refs_in) {
      const GradientImage g = MakeGradientImage(ReadSurveyImage(b, kf, false));
      for (const std::int64_t id : ids) {
        std::vector<float> p;
        if (SamplePatch(g.image, tracks[id].front()->top, radius, p)) patch[id] = std::move(p);
      }
    }
    std::map<std::int64_t, std::vector<FeatureObservation*>> members_in;
    for (auto& [id, obs] : tracks)
      for (std::size_t j = 1; j < obs.size(); ++j) members_in[obs[j]->keyframe].push_back(obs[j]);
    std::vector<double> moved;
    std::size_t failed = 0, tried = 0, worse = 0, better = 0, worse_loop = 0, tried_loop = 0, failed_loop = 0;
    std::unordered_map<std::int64_t, std::size_t> index_of;
    for (std::size_t i = 0; i < b.nav.size(); ++i) index_of[b.nav[i].keyframe] = i;
    std::vector<double> worse_ncc, better_ncc;
    for (const auto& [kf, members] : members_in) {
      const GradientImage g = MakeGradientImage(ReadSurveyImage(b, kf, false));
      for (FeatureObservation* f : members) {
        const auto p = patch.find(f->landmark);
        if (p == patch.end()) continue;
        ++tried;
        const FeatureObservation& r0 = *tracks[f->landmark].front();
        const bool loop = index_of.at(f->keyframe) > index_of.at(r0.keyframe) + 2;
        tried_loop += loop;
        Eigen::Matrix2d warp0 = Eigen::Matrix2d::Identity();
        if (prior_warp) {
          const Pose ca = CameraPoseFromNav(b.manifest, b.nav[index_of.at(r0.keyframe)]);
          const Pose cb = CameraPoseFromNav(b.manifest, b.nav[index_of.at(f->keyframe)]);
          warp0 = InfiniteHomographyWarp(K, K, cb.rotation().transpose() * ca.rotation(), r0.top);
        }
        const PatchAlignment a = AlignPatch(p->second, radius, g, f->top, warp0, refine == "affine");
        if (!a.converged || (a.point - f->top).norm() > 3) {
          ++failed;
          failed_loop += loop;
          continue;
        }
        // Scored against the truth here already (before / after).
        if (cams.count(r0.keyframe) && cams.count(f->keyframe)) {
          const Pose& c0 = cams.at(r0.keyframe);
          const RayHit h = scene->index().Raycast(c0.translation(), c0.rotation() * k.Unproject(r0.top).normalized());
          const Eigen::Vector3d pc = cams.at(f->keyframe).Inverse() * h.point;
          if (h.hit && pc.z() > 0) {
            const double before = (k.Project(pc) - f->top).norm(), after = (k.Project(pc) - a.point).norm();
            if (after > before + 0.5) {
              ++worse;
              worse_loop += loop;
              worse_ncc.push_back(a.ncc);
            } else if (before > after + 0.5) {
              ++better;
              better_ncc.push_back(a.ncc);
            }
          }
        }
        moved.push_back((a.point - f->top).norm());
        f->top = a.point;
      }
    }
    std::printf("refined (%s, radius %d): %zu members tried, %zu kept the detector's pixel\n", refine.c_str(), radius,
                tried, failed);
    PrintQuantiles("moved by (px)", moved);
    std::printf(
        "  %zu members more than 0.5 px better, %zu more than 0.5 px worse (%zu of them loops); loops: %zu tried, "
        "%zu kept the detector's pixel\n",
        better, worse, worse_loop, tried_loop, failed_loop);
    PrintQuantiles("NCC of the worse", worse_ncc);
    for (double t : {0.8, 0.9, 0.95}) {
      const auto below = [t](const std::vector<double>& v) {
        return std::count_if(v.begin(), v.end(), [t](double x) { return x < t; });
      };
      std::printf("  NCC < %.2f: %ld of the worse, %ld of the better\n", t, static_cast<long>(below(worse_ncc)),
                  static_cast<long>(below(better_ncc)));
    }
    PrintQuantiles("NCC of the better", better_ncc);
  }

  std::map<int, std::vector<double>> error_by_views, along_by_views, across_by_views;
  std::vector<double> two_view_surface, two_view_signed;
  std::size_t wrong = 0, pairs = 0;
  for (const auto& [id, obs_] : tracks) {
    const std::vector<FeatureObservation*>& obs = obs_;
    const FeatureObservation& f0 = *obs.front();
    if (!cams.count(f0.keyframe)) continue;
    const Pose& c0 = cams.at(f0.keyframe);
    const RayHit h = scene->index().Raycast(c0.translation(), c0.rotation() * k.Unproject(f0.top).normalized());
    if (!h.hit) continue;
    const int views = std::min<int>(static_cast<int>(obs.size()), 5);
    for (std::size_t j = 1; j < obs.size(); ++j) {
      const FeatureObservation& f = *obs[j];
      if (!cams.count(f.keyframe)) continue;
      const Pose& c = cams.at(f.keyframe);
      const Eigen::Vector3d pc = c.Inverse() * h.point;
      if (pc.z() <= 0) continue;
      const Eigen::Vector2d e = k.Project(pc) - f.top;
      ++pairs;
      if (e.norm() > max_error) {
        ++wrong;
        continue;
      }
      // The epipolar direction in image j at the feature: where the first
      // camera's centre projects (the epipole) towards the feature.
      const Eigen::Vector3d epi_c = c.Inverse() * c0.translation();
      Eigen::Vector2d dir;
      if (std::abs(epi_c.z()) > 1e-9) {
        dir = (f.top - k.Project(epi_c)).normalized();
        if (epi_c.z() < 0) dir = -dir;
      } else {
        dir = Eigen::Vector2d(epi_c.x(), epi_c.y()).normalized();
      }
      error_by_views[views].push_back(e.norm());
      along_by_views[views].push_back(std::abs(e.dot(dir)));
      across_by_views[views].push_back(std::abs(e.x() * dir.y() - e.y() * dir.x()));
    }
    if (obs.size() == 2 && cams.count(obs[1]->keyframe)) {
      const Pose& c1 = cams.at(obs[1]->keyframe);
      const Eigen::Vector3d X = TriangulateDlt(ProjectionMatrix(K, c0), ProjectionMatrix(K, c1), f0.top, obs[1]->top);
      if (X.allFinite() && (X - h.point).norm() < 0.5) {
        const ClosestPoint cp = scene->index().Closest(X);
        two_view_surface.push_back(cp.distance);
        // Signed: positive when the point stands in front of the surface (towards the first camera).
        two_view_signed.push_back((X - h.point).dot((c0.translation() - h.point).normalized()));
      }
    }
  }
  std::printf("%zu tracks, %zu pairs (first observation, another), %zu with an error > %.1f px (wrong matches)\n",
              tracks.size(), pairs, wrong, max_error);
  std::printf("relative localisation error (px) of the right pairs, by the track's views (5: 5 or more):\n");
  for (const auto& [v, e] : error_by_views) {
    std::printf(" %d views\n", v);
    PrintQuantiles("|error|", e);
    PrintQuantiles("along the epipolar line", along_by_views[v]);
    PrintQuantiles("across it", across_by_views[v]);
  }
  std::printf("two-view tracks triangulated with the true cameras (m):\n");
  PrintQuantiles("distance to the true surface", two_view_surface);
  std::vector<double> abs_signed;
  for (double s : two_view_signed) abs_signed.push_back(std::abs(s));
  PrintQuantiles("|offset along the first ray| from the hit", abs_signed);
  std::size_t within = 0;
  for (double d : two_view_surface) within += d <= 0.01;
  std::printf(
      "  within 1 cm of the surface: %.2f %%\n",
      100.0 * static_cast<double>(within) / static_cast<double>(std::max<std::size_t>(1, two_view_surface.size())));
  return 0;
}
