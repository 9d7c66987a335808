// Private to core/mosaic: what BuildMosaic (photomosaic.cc) shares with its
// visibility stage (mosaic_visibility.cc: the centroid grid, the views'
// candidate faces), its view-choice stages (mosaic_views.cc: edge
// splitting, face adjacency, the Potts labelling, feathering weights) and
// its atlas geometry
// (mosaic_atlas.cc: flat charts, shelf packing, barycentrics, bilinear
// image samples). Not installed, not for other modules.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <opencv2/core/mat.hpp>
#include <utility>
#include <vector>

#include "base/progress.h"
#include "geometry/mesh_index.h"
#include "geometry/triangle_mesh.h"
#include "mosaic/mosaic_camera.h"
#include "mosaic/photomosaic.h"

namespace hull {
namespace mosaic_internal {

constexpr int kSamples = 4;  // points per face for visibility and gains
constexpr int kMaxViewsPerVertex = 4;

struct Candidate {
  int view = -1;
  float score = 0;  // cos(incidence) / distance^2
  float value = 0;  // mean normalised value at the face's samples (before gains); <= 0: unusable for gains
};

// ---- mosaic_visibility.cc

// The centroid and three points toward the corners (85 % of the way): a face
// counts as seen only when all four are.
std::array<Eigen::Vector3d, kSamples> FaceSamples(const TriangleMesh& m, int f);

// The candidate rule for view v and face f: the centroid within max_range
// of the camera centre, the face turned toward it within max_incidence_deg,
// all three corners image_margin inside the width x height image (in front
// of the camera), and the rays from the four FaceSamples to the camera
// centre free (MeshIndex::OccludedToward, ignoring the first millimetre).
// score = cos(incidence) / distance^2.
struct Visibility {
  std::vector<std::vector<std::pair<int, float>>> seen;  // per view: (face, score), in face order
  std::size_t near = 0;                                  // (view, face) pairs with the centroid within the range
  std::size_t projected = 0;  // pairs in range, frontal, centroid in the frustum: corners projected
  std::size_t rays = 0;       // rays cast (four per pair with its corners in the image)
};
// Runs on the calling thread's TBB arena, in parallel over the views;
// a cancelled `progress` leaves the remaining views empty.
Visibility SeenFaces(const TriangleMesh& model, const MeshIndex& index, const std::vector<MosaicCamera>& cameras,
                     int width, int height, const MosaicOptions& options, Progress& progress);

// ---- mosaic_views.cc

// Splits every edge longer than max_edge of the faces that `near` accepts,
// conformingly: each round bisects the marked edges, a face with one, two
// or three marked edges becomes two, three or four triangles.
void SplitLongEdges(TriangleMesh& m, double max_edge, const std::function<bool(int)>& near);

// Face adjacency over shared edges: per face, the neighbour across edge
// i (corner i -> i+1), -1 on the border and at non-manifold edges.
std::vector<std::array<int, 3>> FaceNeighbours(const TriangleMesh& model);

// One MosaicFace per face of `cand` with its candidates counted and its view
// chosen: the best-scoring candidate, then Potts smoothing by iterated
// conditional modes (label_iterations, seam_weight).
std::vector<MosaicFace> ChooseViews(const std::vector<std::vector<Candidate>>& cand,
                                    const std::vector<std::array<int, 3>>& nbr, const MosaicOptions& options);

// Sparse per-vertex view weights.
struct ViewWeights {
  std::array<int, kMaxViewsPerVertex> view;
  std::array<float, kMaxViewsPerVertex> weight;
  ViewWeights() {
    view.fill(-1);
    weight.fill(0);
  }
  float Of(int v) const {
    for (int i = 0; i < kMaxViewsPerVertex; ++i) {
      if (view[static_cast<std::size_t>(i)] == v) return weight[static_cast<std::size_t>(i)];
    }
    return 0;
  }
};

// Feathering weights per vertex: the views of the incident faces by area,
// smoothed over feather_rings one-rings.
std::vector<ViewWeights> FeatherWeights(const TriangleMesh& model, const std::vector<MosaicFace>& faces,
                                        const MosaicOptions& options);

// ---- mosaic_atlas.cc

// Bilinear sample of an 8/16-bit, 1- or 3-channel image at pixel position
// (u, v) (pixel centres at integers), as shares of full scale; false outside.
bool Sample(const cv::Mat& img, double u, double v, float* out);

// A face's rectangle in the atlas and its corners there.
struct Chart {
  int x = 0, y = 0, w = 0, h = 0;        // texels
  std::array<Eigen::Vector2d, 3> local;  // corners in texels relative to (x, y)
};

// Lays the triangle out flat (longest edge along x) at `texel` m per texel
// with one texel of border.
Chart FlatChart(const TriangleMesh& m, int f, double texel);

// Shelf packing (tallest first) into rows of `width` texels; returns the height.
int PackShelves(std::vector<Chart>& charts, const std::vector<int>& order, int width);

// Barycentric coordinates of q in the 2-D triangle, clamped onto it (the
// closest point of the triangle in barycentric form); `inside` says whether
// q was inside already.
Eigen::Vector3d Barycentric(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& q, bool* inside);

}  // namespace mosaic_internal
}  // namespace hull
