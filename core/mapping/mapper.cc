#include "mapping/mapper.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <mutex>
#include <optional>

#include "base/csv.h"
#include "base/error.h"
#include "geometry/mesh_index.h"
#include "geometry/point_index.h"
#include "mapping/detected_objects.h"
#include "mapping/fouling.h"
#include "mapping/hull_zones.h"
#include "mapping/inspection.h"
#include "mapping/mesh_refinement.h"
#include "mapping/peak_fit.h"
#include "mapping/point_cone_tree.h"
#include "mapping/refinement_region.h"
#include "mapping/shape_detection.h"
#include "mapping/shape_fusion.h"

namespace hull {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Every option Algorithm 1 reads (DetectShapes).
struct ShapeKey {
  double tau, alpha, eps, grow_height;
  int min_points;
  bool keep_peaks;         // AdmitPeakPoints
  bool seed_across_views;  // SeededLandmarks
  bool operator==(const ShapeKey& o) const {
    return tau == o.tau && alpha == o.alpha && eps == o.eps && grow_height == o.grow_height &&
           min_points == o.min_points && keep_peaks == o.keep_peaks && seed_across_views == o.seed_across_views;
  }
};

struct InspectionKey {
  int stations;
  double bottom_angle, spacing, range;
  int min_points;
  bool operator==(const InspectionKey& o) const {
    return stations == o.stations && bottom_angle == o.bottom_angle && spacing == o.spacing && range == o.range &&
           min_points == o.min_points;
  }
};

// The top cameras whose keyframes observed at least min_points landmarks:
// a keyframe with fewer than DBSCAN needs for a cluster can detect nothing,
// so what its camera saw is not counted as inspected (images that showed
// nothing never rate a zone).
std::vector<Pose> InspectingCameras(const MappingInput& input, const std::vector<Pose>& x_M_cT, int min_points) {
  std::vector<Pose> out;
  for (std::size_t k = 0; k < input.keyframes.size(); ++k) {
    if (static_cast<int>(input.keyframes[k].landmarks.size()) >= min_points) out.push_back(x_M_cT[k]);
  }
  return out;
}

// The refined mesh with the structures built over it.
struct Refined {
  RefinedMesh refined;
  std::unique_ptr<PointConeTree> tree;
  std::unique_ptr<PointIndex> index;
};

// The refined mesh with vertices moved under features (the fusion along
// normals, SnapVerticesToFeatures) and the structures built over it.
struct Snapped {
  TriangleMesh mesh;
  std::unique_ptr<PointConeTree> tree;
  std::unique_ptr<PointIndex> index;
};

// The lumps' apexes beyond their highest features (peak_fit.h) that were
// accepted: where each stands on the CAD, and which of r.peaks it is.
struct AcceptedApexes {
  std::vector<Eigen::Vector3d> feet;
  std::vector<std::size_t> peak;  // per foot: index into MappingResult::peaks
  std::vector<int> vertex;        // per foot: the prior's vertex moved under it (-1: none)
};

AcceptedApexes AcceptApexes(const std::vector<FittedPeak>& peaks) {
  AcceptedApexes a;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    if (!peaks[i].accepted) continue;
    a.feet.push_back(peaks[i].foot);
    a.peak.push_back(i);
  }
  return a;
}

// The accepted apexes: the vertex under each rises to it where the fusion
// moved that vertex (the shapes of `fusion_support` views reach it) and left
// it lower. Each peak says why it was or was not placed.
void PlaceApexes(const AcceptedApexes& apexes, const TriangleMesh& prior, FusionResult& fused, MappingResult& r) {
  MappingSummary& s = r.summary;
  for (std::size_t i = 0; i < apexes.feet.size(); ++i) {
    FittedPeak& peak = r.peaks[apexes.peak[i]];
    ++s.peaks_fitted;
    const int v = apexes.vertex.empty() ? -1 : apexes.vertex[i];
    if (v < 0) {
      peak.placement = "no vertex could be moved under it";
      continue;
    }
    const std::size_t vi = static_cast<std::size_t>(v);
    if (fused.support[vi] == 0) {
      peak.placement = "its vertex is not fused";
      continue;
    }
    const double h = (fused.vertices[vi] - prior.vertices[vi]).dot(peak.normal);
    if (!(h < peak.height)) {
      peak.placement = "the fused vertex is already higher";
      continue;
    }
    fused.vertices[vi] = prior.vertices[vi] + peak.height * peak.normal;
    peak.placement = "placed";
    peak.vertex = v;
    ++s.peaks_placed;
  }
}

