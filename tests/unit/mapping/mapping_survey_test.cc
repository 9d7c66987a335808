// Model-assisted mapping of simulated, adjusted surveys (Ozog et al.,
// Section 4.2): what the issue asks it to show, for stereo and mono. Each
// preset is simulated and adjusted once (about 5-10 s) and mapped by two
// Mappers kept alive as the GUI keeps one: the paper's parameters
// (eps = 0.10 m, alpha = 0.12 m) and parameters suited to the simulator's
// feature density (eps = 0.20 m, alpha = 0.30 m; see docs/mapping.md).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "adjust/bundle_adjuster.h"
#include "base/csv.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"
#include "mapping/mapper.h"
#include "mapping/object_height_check.h"
#include "mapping/shape_fusion.h"
#include "mapping/surface_clip.h"
#include "results/mapping_files.h"
#include "simulate/survey_simulator.h"

namespace hull {
namespace {

enum class Params { kPaper, kDense };

MappingOptions Options(Params params, double tau) {
  MappingOptions o;
  o.tau = tau;
  if (params == Params::kDense) {
    o.dbscan_eps = 0.20;
    o.alpha = 0.30;
  }
  return o;
}

const char* Name(Params p) { return p == Params::kPaper ? "paper eps/alpha" : "dense eps/alpha"; }

struct Case {
  SimulatedSurvey survey;
  AdjustmentResult adjustment;
  std::map<Params, std::unique_ptr<Mapper>> mappers;
  std::map<std::pair<Params, double>, MappingResult> runs;
  // The adjusted model frame to the true one. Where the surveyed hull cannot
  // fix the model pose (sliding along a flat bottom: the gauge of
  // core/adjust/evaluation.h), the adjusted M is the true M moved along the
  // hull, so positions are compared after the rigid fit of the adjusted
  // landmarks (in the adjusted M) onto the true ones (in the true M).
  Pose est_to_true;
  Eigen::Vector3d ToTrue(const Eigen::Vector3d& p) const { return est_to_true * p; }
};

Case& GetCase(const std::string& preset) {
  static std::map<std::string, std::unique_ptr<Case>> cache;
  auto it = cache.find(preset);
  if (it != cache.end()) return *it->second;
  NullProgress p;
  auto c = std::make_unique<Case>();
  c->survey = SimulateSurvey(SurveyPreset(preset), p);
  c->adjustment = RunAdjustment(c->survey.bundle, c->survey.cad,
                                Pose::FromVector(*c->survey.bundle.manifest.model_pose_guess), AdjustmentOptions{}, p);
  c->est_to_true = GaugeFitToTruth(c->survey.bundle, c->adjustment);
  std::printf("[%s] adjusted model frame vs the true one: %.3f m, %.3f deg (the survey's gauge)\n", preset.c_str(),
              c->est_to_true.translation().norm(), Pose::AngleBetween(c->est_to_true, Pose()) * 180 / M_PI);
  for (const Params params : {Params::kPaper, Params::kDense}) {
    c->mappers[params] =
        std::make_unique<Mapper>(MappingInputFromAdjustment(c->adjustment, c->survey.bundle), c->survey.cad);
  }
  return *cache.emplace(preset, std::move(c)).first->second;
}

const MappingResult& Map(const std::string& preset, Params params, double tau) {
  Case& c = GetCase(preset);
  auto it = c.runs.find({params, tau});
  if (it != c.runs.end()) return it->second;
  NullProgress p;
  MappingResult r = c.mappers.at(params)->Run(Options(params, tau), p);
  const MappingSummary& s = r.summary;
  std::printf(
      "[%s, %s, tau %.2f] %zu shapes (%zu triangles); model %zu vertices (%.2f m^2 refined%s), %zu fused; "
      "%zu objects; %.2f s (shapes %.2f, region %.2f, refinement %.2f, fusion %.2f, inspection %.2f)\n",
      preset.c_str(), Name(params), tau, s.shapes, s.shape_triangles, s.model_vertices, s.refined_area,
      s.refinement_reused ? ", reused" : "", s.vertices_fused, r.objects.size(), s.seconds.total, s.seconds.shapes,
      s.seconds.region, s.seconds.refinement, s.seconds.fusion, s.seconds.inspection);
  return c.runs.emplace(std::make_pair(params, tau), std::move(r)).first->second;
}

// Tangent-plane geometry of a true object (as MakeObjectMesh orients it).
struct Footprint {
  const TrueObject* o;
  const TriangleMesh* mesh;
  Eigen::Vector3d e1, e2, n;
  Footprint(const TrueObject& obj, const TriangleMesh& m) : o(&obj), mesh(&m) {
    n = obj.normal.normalized();
    e1 = Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitX().dot(n) * n;
    if (e1.norm() < 1e-6) e1 = n.unitOrthogonal();
    e1.normalize();
    e2 = n.cross(e1);
  }
  // Distance (in the tangent plane) from p to the footprint; 0 inside.
  double Outside(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - o->center;
    if (o->kind == ObjectKind::kBox) {
      const double x = std::max(0.0, std::abs(d.dot(e1)) - 0.5 * o->size.x());
      const double y = std::max(0.0, std::abs(d.dot(e2)) - 0.5 * o->size.y());
      return std::hypot(x, y);
    }
    return std::max(0.0, std::hypot(d.dot(e1), d.dot(e2)) - o->radius);
  }
  double Width() const { return o->kind == ObjectKind::kBox ? std::min(o->size.x(), o->size.y()) : 2 * o->radius; }
  bool Required() const { return o->Height() >= 0.06 && Width() >= 0.2; }
  // The true footprint area where the object stands more than h above the
  // hull (its top surface clipped at height h, projected on the tangent plane).
  double AreaAbove(double h) const {
    double area = 0;
    for (const Face& f : mesh->faces) {
      ClipPolygon poly;
      for (const int v : f) {
        const Eigen::Vector3d d = mesh->vertices[static_cast<std::size_t>(v)] - o->center;
        poly.push_back({o->center + d.dot(e1) * e1 + d.dot(e2) * e2, d.dot(n)});
      }
      const Eigen::Vector3d a = mesh->vertices[static_cast<std::size_t>(f[0])];
      const Eigen::Vector3d normal = (mesh->vertices[static_cast<std::size_t>(f[1])] - a)
                                         .cross(mesh->vertices[static_cast<std::size_t>(f[2])] - a);
      if (!(normal.dot(n) > 1e-12)) continue;  // the top surface only
      ClipKeep(poly, [h](const ClipVertex& c) { return c.value - h; });
      area += Moments(poly).area;
    }
    return area;
  }
};

std::vector<Footprint> Footprints(const Case& c) {
  std::vector<Footprint> f;
  for (std::size_t i = 0; i < c.survey.bundle.truth->objects.size(); ++i) {
    f.emplace_back(c.survey.bundle.truth->objects[i], c.survey.object_meshes[i]);
  }
  return f;
}

// A detected object's region reaches into a true footprint (grown by tolerance).
bool Touches(const Case& c, const MappingResult& r, const DetectedObject& d, const Footprint& f, double tolerance) {
  for (const int v : d.vertices) {
    if (f.Outside(c.ToTrue(r.model.vertices[static_cast<std::size_t>(v)])) <= tolerance) return true;
  }
  return false;
}

// Detected objects not within 10 cm of any true object.
int CountFalseObjects(const Case& c, const MappingResult& r, const char* label) {
  int n = 0;
  for (const auto& d : r.objects) {
    bool near = false;
    for (const auto& f : Footprints(c)) near = near || Touches(c, r, d, f, 0.10);
    if (near) continue;
    ++n;
    std::printf("    %s: false object %s at %.2f m from the bow: %.4f m^2, max height %.3f m, %d features, %d views\n",
                label, d.id.c_str(), d.distance_from_bow, d.area, d.max_height, d.num_features, d.num_views);
  }
  return n;
}

struct Detection {
  int required = 0, detected = 0;
  int undetectable = 0;  // required, but smaller above h_min than min_area: not an object by definition
  int marginal = 0;      // required, an object by definition, but at most 1.5 x min_area above h_min
  int missed_clear = 0;  // required, larger than that, and not detected
};

// How much of an object stands above h_min decides whether it is an object:
// below min_area it is not one by definition; up to 1.5 x min_area the
// fused surface, which interpolates the few features on it and so cuts its
// peak, covers about min_area above h_min and the detection goes either way
// (patch-2 of the demo: 0.014 m^2 true, 3 features above h_min, fused to
// 0.010-0.013 m^2 above h_min depending on the mesh and the preset).
Detection Detect(const std::string& preset, Params params) {
  const Case& c = GetCase(preset);
  const MappingResult& r = Map(preset, params, 0.0);
  Detection out;
  std::map<std::string, int> features;
  {
    std::map<std::int64_t, std::string> object_of;
    for (const auto& l : c.survey.bundle.truth->landmarks) object_of[l.landmark] = l.object;
    for (const auto& l : c.adjustment.landmarks) {
      const std::string& o = object_of.at(l.id);
      if (!o.empty() && l.deviation > r.options.object_min_height) ++features[o];
    }
  }
  for (const auto& f : Footprints(c)) {
    const DetectedObject* hit = nullptr;
    for (const auto& d : r.objects) {
      if (!hit && Touches(c, r, d, f, 0.0)) hit = &d;
    }
    const double above = f.AreaAbove(r.options.object_min_height);
    const bool definable = above >= r.options.object_min_area;
    const bool marginal = definable && above <= 1.5 * r.options.object_min_area;
    std::string status = hit ? "detected as " + hit->id + " (" + std::to_string(hit->area).substr(0, 6) + " m^2)"
                             : std::string("NOT detected");
    if (!f.Required()) {
      status += " (not required)";
    } else if (!definable) {
      status += " (below min_area above h_min)";
    } else if (marginal) {
      status += " (marginal: at most 1.5 x min_area above h_min)";
    }
    std::printf("  %-9s %-8s height %.3f width %.3f, true area above h_min %.4f m^2, %2d features above h_min: %s\n",
                f.o->id.c_str(), ObjectKindName(f.o->kind), f.o->Height(), f.Width(), above, features[f.o->id],
                status.c_str());
    if (!f.Required()) continue;
    ++out.required;
    if (hit) ++out.detected;
    if (!definable) ++out.undetectable;
    if (marginal) ++out.marginal;
    if (!hit && definable && !marginal) ++out.missed_clear;
  }
  std::printf(
      "[%s, %s, tau 0] %d of %d required objects detected (%d below min_area above h_min, %d marginal); "
      "%d false objects\n",
      preset.c_str(), Name(params), out.detected, out.required, out.undetectable, out.marginal,
      CountFalseObjects(c, r, "tau 0"));
  return out;
}

void EveryDetectableLargeObjectIsDetectedAtTauZero(const std::string& preset) {
  // With eps and alpha suited to the simulated feature density, every
  // required object with more than 1.5 x min_area above h_min is detected
  // (see Detect() for the marginal ones; on these surveys: patch-3, not an
  // object by definition, and patch-2).
  const Detection d = Detect(preset, Params::kDense);
  EXPECT_GE(d.required - d.undetectable - d.marginal, 15);  // the clear cases, all to be detected
  EXPECT_EQ(d.missed_clear, 0);
}

void PaperParametersDetectMostLargeObjects(const std::string& preset) {
  // The paper's eps and alpha were chosen for denser features than the
  // simulator's ~150 per m^2 of foreign structure: objects sampled by a few
  // features at most 10 cm apart can form no cluster (measured: 15 of 19
  // detected on both presets; see docs/mapping.md).
  const Detection d = Detect(preset, Params::kPaper);
  EXPECT_GE(d.detected, d.required - 4);
}

void CylinderHeightOnTheRemeshedModel(const std::string& preset) {
  const Case& c = GetCase(preset);
  for (const Params params : {Params::kPaper, Params::kDense}) {
    const MappingResult& r = Map(preset, params, 0.0);
    const TrueObject* cyl = nullptr;
    for (const auto& o : c.survey.bundle.truth->objects) {
      if (o.id == "cyl-1") cyl = &o;
    }
    ASSERT_NE(cyl, nullptr);
    const Footprint f(*cyl, c.survey.cad);
    const std::vector<double>& dev = *r.model.FindScalar("deviation");
    const std::vector<double>& fusions = *r.model.FindScalar("fusions");
    std::vector<double> top;
    for (std::size_t v = 0; v < r.model.num_vertices(); ++v) {
      const Eigen::Vector3d d = c.ToTrue(r.model.vertices[v]) - cyl->center;
      if (fusions[v] > 0 && std::hypot(d.dot(f.e1), d.dot(f.e2)) < cyl->radius - 0.05) top.push_back(dev[v]);
    }
    ASSERT_GE(top.size(), 20u);
    std::nth_element(top.begin(), top.begin() + static_cast<long>(top.size() / 2), top.end());
    const double median = top[top.size() / 2];
    const double highest = *std::max_element(top.begin(), top.end());
    std::printf(
        "[%s, %s] cylinder (true height %.3f m): median %.4f m, max %.4f m over %zu fused vertices of its "
        "top (within %.2f m of its axis)\n",
        preset.c_str(), Name(params), cyl->height, median, highest, top.size(), cyl->radius - 0.05);
    EXPECT_NEAR(median, cyl->height, 0.015);
  }
}

void ModelStaysOnTheCadAwayFromObjects(const std::string& preset) {
  const Case& c = GetCase(preset);
  const auto foot = Footprints(c);
  // How far the adjusted features of the clean hull lie from the CAD: the
  // fused surface passes through them, so it cannot be flatter.
  std::vector<double> hull;
  double hull_beyond_share = 0;
  {
    std::map<std::int64_t, std::string> object_of;
    for (const auto& l : c.survey.bundle.truth->landmarks) object_of[l.landmark] = l.object;
    for (const auto& l : c.adjustment.landmarks) {
      if (object_of.at(l.id).empty()) hull.push_back(std::abs(l.deviation));
    }
    std::sort(hull.begin(), hull.end());
    const auto beyond = std::count_if(hull.begin(), hull.end(), [](double d) { return d > 0.01; });
    hull_beyond_share = static_cast<double>(beyond) / static_cast<double>(hull.size());
    std::printf(
        "[%s] adjusted hull features: |deviation| median %.4f m, 99th percentile %.4f m, max %.4f m; "
        "%.2f %% beyond 1 cm\n",
        preset.c_str(), hull[hull.size() / 2], hull[hull.size() * 99 / 100], hull.back(),
        100.0 * static_cast<double>(beyond) / static_cast<double>(hull.size()));
  }
  for (const Params params : {Params::kPaper, Params::kDense}) {
    const MappingResult& r = Map(preset, params, 0.0);
    const std::vector<double>& dev = *r.model.FindScalar("deviation");
    const std::vector<double>& fusions = *r.model.FindScalar("fusions");
    std::size_t away = 0;
    std::vector<double> fused;
    for (std::size_t v = 0; v < r.model.num_vertices(); ++v) {
      bool far = true;
      for (const auto& f : foot) far = far && f.Outside(c.ToTrue(r.model.vertices[v])) > 0.3;
      if (!far) continue;
      ++away;
      if (fusions[v] > 0) fused.push_back(std::abs(dev[v]));
      if (!(fusions[v] > 0)) {
        EXPECT_NEAR(dev[v], 0.0, 1e-9);  // never hit: the CAD vertex itself (its distance, computed)
      }
    }
    std::sort(fused.begin(), fused.end());
    const auto beyond = std::count_if(fused.begin(), fused.end(), [](double d) { return d > 0.01; });
    const double p99 = fused.empty() ? 0 : fused[fused.size() * 99 / 100];
    const double worst = fused.empty() ? 0 : fused.back();
    std::printf(
        "[%s, %s] %zu vertices > 0.3 m from every object, %zu of them fused: |deviation| 99th percentile "
        "%.4f m, max %.4f m, %zd beyond 1 cm\n",
        preset.c_str(), Name(params), away, fused.size(), p99, worst, beyond);
    EXPECT_GT(away, 1000u);
    // Within 1 cm except where the features it passes through lie further
    // off themselves (2-6 % of the adjusted hull features do, up to 2.5 cm):
    // no larger a share beyond 1 cm than the features', and no worse than
    // the worst of them by more than 1.5 mm (a shape's flat triangle
    // between features below a convex hull lies deeper than they do, by its
    // sagitta; along the normals the demo's worst fused vertex was 0.8 mm
    // beyond its worst feature, then 0.7 mm, and 1.1 mm with the cavity
    // labels of the adjustment: a vertex under a dense-alpha triangle with
    // no feature within 8 cm, 0.0214 -> 0.0217 m, the worst feature
    // 0.0207 -> 0.0206 m).
    EXPECT_LE(static_cast<double>(beyond) / static_cast<double>(fused.size()), hull_beyond_share + 0.005);
    EXPECT_LE(p99, hull[hull.size() * 99 / 100] + 0.001);
    EXPECT_LE(worst, hull.back() + 0.0015);
    // With the dense parameters the hull's own features form shapes (at
    // tau = 0 they cover much of what was seen), so this is no empty claim.
    if (params == Params::kDense) {
      EXPECT_GT(fused.size(), 1000u);
    }
  }
}

void NoFalseObjectsAtTauSixCentimetres(const std::string& preset) {
  const Case& c = GetCase(preset);
  for (const Params params : {Params::kPaper, Params::kDense}) {
    const MappingResult& r = Map(preset, params, 0.06);
    const int n = CountFalseObjects(c, r, "tau 0.06");
    std::printf("[%s, %s, tau 0.06] %zu objects, %d false\n", preset.c_str(), Name(params), r.objects.size(), n);
    EXPECT_EQ(n, 0);
    EXPECT_GE(r.objects.size(), 3u);
  }
}

void RerunAfterTauChangeReusesTheRefinedMesh(const std::string& preset) {
  Case& c = GetCase(preset);
  for (const Params params : {Params::kPaper, Params::kDense}) {
    const MappingResult& low = Map(preset, params, 0.0);
    const int before = c.mappers.at(params)->refinements();
    NullProgress p;
    for (const double tau : {0.03, 0.06, 0.1}) {
      const MappingResult r = c.mappers.at(params)->Run(Options(params, tau), p);
      EXPECT_TRUE(r.summary.refinement_reused) << "tau " << tau;
      EXPECT_LT(r.summary.points_clustered, low.summary.points_clustered);
      std::printf("[%s, %s] re-run at tau %.2f: %.3f s\n", preset.c_str(), Name(params), tau, r.summary.seconds.total);
    }
    EXPECT_EQ(c.mappers.at(params)->refinements(), before);
  }
}

void UnseenZonesAreUninspectedAndSeenOnesRated(const std::string& preset) {
  const MappingResult& r = Map(preset, Params::kPaper, 0.0);
  int inspected = 0, uninspected = 0;
  double seen = 0;
  for (const auto& z : r.zones) {
    if (z.rating == FoulingRating::kUninspected) {
      ++uninspected;
      EXPECT_EQ(z.inspected_area, 0.0);
      EXPECT_EQ(z.covered_area, 0.0);
      continue;
    }
    ++inspected;
    seen += z.inspected_area;
    EXPECT_LE(z.inspected_area, z.hull_area + 1e-9);
    EXPECT_EQ(z.rating, RateCover(z.cover_percent));
    std::printf("  station %2d %-9s hull %.1f m^2, inspected %.2f m^2, covered %.3f m^2 (%.2f %%), rating %s\n",
                z.station, HullSideName(z.side), z.hull_area, z.inspected_area, z.covered_area, z.cover_percent,
                FoulingRatingName(z.rating));
  }
  // The demo surveys a 12 m stretch of bottom around the keel (about 5 m
  // wide at 1.5 m standoff): a few bottom zones, the rest never.
  EXPECT_GE(inspected, 1);
  EXPECT_LE(inspected, 4);
  EXPECT_GT(uninspected, 50);
  EXPECT_GT(seen, 40.0);
  EXPECT_LT(seen, 150.0);
  double covered = 0, objects = 0;
  for (const auto& z : r.zones) covered += z.covered_area;
  for (const auto& o : r.objects) objects += o.area;
  EXPECT_NEAR(covered, objects, 1e-9);
}

void FastFusionEqualsThePapersLoops(const std::string& preset) {
  Case& c = GetCase(preset);
  Mapper& mapper = *c.mappers.at(Params::kDense);
  NullProgress p;
  // Along the camera's rays (the paper's) and along the vertex normals (the
  // default; its prior is the refined mesh with vertices moved under
  // features).
  for (const bool along_normal : {false, true}) {
    SCOPED_TRACE(along_normal ? "along the normals" : "along the camera's rays");
    MappingOptions options = Options(Params::kDense, 0.0);
    options.fusion_along_normal = along_normal;
    const MappingResult last = mapper.Run(options, p);  // fused into prior_mesh()
    ASSERT_NE(mapper.prior_mesh(), nullptr);
    const TriangleMesh& prior = *mapper.prior_mesh();
    std::vector<Pose> x_M_cT;
    for (const auto& k : mapper.input().keyframes) x_M_cT.push_back(mapper.input().x_gM.Inverse() * k.x_g_cT);
    const FusionRule rule{last.options.fusion_keep_peaks, last.options.fusion_support, last.options.fusion_peak_band,
                          last.options.fusion_along_normal};
    const FusionResult brute = FuseShapesBruteForce(prior, x_M_cT, last.keyframes, last.options.fusion_radius, rule);
    const FusionResult fast =
        FuseShapes(prior, PointConeTree(prior.vertices), x_M_cT, last.keyframes, last.options.fusion_radius, rule, p);
    ASSERT_EQ(fast.vertices.size(), brute.vertices.size());
    EXPECT_EQ(fast.hits, brute.hits);
    EXPECT_GT(fast.hits, 1000u);
    std::size_t differ = 0;
    for (std::size_t v = 0; v < fast.vertices.size(); ++v) {
      differ += fast.count[v] != brute.count[v] || fast.vertices[v] != brute.vertices[v];
    }
    EXPECT_EQ(differ, 0u);
    // The run's model is that fusion, with the vertices under the apexes
    // the peak fit placed raised to them.
    std::vector<Eigen::Vector3d> expected = fast.vertices;
    for (const FittedPeak& f : last.peaks) {
      if (f.vertex < 0) continue;
      const std::size_t v = static_cast<std::size_t>(f.vertex);
      expected[v] = prior.vertices[v] + f.height * f.normal;
    }
    if (along_normal) {
      EXPECT_GT(last.summary.peaks_placed, 0u);
    }
    EXPECT_EQ(last.model.vertices, expected);
  }
}

void WritesTheResultsFolder(const std::string& preset) {
  const MappingResult& r = Map(preset, Params::kPaper, 0.0);
  const std::string dir = std::string(HI_BINARY_DIR) + "/test-output/mapping-" + preset;
  std::filesystem::remove_all(dir);
  WriteMappingResult(r, dir);
  MeshLoadOptions raw;
  raw.weld = false;
  raw.orient_outward = false;
  const TriangleMesh ply = LoadMesh(dir + "/model.ply", raw);
  ASSERT_EQ(ply.num_vertices(), r.model.num_vertices());
  ASSERT_NE(ply.FindScalar("deviation"), nullptr);
  EXPECT_EQ(*ply.FindScalar("deviation"), *r.model.FindScalar("deviation"));
  EXPECT_EQ(LoadMesh(dir + "/model.obj", raw).num_faces(), r.model.num_faces());
  EXPECT_EQ(LoadMesh(dir + "/model.stl", raw).num_faces(), r.model.num_faces());
  const std::string objects = ReadFileToString(dir + "/objects.csv");
  CsvReader csv(objects, "objects.csv");
  std::size_t rows = 0;
  while (csv.Next()) ++rows;
  EXPECT_EQ(rows, r.objects.size());
  const Json zones = Json::Parse(ReadFileToString(dir + "/zones.json"), "zones.json");
  ASSERT_NE(zones.Get("zones"), nullptr);
  EXPECT_EQ(zones.Get("zones")->items().size(), r.zones.size());
  const Json summary = Json::Parse(ReadFileToString(dir + "/mapping.json"), "mapping.json");
  EXPECT_EQ(summary.Get("format")->as_string(), "hull-mapping");
  EXPECT_EQ(summary.Get("version")->as_number(), 1);
}

// Issue 12, part 1, per true object (not per detected object: on the
// demo's strip of touching lumps a detected object holds several lumps or
// part of one): the fused model's max height in each true object's region
// against its true height and against the adjusted features there.
void PeaksPerTrueObject(const std::string& preset) {
  const Case& c = GetCase(preset);
  const MappingResult& r = Map(preset, Params::kPaper, 0.0);
  const MeshIndex cad(c.survey.cad);
  const auto checks =
      CheckObjectHeights(r.model, r.objects, MappingInputFromAdjustment(c.adjustment, c.survey.bundle), c.est_to_true,
                         c.survey.bundle.truth->objects, c.survey.object_meshes, cad, &r.keyframes);
  std::printf("[%s, paper eps/alpha, tau 0] per true object:\n%s", preset.c_str(),
              ObjectHeightTable(checks, 0.06, 0.01).c_str());
  int isolated = 0;
  for (const auto& k : checks) {
    if (!std::isfinite(k.true_max) || k.height < 0.06) continue;
    // Nothing rises above the truth (a wrong match or a merged neighbour
    // would): the model's max is at most 1 cm above the true max.
    if (std::isfinite(k.model_max)) {
      EXPECT_LE(k.model_max, k.true_max + 0.01) << k.id;
    }
    // The top features reach the shapes: the highest feature in at least
    // two keyframes' shapes is at least the features' robust maximum (the
    // second highest). DBSCAN's |d| axis used to cut a narrow top off as
    // noise (the demo's 0.18 m strip-8: features at 0.174 and 0.159 m, its
    // shapes stopped at 0.129 m).
    if (std::isfinite(k.feature_robust_max) && k.feature_robust_max > r.options.object_min_height) {
      EXPECT_GE(k.shaped_max, k.feature_robust_max) << k.id;
    }
    // Isolated objects (the cylinder, the box, the 0.15 m patch) within 1 cm.
    if (k.id == "cyl-1" || k.id == "box-1" || k.id == "patch-1") {
      ++isolated;
      EXPECT_NEAR(k.model_max, k.true_max, 0.01) << k.id;
    }
  }
  EXPECT_EQ(isolated, 3);
}

// Each case below runs in its own process under ctest (gtest_discover_tests)
// and simulates and adjusts its preset once: a few cases, each checking
// several things, keep the suite short.
class MappingSurvey : public ::testing::TestWithParam<std::string> {};

TEST_P(MappingSurvey, DetectionAtTauZero) {
  EveryDetectableLargeObjectIsDetectedAtTauZero(GetParam());
  PaperParametersDetectMostLargeObjects(GetParam());
}

TEST_P(MappingSurvey, HeightsAndFlatness) {
  CylinderHeightOnTheRemeshedModel(GetParam());
  ModelStaysOnTheCadAwayFromObjects(GetParam());
  PeaksPerTrueObject(GetParam());
}

TEST_P(MappingSurvey, HigherTau) {
  NoFalseObjectsAtTauSixCentimetres(GetParam());
  RerunAfterTauChangeReusesTheRefinedMesh(GetParam());
}

TEST_P(MappingSurvey, ZonesFusionAndFiles) {
  UnseenZonesAreUninspectedAndSeenOnesRated(GetParam());
  FastFusionEqualsThePapersLoops(GetParam());
  WritesTheResultsFolder(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Presets, MappingSurvey, ::testing::Values("demo", "mono"));

}  // namespace
}  // namespace hull