// The summary's counts of the shapes, the model and the areas.
void CountResult(const std::vector<KeyframeShapes>& shapes, const FusionResult& fused,
                 const InspectionCoverage& inspection, MappingResult& r) {
  MappingSummary& s = r.summary;
  s.keyframes = shapes.size();
  for (const auto& k : shapes) {
    s.points += k.points.size();
    for (const auto& p : k.points) s.points_clustered += p.cluster != ShapePoint::kBelowTau;
    s.shapes += k.shapes.size();
    if (!k.shapes.empty()) ++s.keyframes_with_shapes;
    for (const auto& sh : k.shapes) s.shape_triangles += sh.triangles.size();
  }
  s.model_vertices = r.model.num_vertices();
  s.model_faces = r.model.num_faces();
  for (const int c : fused.support) s.vertices_fused += c > 0;
  s.fusion_hits = fused.hits;
  s.hull_area = inspection.total_hull_area;
  s.inspected_area = inspection.total_inspected_area;
  for (const auto& z : r.zones) s.covered_area += z.covered_area;
}

}  // namespace

// The mapper's state, kept between runs: each stage reuses what the last run
// made when the options it reads are unchanged (shapes, the refined mesh,
// the inspected area).
struct Mapper::Impl {
  MappingInput input;
  TriangleMesh cad;
  std::unique_ptr<MeshIndex> cad_index;
  std::vector<Pose> x_M_cT;
  // Landmarks with a sigma_h (in M) and their sigmas; null when none has one.
  std::unique_ptr<PointIndex> landmark_sigma_index;
  std::vector<double> landmark_sigma;
  std::mutex mutex;
  int refinements = 0;

  std::optional<ShapeKey> shape_key;
  std::vector<KeyframeShapes> shapes;
  std::unique_ptr<Refined> refined;
  std::unique_ptr<Snapped> snapped;  // the last run's, when it fused along normals
  std::optional<InspectionKey> inspection_key;
  HullFrame hull;
  InspectionCoverage inspection;

  MappingResult Run(const MappingOptions& o, Progress& progress);

 private:
  void DetectShapesOnce(const MappingOptions& o, Progress& progress, MappingSummary& s);
  void RefineOnce(const MappingOptions& o, Progress& progress, MappingSummary& s);
  std::vector<PeakFeature> SnapToFeatures(const MappingOptions& o, AcceptedApexes& apexes,
                                          std::vector<int>* peak_vertex);
  void MeasureDeviation(const MappingOptions& o, const TriangleMesh& prior, const FusionResult& fused,
                        MappingResult& r) const;
  void MeasureInspectionOnce(const MappingOptions& o, Progress& progress, MappingSummary& s);
};

Mapper::Mapper(MappingInput input, TriangleMesh cad) : impl_(std::make_unique<Impl>()) {
  impl_->input = std::move(input);
  impl_->cad = std::move(cad);
  impl_->cad.vertex_scalars.clear();
  impl_->cad.ComputeNormals();
  impl_->cad_index = std::make_unique<MeshIndex>(impl_->cad);
  const Pose x_Mg = impl_->input.x_gM.Inverse();
  for (const auto& k : impl_->input.keyframes) impl_->x_M_cT.push_back(x_Mg * k.x_g_cT);
  std::vector<Eigen::Vector3d> with_sigma;
  for (const auto& l : impl_->input.landmarks) {
    if (!(l.sigma_h > 0)) continue;
    with_sigma.push_back(x_Mg * l.p_g);
    impl_->landmark_sigma.push_back(l.sigma_h);
  }
  if (!with_sigma.empty()) impl_->landmark_sigma_index = std::make_unique<PointIndex>(with_sigma);
}

Mapper::~Mapper() = default;

const MappingInput& Mapper::input() const { return impl_->input; }
const TriangleMesh& Mapper::cad() const { return impl_->cad; }
int Mapper::refinements() const { return impl_->refinements; }
const TriangleMesh* Mapper::prior_mesh() const {
  if (impl_->snapped) return &impl_->snapped->mesh;
  return impl_->refined ? &impl_->refined->refined.mesh : nullptr;
}

MappingResult Mapper::Run(const MappingOptions& options, Progress& progress) {
  options.Check();
  std::lock_guard<std::mutex> lock(impl_->mutex);
  tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
  MappingResult result;
  arena.execute([&] { result = impl_->Run(options, progress); });
  return result;
}

// Algorithm 1 per keyframe, again only when an option it reads changed.
void Mapper::Impl::DetectShapesOnce(const MappingOptions& o, Progress& progress, MappingSummary& s) {
  const auto t = Clock::now();
  progress.Update(0.0, "detecting shapes (Algorithm 1)");
  const ShapeKey sk{o.tau,
                    o.alpha,
                    o.dbscan_eps,
                    o.shape_grow_height,
                    o.dbscan_min_points,
                    o.fusion_keep_peaks,
                    o.shape_seed_across_views};
  if (!shape_key || !(*shape_key == sk)) {
    shape_key.reset();
    shapes = DetectAllShapes(input, o, progress);
    shape_key = sk;
  }
  s.seconds.shapes = Since(t);
}

// The region where shapes depart from the CAD, and the mesh refined there
// (kept when the last refinement already covers the region at this edge).
void Mapper::Impl::RefineOnce(const MappingOptions& o, Progress& progress, MappingSummary& s) {
  auto t = Clock::now();
  progress.Update(0.2, "finding where the shapes depart from the model");
  SubProgress region_progress(progress, 0.2, 0.3);
  const RefinementRegion region = DepartureRegion(shapes, x_M_cT, *cad_index, o, region_progress);
  s.seconds.region = Since(t);
  t = Clock::now();
  const bool same_edge = refined && refined->refined.edge == o.refine_edge;
  if (same_edge && refined->refined.region.Includes(region)) {
    s.refinement_reused = true;
  } else {
    progress.Update(0.3, "refining the model where shapes depart from it");
    RefinementRegion grown = region;
    if (same_edge) grown.Merge(refined->refined.region);
    auto next = std::make_unique<Refined>();
    next->refined = RefineMesh(cad, *cad_index, grown, o.refine_edge);
    next->tree = std::make_unique<PointConeTree>(next->refined.mesh.vertices);
    next->index = std::make_unique<PointIndex>(next->refined.mesh.vertices);
    refined = std::move(next);
    ++refinements;
    progress.ThrowIfCancelled();
  }
  s.seconds.refinement = Since(t);
  s.region_cells = refined->refined.region.num_cells();
  s.refined_area = refined->refined.refined_area;
}

// Fusion along normals: the refined mesh with vertices moved under the
// features and the accepted apexes (SnapVerticesToFeatures; `snapped`), and
// the peak features (shape_fusion.h: lump tops that no keyframe could mesh)
// with the vertex under each.
std::vector<PeakFeature> Mapper::Impl::SnapToFeatures(const MappingOptions& o, AcceptedApexes& apexes,
                                                      std::vector<int>* peak_vertex) {
  const Pose x_Mg = input.x_gM.Inverse();
  std::vector<Eigen::Vector3d> landmarks_M(input.landmarks.size());
  std::vector<double> landmark_deviation(input.landmarks.size());
  for (std::size_t i = 0; i < input.landmarks.size(); ++i) {
    landmarks_M[i] = x_Mg * input.landmarks[i].p_g;
    landmark_deviation[i] = input.landmarks[i].deviation;
  }
  std::vector<PeakFeature> peak_features = FindPeakFeatures(shapes, landmarks_M, landmark_deviation, *cad_index, o.tau,
                                                            o.object_min_height, o.dbscan_eps, o.fusion_support);
  auto next = std::make_unique<Snapped>();
  next->mesh = refined->refined.mesh;
  SnapVerticesToFeatures(next->mesh, *refined->index, *cad_index, shapes, x_Mg, o.fusion_support, o.object_min_height,
                         0.6 * o.refine_edge, apexes.feet, &apexes.vertex, peak_features, peak_vertex);
  next->tree = std::make_unique<PointConeTree>(next->mesh.vertices);
  next->index = std::make_unique<PointIndex>(next->mesh.vertices);
  snapped = std::move(next);
  return peak_features;
}

// The remeshed model: every vertex's signed distance to the CAD surface
// (fused or not: a vertex no shape touched lies on the CAD, within
// rounding), its fusion count, and the sigma_h of the nearest landmark that
// has one with whether the deviation is significant against it.
void Mapper::Impl::MeasureDeviation(const MappingOptions& o, const TriangleMesh& prior, const FusionResult& fused,
                                    MappingResult& r) const {
  std::vector<double> deviation(prior.num_vertices(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, prior.num_vertices(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        deviation[i] = cad_index->SignedDistance(fused.vertices[i]);
                      }
                    });
  r.model.vertices = fused.vertices;
  r.model.faces = prior.faces;
  r.model.ComputeNormals();
  r.model.SetScalar("deviation", deviation);
  r.model.SetScalar("fusions", std::vector<double>(fused.count.begin(), fused.count.end()));
  if (!landmark_sigma_index) return;
  std::vector<double> sigma(prior.num_vertices(), std::nan("")), significant(prior.num_vertices(), 0.0);
  tbb::parallel_for(std::size_t(0), prior.num_vertices(), [&](std::size_t i) {
    const auto nearest = landmark_sigma_index->NearestOne(fused.vertices[i]);
    if (nearest.first < 0) return;
    sigma[i] = landmark_sigma[static_cast<std::size_t>(nearest.first)];
    significant[i] = std::abs(deviation[i]) > o.significance_k * sigma[i] ? 1.0 : 0.0;
  });
  r.model.SetScalar("sigma", sigma);
  r.model.SetScalar("significant", significant);
}

// The inspected area, again only when an option it reads changed; a survey
// that inspected none of the model is InsufficientData.
void Mapper::Impl::MeasureInspectionOnce(const MappingOptions& o, Progress& progress, MappingSummary& s) {
  const auto t = Clock::now();
  const InspectionKey ik{o.stations, o.bottom_angle_deg, o.inspection_spacing, o.inspection_range, o.dbscan_min_points};
  if (!inspection_key || !(*inspection_key == ik)) {
    progress.Update(0.85, "measuring the inspected area");
    inspection_key.reset();
    hull = MakeHullFrame(cad, input.model_axes, input.x_gM, o.stations, o.bottom_angle_deg);
    SubProgress inspection_progress(progress, 0.85, 0.95);
    inspection = MeasureInspection(cad, *cad_index, hull, InspectingCameras(input, x_M_cT, o.dbscan_min_points),
                                   input.camera, o.inspection_spacing, o.inspection_range, inspection_progress);
    inspection_key = ik;
  }
  s.seconds.inspection = Since(t);
  if (inspection.total_inspected_area <= 0) {
    throw InsufficientData("mapping", "the survey inspected none of the model: no keyframe with " +
                                          std::to_string(o.dbscan_min_points) +
                                          " landmarks or more sees the CAD surface within " +
                                          FormatDouble(o.inspection_range) + " m (a wrong mesh or model pose?)");
  }
}

MappingResult Mapper::Impl::Run(const MappingOptions& o, Progress& progress) {
  const auto start = Clock::now();
  MappingResult r;
  r.options = o;
  MappingSummary& s = r.summary;
  s.source = input.source;
  if (input.landmarks.empty()) {
    throw InsufficientData("mapping",
                           "the adjustment holds no landmarks: nothing was measured on the hull, so nothing can be "
                           "mapped or rated");
  }
  DetectShapesOnce(o, progress, s);
  RefineOnce(o, progress, s);
  snapped.reset();
  // Lumps' apexes beyond their highest features: a vertex is moved under
  // each accepted apex, before the features' vertices.
  if (o.fusion_along_normal && o.fusion_keep_peaks && o.peak_fit) {
    r.peaks = FitPeaks(input, *cad_index, shapes, PeakFitOptionsFor(o));
  }
  AcceptedApexes apexes = AcceptApexes(r.peaks);
  std::vector<PeakFeature> peak_features;
  std::vector<int> peak_vertex;
  if (o.fusion_along_normal && o.fusion_keep_peaks) peak_features = SnapToFeatures(o, apexes, &peak_vertex);
  const TriangleMesh& prior = snapped ? snapped->mesh : refined->refined.mesh;
  const PointConeTree& prior_tree = snapped ? *snapped->tree : *refined->tree;
  const PointIndex& prior_index = snapped ? *snapped->index : *refined->index;

  // Algorithm 2.
  auto t = Clock::now();
  progress.Update(0.5, "fusing shapes into the model (Algorithm 2)");
  SubProgress fusion_progress(progress, 0.5, 0.8);
  const FusionRule rule{o.fusion_keep_peaks, o.fusion_support, o.fusion_peak_band, o.fusion_along_normal};
  FusionResult fused = FuseShapes(prior, prior_tree, x_M_cT, shapes, o.fusion_radius, rule, fusion_progress);
  PlaceApexes(apexes, prior, fused, r);
  if (!peak_features.empty()) {
    s.peak_features = peak_features.size();
    s.peak_features_raised =
        static_cast<std::size_t>(RaisePeakFeatures(prior, peak_features, peak_vertex, o.object_min_height, fused));
  }
  s.seconds.fusion = Since(t);

  t = Clock::now();
  progress.Update(0.8, "measuring the fused model's deviation from the CAD");
  MeasureDeviation(o, prior, fused, r);
  s.seconds.deviation = Since(t);
  progress.ThrowIfCancelled();
  MeasureInspectionOnce(o, progress, s);

  // Objects and the assessment.
  t = Clock::now();
  progress.Update(0.95, "detecting objects and rating the zones");
  const std::vector<double>& deviation = *r.model.FindScalar("deviation");
  ObjectDetection objects = DetectObjects(prior, deviation, prior_index, *cad_index, hull, input, shapes, o);
  r.zones = AssessFouling(hull, inspection, objects);
  r.objects = std::move(objects.objects);
  s.seconds.objects = Since(t);
  r.hull = hull;
  r.keyframes = shapes;
  CountResult(shapes, fused, inspection, r);
  s.seconds.total = Since(start);
  progress.Update(1.0, "mapped: " + std::to_string(r.objects.size()) + " objects");
  return r;
}

MappingResult RunMapping(MappingInput input, TriangleMesh cad, const MappingOptions& options, Progress& progress) {
  Mapper mapper(std::move(input), std::move(cad));
  return mapper.Run(options, progress);
}

}  // namespace hull
