#include "ui/report/report_document.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "geometry/mesh_index.h"
#include "mapping/fouling.h"

namespace hull::report {
namespace {

__attribute__((format(printf, 1, 2))) std::string Format(const char* fmt, ...) {
  char buffer[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

std::string Num(double v, int digits) { return std::isfinite(v) ? Format("%.*f", digits, v) : "–"; }
std::string Metres(double v, int digits = 3) { return std::isfinite(v) ? Num(v, digits) + " m" : "–"; }
std::string Percent(double fraction, int digits = 1) { return Num(100 * fraction, digits) + " %"; }
std::string Count(long long n) {
  std::string s = std::to_string(n);
  const int first = n < 0 ? 1 : 0;
  for (int i = static_cast<int>(s.size()) - 3; i > first; i -= 3) s.insert(static_cast<std::size_t>(i), "\u2009");
  return s;
}
std::string Rounded(double v) { return std::isfinite(v) && std::abs(v) < 1e15 ? Count(std::llround(v)) : "–"; }

std::string Duration(double s) {
  if (!(s >= 0)) return "–";
  if (s < 60) return Format("%.1f s", s);
  const long total = std::lround(s);
  if (total < 3600) return Format("%ld min %02ld s", total / 60, total % 60);
  return Format("%ld h %02ld min", total / 3600, (total % 3600) / 60);
}

std::string Quantile(std::vector<double> v, double q, int digits) {
  if (v.empty()) return "–";
  std::sort(v.begin(), v.end());
  return Num(v[static_cast<std::size_t>(q * (v.size() - 1))], digits);
}

// "0–7, 11, 13–19"
std::string Ranges(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  std::string s;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i;
    while (j + 1 < v.size() && v[j + 1] == v[j] + 1) ++j;
    if (!s.empty()) s += ", ";
    s += std::to_string(v[i]);
    if (j > i) s += "–" + std::to_string(v[j]);
    i = j + 1;
  }
  return s;
}

Block Paragraph(std::string text) {
  Block b;
  b.text = std::move(text);
  return b;
}
Block Note(std::string text) {
  Block b;
  b.kind = Block::Kind::kNote;
  b.text = std::move(text);
  return b;
}
Block Subheading(std::string text) {
  Block b;
  b.kind = Block::Kind::kSubheading;
  b.text = std::move(text);
  return b;
}
Block Facts(std::vector<std::pair<std::string, std::string>> facts) {
  Block b;
  b.kind = Block::Kind::kFacts;
  b.facts = std::move(facts);
  return b;
}
Block TableBlock(Table t) {
  Block b;
  b.kind = Block::Kind::kTable;
  b.table = std::move(t);
  return b;
}
Block List(std::vector<std::string> items) {
  Block b;
  b.kind = Block::Kind::kList;
  b.items = std::move(items);
  return b;
}
Block FigureBlock(const FigureRef& f) {
  Block b;
  b.kind = Block::Kind::kFigure;
  b.figure = f;
  return b;
}

std::string ModelTitle(SurfaceModel m) {
  switch (m) {
    case SurfaceModel::kNaive:
      return "naive";
    case SurfaceModel::kAllOnSurface:
      return "all-on-surface";
    case SurfaceModel::kMaxMixture:
      return "max-mixture";
  }
  return "?";
}

const char* YesNo(bool b) { return b ? "yes" : "no"; }

const AdjustmentEvaluation* EvaluationOf(const PipelineResult& r, const AdjustmentResult* a) {
  if (a == &r.adjustment) return r.evaluation ? &*r.evaluation : nullptr;
  for (std::size_t i = 0; i < r.baselines.size(); ++i) {
    if (&r.baselines[i] == a) return i < r.baseline_evaluations.size() ? &r.baseline_evaluations[i] : nullptr;
  }
  return nullptr;
}

// Inspected area per side (bottom, port, starboard) from mapping's zones.
std::array<double, kZoneSides> InspectedBySide(const MappingResult& m) {
  std::array<double, kZoneSides> a{};
  for (const ZoneAssessment& z : m.zones) {
    if (z.side != HullSide::kNone) a[static_cast<int>(z.side)] += z.inspected_area;
  }
  return a;
}

// Landmarks per side (from the CAD face nearest each), without mapping.
std::array<double, kZoneSides> LandmarksBySide(const ReportInputs& in, const HullFrame& hull) {
  std::array<double, kZoneSides> a{};
  TriangleMesh cad = *in.cad;
  if (cad.face_normals.size() != cad.faces.size()) cad.ComputeNormals();
  const MeshIndex index(cad);
  for (const PlacedLandmark& l : LandmarksInModel(in.pipeline->adjustment)) {
    const ClosestPoint c = index.Closest(l.p_m);
    if (c.face < 0) continue;
    const HullSide s = hull.Side(cad.face_normals[c.face]);
    if (s != HullSide::kNone) a[static_cast<int>(s)] += 1;
  }
  return a;
}

std::string ViewPhrase(HullView v) {
  switch (v) {
    case HullView::kBottom:
      return "from below (bow to the right, starboard up)";
    case HullView::kPort:
      return "from the port side (bow to the left)";
    case HullView::kStarboard:
      return "from the starboard side (bow to the right)";
  }
  return "";
}

}  // namespace

void CheckInputs(const ReportInputs& in) {
  if (!in.bundle) throw std::invalid_argument("report: no survey bundle");
  if (!in.cad || in.cad->empty()) throw std::invalid_argument("report: no prior (CAD) mesh");
  if (!in.pipeline) throw std::invalid_argument("report: no pipeline result");
}

std::vector<std::string> SectionIds() {
  return {"summary", "method", "deviation",  "cross-section", "objects",
          "zones",   "solver", "evaluation", "not-inspected"};
}

const Section* ReportDocument::Find(const std::string& id) const {
  for (const Section& s : sections) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

std::string RatingTone(const std::string& rating) {
  if (rating == "0-1") return "#d9f0d3";
  if (rating == "2") return "#fff3b0";
  if (rating == "3") return "#fdc98a";
  if (rating == "4") return "#f4a3a3";
  return "#e0e0e0";
}

std::vector<FigureRef> PlanFigures(const ReportInputs& in, const ReportOptions& options) {
  CheckInputs(in);
  const HullFrame hull = ReportHullFrame(in);
  std::vector<FigureRef> out;
  // Heatmaps: the sides that hold at least a tenth of what was seen.
  const std::array<double, kZoneSides> seen = in.mapping ? InspectedBySide(*in.mapping) : LandmarksBySide(in, hull);
  const double total = seen[0] + seen[1] + seen[2];
  const HullView views[kZoneSides] = {HullView::kBottom, HullView::kPort, HullView::kStarboard};
  for (int s = 0; s < kZoneSides; ++s) {
    if (total > 0 ? seen[s] < 0.1 * total : s != 0) continue;
    FigureRef f;
    f.id = std::string("heatmap-") + HullViewName(views[s]);
    f.kind = FigureKind::kHeatmap;
    f.view = views[s];
    if (in.mapping) {
      f.title = "Deviation of the fused model, " + ViewPhrase(views[s]);
      f.caption =
          "The fused, locally remeshed model coloured by its signed deviation from the CAD surface "
          "(red: standing off the hull, blue: below it), seen " +
          ViewPhrase(views[s]) +
          ". Top: the whole hull; the box marks the detail below. Bottom: the surveyed stretch, detected "
          "objects labelled; the dashed line encloses the adjusted features on this side of the hull.";
    } else {
      f.title = "Landmark deviation over the CAD model, " + ViewPhrase(views[s]);
      f.caption =
          "Mapping has not run: the adjusted landmarks, coloured by their signed deviation from the CAD "
          "surface, over the CAD model seen " +
          ViewPhrase(views[s]) + ". Top: the whole hull; bottom: the surveyed stretch.";
    }
    out.push_back(f);
  }
  {
    FigureRef f;
    f.id = "cross-section";
    f.kind = FigureKind::kCrossSection;
    f.title = "Cross-section of the reconstruction";
    f.caption = Format(
        "A slab %.2f m wide across the hull (the paper's Fig. 14), seen looking aft: the CAD profile (black), the "
        "DVL returns (blue) and the features (green on the hull, red beyond the max-mixture decision boundary) "
        "inside the slab, placed by each model's adjustment",
        options.slab_width);
    f.caption += in.mapping ? "; the fused model's profile in orange. " : ". ";
    f.caption += "Rows: the whole section, the surveyed part, a close-up (equal scales on both axes).";
    out.push_back(f);
  }
  {
    FigureRef f;
    f.id = "solver-convergence";
    f.kind = FigureKind::kConvergence;
    f.title = "Convergence of the adjustment";
    f.caption =
        "Left: the cost (½ Σ r², robustified) per solver iteration of each model. Right: the share of "
        "landmarks with λ = 1 (on the hull) per iteration of the max-mixture model (the paper's Fig. 16).";
    out.push_back(f);
  }
  {
    FigureRef f;
    f.id = "dvl-residuals";
    f.kind = FigureKind::kDvlResiduals;
    f.title = "DVL range residuals";
    f.caption =
        "Histograms of the DVL range residuals (measured − predicted range) at the initial alignment (grey) "
        "and after each model's adjustment (colour), as in the paper's Fig. 18. Values beyond the axis are "
        "counted in the outer bars.";
    out.push_back(f);
  }
  if (!in.pipeline->baselines.empty()) {
    FigureRef f;
    f.id = "model-timing";
    f.kind = FigureKind::kModelTiming;
    f.title = "Time per model";
    f.caption =
        "Wall time of each model's adjustment (light: the whole step, dark: the Ceres solver) with its "
        "iterations and final cost, as in the paper's Fig. 17.";
    out.push_back(f);
  }
  return out;
}

namespace {

const FigureRef* FindFigure(const std::vector<FigureRef>& figures, FigureKind kind) {
  for (const FigureRef& f : figures) {
    if (f.kind == kind) return &f;
  }
  return nullptr;
}

Section SummarySection(const ReportInputs& in, const HullFrame& hull) {
  const SurveyBundle& b = *in.bundle;
  const PipelineResult& p = *in.pipeline;
  const SurveyManifest& m = b.manifest;
  Section s{"summary", "Survey and vessel", false, {}};
  std::vector<std::pair<std::string, std::string>> f;
  f.emplace_back("Survey", m.name.empty() ? "(unnamed)" : m.name);
  f.emplace_back("Vehicle", m.vehicle.empty() ? "(not given)" : m.vehicle);
  f.emplace_back("Survey bundle", in.bundle_path.empty() ? b.directory : in.bundle_path);
  f.emplace_back("Keyframes", Count(b.nav.size()));
  if (b.nav.size() >= 2) f.emplace_back("Duration", Duration(b.nav.back().t - b.nav.front().t));
  const PinholeIntrinsics& k = m.camera.top;
  f.emplace_back("Camera", Format("%s, %d × %d px, f = %.0f px", m.camera.stereo() ? "stereo" : "monocular",
                                  m.camera.width, m.camera.height, k.fx));
  std::size_t returns = 0;
  for (const DvlRecord& d : b.dvl) {
    for (double r : d.range) returns += DvlRecord::HasReturn(r) ? 1 : 0;
  }
  f.emplace_back("DVL", Format("4 beams, %zu pings, %zu returns (%.1f %% of beams)", b.dvl.size(), returns,
                               b.dvl.empty() ? 0.0 : 100.0 * returns / (4.0 * b.dvl.size())));
  f.emplace_back("Feature observations", Count(b.features.size()));
  f.emplace_back("Landmarks",
                 Count(b.CountLandmarks()) + " observed, " + Count(p.adjustment.landmarks.size()) + " adjusted");
  // The hull.
  const TriangleMesh& cad = *in.cad;
  Eigen::AlignedBox<double, 1> beam, depth;
  for (const Eigen::Vector3d& v : cad.vertices) {
    beam.extend(Eigen::Matrix<double, 1, 1>(v.dot(hull.port())));
    depth.extend(Eigen::Matrix<double, 1, 1>(v.dot(hull.up())));
  }
  f.emplace_back("Prior mesh", in.mesh_path.empty() ? "(in memory)" : in.mesh_path);
  f.emplace_back("Mesh size", Count(cad.num_vertices()) + " vertices, " + Count(cad.num_faces()) + " faces, " +
                                  Rounded(cad.SurfaceArea()) + " m²");
  f.emplace_back("Hull", Format("length %.1f m, beam %.1f m, depth %.1f m (from the mesh along the hull axes)",
                                hull.length(), beam.sizes()[0], depth.sizes()[0]));
  std::vector<double> along;
  for (const PlacedLandmark& l : LandmarksInModel(p.adjustment)) along.push_back(hull.DistanceFromBow(l.p_m));
  if (!along.empty()) {
    std::sort(along.begin(), along.end());
    const double a = along[along.size() / 50], z = along[along.size() - 1 - along.size() / 50];
    f.emplace_back("Surveyed stretch",
                   Format("%.1f m to %.1f m from the bow (stations %d to %d of %d; 96 %% of the "
                          "landmarks)",
                          a, z, std::min(hull.stations() - 1, int(a / hull.station_length())),
                          std::min(hull.stations() - 1, int(z / hull.station_length())), hull.stations()));
  }
  if (in.mapping) {
    const MappingSummary& ms = in.mapping->summary;
    f.emplace_back("Fused model", Count(ms.model_vertices) + " vertices, " + Count(ms.model_faces) + " faces; " +
                                      Num(ms.refined_area, 1) + " m² remeshed, " + Count(ms.vertices_fused) +
                                      " vertices fused");
    f.emplace_back("Inspected area", Num(ms.inspected_area, 1) + " m² of " + Rounded(ms.hull_area) + " m² (" +
                                         Percent(ms.hull_area > 0 ? ms.inspected_area / ms.hull_area : 0, 2) + ")");
  }
  f.emplace_back("Ground truth", b.truth ? "present (a simulated survey): see the evaluation" : "none");
  if (!in.results_path.empty()) f.emplace_back("Results", in.results_path);
  if (in.run_seconds > 0) f.emplace_back("Run time", Duration(in.run_seconds));
  s.blocks.push_back(Facts(std::move(f)));
  return s;
}

Section MethodSection(const ReportInputs& in) {
  const PipelineResult& p = *in.pipeline;
  const AdjustmentOptions& o = p.adjustment.options;
  Section s{"method", "Method and parameters", false, {}};
  s.blocks.push_back(Paragraph(
      "The survey's DVL returns were first registered to the CAD mesh (GICP) to place the model; then a "
      "model-assisted bundle adjustment (Ozog et al.) estimated the vehicle poses, the servo angles, the camera "
      "extrinsic, the model pose and the feature positions together, constraining each feature to the CAD surface "
      "through the " +
      ModelTitle(o.model) +
      " surface model. Under the max-mixture model each feature takes the likelier of two Gaussians of its "
      "distance to the surface, σ1 (on the hull, λ = 1) or σ0 (foreign structure, λ = 0); the two are equally "
      "likely at the decision boundary."));
  if (in.mapping) {
    s.blocks.push_back(Paragraph(
        "Mapping then clustered, per keyframe, the features whose deviation exceeds τ (DBSCAN with radius ε and "
        "min points), meshed each cluster as an alpha shape of radius α, and fused the shapes into a copy of the "
        "CAD mesh remeshed locally where they depart from it (Algorithm 2). Connected regions of the fused model "
        "standing more than h_min off the CAD surface over at least the minimum area are the detected objects; "
        "their cover of the inspected area rates each hull zone on the IMO scale."));
  }
  Table t;
  t.header = {"Parameter", "Value", "Meaning"};
  t.numeric = {false, true, false};
  const auto row = [&](std::string a, std::string b, std::string c) {
    t.rows.push_back({std::move(a), std::move(b), std::move(c)});
  };
  row("Surface model", ModelTitle(o.model), "constraint of the features to the CAD surface");
  row("σ0", Metres(o.sigma0), "off the model (λ = 0)");
  row("σ1", Metres(o.sigma1), "on the model (λ = 1)");
  row("Decision boundary", Metres(o.DecisionBoundary()), "|h| where both components are equally likely");
  row("Huber threshold", Num(o.huber_sigmas, 1) + " σ", "robust loss on reprojection and DVL residuals");
  row("Min observations", std::to_string(o.min_observations), "keyframes a landmark needs");
  row("Outlier rejection", Num(o.outlier_sigmas, 1) + " σ × " + std::to_string(o.rejection_rounds),
      "reprojection outliers removed, rounds");
  row("Max iterations", std::to_string(o.max_iterations), "solver limit");
  row("Estimated",
      std::string("servo ") + YesNo(o.estimate_servo) + ", extrinsic " + YesNo(o.estimate_extrinsic) + ", model pose " +
          YesNo(o.estimate_model_pose) + ", DVL " + YesNo(o.use_dvl),
      "what the adjustment solves for besides poses and landmarks");
  row("Models compared", p.baselines.empty() ? "no" : "naive, all-on-surface, max-mixture", "");
  if (in.mapping) {
    const MappingOptions& m = in.mapping->options;
    row("τ", Metres(m.tau), "features with |deviation| > τ are clustered");
    row("α", Metres(m.alpha), "alpha-shape radius");
    row("ε", Metres(m.dbscan_eps), "DBSCAN neighbourhood radius");
    row("Min points", std::to_string(m.dbscan_min_points), "DBSCAN core-point count");
    row("Refinement edge", Metres(m.refine_edge), "target edge length where shapes depart from the CAD");
    row("h_min", Metres(m.object_min_height), "height that makes part of an object");
    row("Min object area", Num(m.object_min_area, 3) + " m²", "smallest footprint reported");
    row("Stations", std::to_string(m.stations), "zones: stations × bottom, port, starboard");
    row("Bottom angle", Num(m.bottom_angle_deg, 0) + "°", "outward normal within this of straight down");
  } else {
    row("τ, α, ε, min points", "–", "mapping has not run");
  }
  s.blocks.push_back(TableBlock(std::move(t)));
  return s;
}

Section DeviationSection(const ReportInputs& in, const ReportOptions&, const std::vector<FigureRef>& figures) {
  Section s{"deviation", "Deviation from the CAD model", true, {}};
  if (in.mapping) {
    std::vector<double> fused;
    const std::vector<double>* dev = in.mapping->model.FindScalar("deviation");
    const std::vector<double>* fusions = in.mapping->model.FindScalar("fusions");
    if (dev) {
      for (std::size_t i = 0; i < dev->size(); ++i) {
        if (!fusions || (*fusions)[i] > 0) fused.push_back((*dev)[i]);
      }
    }
    s.blocks.push_back(
        Paragraph("Each vertex of the fused model carries its signed distance from the CAD surface. Over the " +
                  Count(fused.size()) + " fused vertices the deviation runs from " + Quantile(fused, 0.0, 3) +
                  " m to " + Quantile(fused, 1.0, 3) + " m (median " + Quantile(fused, 0.5, 3) +
                  " m, 99th percentile " + Quantile(fused, 0.99, 3) + " m)."));
  } else {
    s.blocks.push_back(Paragraph(
        "Mapping has not run, so there is no fused model yet: the figures show the adjusted landmarks coloured by "
        "their deviation from the CAD surface."));
  }
  for (const FigureRef& f : figures) {
    if (f.kind == FigureKind::kHeatmap) s.blocks.push_back(FigureBlock(f));
  }
  return s;
}

Section CrossSectionSection(const ReportInputs& in, const HullFrame& hull, const ReportOptions& options,
                            const std::vector<FigureRef>& figures) {
  Section s{"cross-section", "Cross-section", true, {}};
  const CrossSection cs = BuildCrossSection(in, hull, options);
  std::string text = Format("The slab is %.2f m wide, %.2f m from the bow (station %d).", cs.width, cs.from_bow,
                            std::min(hull.stations() - 1, int(cs.from_bow / hull.station_length())));
  if (!cs.focus.empty()) text += " The close-up is centred on detected object " + cs.focus + ".";
  for (const SectionModel& m : cs.models) {
    int off = 0;
    for (const SectionFeature& f : m.features) off += f.off_hull ? 1 : 0;
    text += Format(" %s: %zu features (%d off the hull), %zu DVL returns.", ModelTitle(m.model).c_str(),
                   m.features.size(), off, m.dvl.size());
  }
  if (in.pipeline->baselines.empty()) {
    text += " Only the " + ModelTitle(in.pipeline->adjustment.options.model) +
            " model ran (the models were not compared), so the figure has one column.";
  }
  s.blocks.push_back(Paragraph(text));
  if (const FigureRef* f = FindFigure(figures, FigureKind::kCrossSection)) s.blocks.push_back(FigureBlock(*f));
  return s;
}

Section ObjectsSection(const ReportInputs& in) {
  Section s{"objects", "Detected objects", false, {}};
  if (!in.mapping) {
    s.blocks.push_back(Paragraph("Mapping has not run: no objects were detected."));
    return s;
  }
  const MappingResult& m = *in.mapping;
  if (m.objects.empty()) {
    s.blocks.push_back(
        Paragraph(Format("No part of the fused model stands more than %.3f m off the CAD surface over "
                         "%.3f m² or more: no objects.",
                         m.options.object_min_height, m.options.object_min_area)));
    return s;
  }
  double area = 0;
  for (const DetectedObject& o : m.objects) area += o.area;
  s.blocks.push_back(Paragraph(Format(
      "%zu objects stand more than h_min = %.3f m off the CAD surface, covering %.2f m² in all. Distances are from "
      "the bow along the hull; heights are the fused model's deviation from the CAD surface over each footprint.",
      m.objects.size(), m.options.object_min_height, area)));
  Table t;
  t.header = {"Object",          "From bow (m)",   "Station",  "Side", "Area (m²)",
              "Mean height (m)", "Max height (m)", "Features", "Views"};
  t.numeric = {false, true, true, false, true, true, true, true, true};
  for (const DetectedObject& o : m.objects) {
    t.rows.push_back({o.id, Num(o.distance_from_bow, 2), std::to_string(o.station), HullSideName(o.side),
                      Num(o.area, 3), Num(o.mean_height, 3), Num(o.max_height, 3), std::to_string(o.num_features),
                      std::to_string(o.num_views)});
  }
  s.blocks.push_back(TableBlock(std::move(t)));
  return s;
}

Section ZonesSection(const ReportInputs& in) {
  Section s{"zones", "Fouling assessment by hull zone", false, {}};
  s.blocks.push_back(Paragraph(
      "The hull is cut into stations along its length (station 0 at the bow) and each station into bottom, port "
      "and starboard side (bottom where the outward normal is within the bottom angle of straight down). A zone's "
      "rating follows the IMO biofouling rating of MEPC.378(80) from the share of its inspected area that detected "
      "objects cover:"));
  Table scale;
  scale.header = {"Rating", "Macrofouling cover", "Meaning"};
  scale.numeric = {false, false, false};
  scale.rows = {{"0-1", "below 1 %", "clean (0) or slime and microfouling (1): not told apart by geometry"},
                {"2", "1 % to 15 %", "light macrofouling"},
                {"3", "above 15 % to 40 %", "medium macrofouling"},
                {"4", "above 40 %", "heavy macrofouling"},
                {"uninspected", "–", "no camera saw any of the zone: not rated, never counted as clean"}};
  for (const auto& r : scale.rows) scale.tone.push_back(RatingTone(r[0]));
  scale.tone_column = 0;
  s.blocks.push_back(TableBlock(std::move(scale)));
  s.blocks.push_back(
      Note("Slime and microfouling (ratings 0 and 1) are invisible to geometry: a thin film does not "
           "change the hull's shape, so a zone rated \"0-1\" may still carry them. Only macrofouling "
           "that stands off the hull by more than h_min is counted."));
  if (!in.mapping) {
    s.blocks.push_back(Paragraph("Mapping has not run: no zone is rated."));
    return s;
  }
  const MappingResult& m = *in.mapping;
  Table t;
  t.header = {"Station",      "From–to bow (m)", "Side",    "Hull (m²)",      "Inspected (m²)", "Inspected (%)",
              "Covered (m²)", "Cover (%)",       "Objects", "Max height (m)", "Rating"};
  t.numeric = {true, true, false, true, true, true, true, true, true, true, false};
  std::map<std::string, int> counts;
  int inspected = 0;
  for (const ZoneAssessment& z : m.zones) {
    const std::string rating = FoulingRatingName(z.rating);
    ++counts[rating];
    if (z.rating == FoulingRating::kUninspected) continue;
    ++inspected;
    t.rows.push_back({std::to_string(z.station), Num(z.from_bow, 1) + "–" + Num(z.to_bow, 1), HullSideName(z.side),
                      Num(z.hull_area, 1), Num(z.inspected_area, 2),
                      Num(z.hull_area > 0 ? 100 * z.inspected_area / z.hull_area : 0, 1), Num(z.covered_area, 3),
                      Num(z.cover_percent, 2), std::to_string(z.objects), Num(z.max_height, 3), rating});
    t.tone.push_back(RatingTone(rating));
  }
  t.tone_column = static_cast<int>(t.header.size()) - 1;
  std::string summary = Format("%d of %zu zones were inspected (those listed below); ", inspected, m.zones.size());
  bool first = true;
  for (const char* r : {"0-1", "2", "3", "4", "uninspected"}) {
    if (!counts.count(r)) continue;
    summary += std::string(first ? "" : ", ") + "rated " + r + ": " + std::to_string(counts[r]);
    first = false;
  }
  summary += ". The zones never seen are listed under \"What was not inspected\".";
  s.blocks.push_back(Paragraph(summary));
  if (!t.rows.empty()) s.blocks.push_back(TableBlock(std::move(t)));
  return s;
}

Section SolverSection(const ReportInputs& in, const std::vector<FigureRef>& figures) {
  const PipelineResult& p = *in.pipeline;
  Section s{"solver", "Solver statistics", true, {}};
  const ModelAlignment& a = p.alignment;
  std::vector<std::pair<std::string, std::string>> f;
  f.emplace_back("Initial alignment", a.coarse.ran ? Format("coarse search (%zu hypotheses, %zu refined, %zu tied) "
                                                            "then GICP",
                                                            a.coarse.hypotheses, a.coarse.refined, a.coarse.tied)
                                                   : std::string("GICP from the survey's model pose guess"));
  f.emplace_back("GICP", Format("%s, %zu DVL returns against %zu mesh samples",
                                a.gicp.converged ? "converged"
                                                 : "not "
                                                   "conver"
                                                   "ged",
                                a.dvl_points, a.target_points));
  f.emplace_back("Directions fixed by the DVL", Format("%d of 6", a.constrained_directions));
  f.emplace_back("DVL residual RMS", Metres(a.residual_rms_before, 4) + " before, " + Metres(a.residual_rms_after, 4) +
                                         " after the alignment");
  s.blocks.push_back(Facts(std::move(f)));
  Table t;
  t.header = {"Model",      "Iterations", "Initial cost", "Final cost",      "Time (s)",
              "Solver (s)", "λ = 1",      "Landmarks",    "Residual blocks", "Converged"};
  t.numeric = {false, true, true, true, true, true, true, true, true, false};
  for (const AdjustmentResult* r : ModelsInOrder(p)) {
    t.rows.push_back({ModelTitle(r->options.model), std::to_string(r->iterations.size()), Rounded(r->initial_cost),
                      Rounded(r->final_cost), Num(r->seconds, 2), Num(r->solver_seconds, 2),
                      Percent(r->FractionOnSurface()), Count(r->landmarks.size()), Count(r->num_residual_blocks),
                      YesNo(r->converged)});
  }
  s.blocks.push_back(TableBlock(std::move(t)));
  s.blocks.push_back(Paragraph(
      "λ = 1: the share of landmarks the max-mixture labels on the hull; for the naive and all-on-surface models, "
      "which do not choose labels, the share within the decision boundary. Termination (" +
      ModelTitle(p.adjustment.options.model) +
      "): " + (p.adjustment.termination.empty() ? "–" : p.adjustment.termination)));
  for (FigureKind k : {FigureKind::kConvergence, FigureKind::kDvlResiduals, FigureKind::kModelTiming}) {
    if (const FigureRef* fig = FindFigure(figures, k)) s.blocks.push_back(FigureBlock(*fig));
  }
  return s;
}

// Half the footprint of a true object across the hull surface.
double HalfSize(const TrueObject& o) { return o.kind == ObjectKind::kBox ? 0.5 * o.size.head<2>().norm() : o.radius; }

// The detected object nearest a true one: centroids within its half-size
// plus 0.5 m (a detected region may merge several neighbouring objects).
const DetectedObject* MatchObject(const MappingResult& m, const TrueObject& o) {
  const DetectedObject* best = nullptr;
  double best_d = HalfSize(o) + 0.5;
  for (const DetectedObject& d : m.objects) {
    const double dist = (d.centroid_m - o.center).norm();
    if (dist <= best_d) {
      best_d = dist;
      best = &d;
    }
  }
  return best;
}

// The fused model's highest deviation over a true object's footprint (NaN:
// no vertex there).
double FusedHeight(const MappingResult& m, const TrueObject& o) {
  const std::vector<double>* dev = m.model.FindScalar("deviation");
  double h = std::nan("");
  if (!dev) return h;
  const double reach = HalfSize(o) + 0.01;
  for (std::size_t i = 0; i < m.model.vertices.size(); ++i) {
    if ((m.model.vertices[i] - o.center).norm() <= reach + std::abs((*dev)[i])) {
      h = std::isnan(h) ? (*dev)[i] : std::max(h, (*dev)[i]);
    }
  }
  return h;
}

Section EvaluationSection(const ReportInputs& in) {
  const PipelineResult& p = *in.pipeline;
  Section s{"evaluation", "Evaluation against truth", false, {}};
  if (!p.evaluation) {
    s.blocks.push_back(Paragraph("The survey has no ground truth (it is not simulated): nothing to evaluate against."));
    return s;
  }
  s.blocks.push_back(
      Paragraph("The survey is simulated, so its truth is known. Positions are compared in the model frame; the "
                "gauge-aligned figures remove the rigid motions the surveyed hull cannot fix (see evaluation.txt)."));
  Table t;
  std::vector<const AdjustmentResult*> models;
  std::vector<const AdjustmentEvaluation*> evals;
  for (const AdjustmentResult* r : ModelsInOrder(p)) {
    if (const AdjustmentEvaluation* e = EvaluationOf(p, r)) {
      models.push_back(r);
      evals.push_back(e);
    }
  }
  t.header = {"Measure"};
  t.numeric = {false};
  for (const AdjustmentResult* r : models) {
    t.header.push_back(ModelTitle(r->options.model));
    t.numeric.push_back(true);
  }
  const auto row = [&](const std::string& name, auto value) {
    std::vector<std::string> r{name};
    for (const AdjustmentEvaluation* e : evals) r.push_back(value(*e));
    t.rows.push_back(std::move(r));
  };
  using E = AdjustmentEvaluation;
  row("Landmark RMSE, gauge-aligned (m)", [](const E& e) { return Num(e.landmark_rmse, 4); });
  row("  on the hull (m)", [](const E& e) { return Num(e.landmark_rmse_hull, 4); });
  row("  on foreign objects (m)", [](const E& e) { return Num(e.landmark_rmse_objects, 4); });
  row("Landmark RMSE, raw (m)", [](const E& e) { return Num(e.landmark_rmse_raw, 4); });
  row("Directions the hull leaves free", [](const E& e) { return std::to_string(e.unobservable_dof); });
  row("Labels agreeing with truth", [](const E& e) { return Percent(e.label_agreement, 2); });
  row("Hull features vs DVL, median (m)", [](const E& e) { return Num(e.hull_feature_offset, 4); });
  row("  spread (m)", [](const E& e) { return Num(e.hull_feature_spread, 4); });
  row("DVL residual std, initial → final (m)",
      [](const E& e) { return Num(e.dvl_std_initial, 4) + " → " + Num(e.dvl_std_final, 4); });
  row("DVL residual robust spread (m)",
      [](const E& e) { return Num(e.dvl_mad_initial, 4) + " → " + Num(e.dvl_mad_final, 4); });
  row("Servo error (°)",
      [](const E& e) { return Num(e.servo_error_initial_deg, 2) + " → " + Num(e.servo_error_final_deg, 2); });
  row("Camera extrinsic error (m)",
      [](const E& e) { return Num(e.extrinsic_error_initial_m, 4) + " → " + Num(e.extrinsic_error_final_m, 4); });
  row("Camera extrinsic error (°)",
      [](const E& e) { return Num(e.extrinsic_error_initial_deg, 2) + " → " + Num(e.extrinsic_error_final_deg, 2); });
  s.blocks.push_back(TableBlock(std::move(t)));

  const SurveyTruth* truth = in.bundle->truth ? &*in.bundle->truth : nullptr;
  if (truth && !truth->objects.empty()) {
    s.blocks.push_back(Subheading("Foreign objects of the truth"));
    Table o;
    o.header = {"Object", "Kind", "Height (m)", "Landmarks", "Deviation (m)", "True deviation (m)"};
    o.numeric = {false, false, true, true, true, true};
    if (in.mapping) {
      o.header.insert(o.header.end(), {"Fused height (m)", "Nearest object"});
      o.numeric.insert(o.numeric.end(), {true, false});
    }
    // A flat stretch of hull cannot fix the model's position in its own plane
    // (see the evaluation), so true objects are compared where the survey
    // puts them: placed in g by the true model pose, and into the estimated
    // model frame by the estimated one.
    const Pose true_to_estimated = Pose::FromVector(p.adjustment.x_gM).Inverse() * Pose::FromVector(truth->x_gM);
    int found = 0;
    for (TrueObject to : truth->objects) {
      to.center = true_to_estimated * to.center;
      const ObjectDeviation* d = p.evaluation->Object(to.id);
      std::vector<std::string> r{to.id,
                                 ObjectKindName(to.kind),
                                 Num(to.Height(), 3),
                                 d ? std::to_string(d->landmarks) : "0",
                                 d ? Num(d->mean_deviation, 3) : "–",
                                 d ? Num(d->true_mean_deviation, 3) : "–"};
      if (in.mapping) {
        const double fused = FusedHeight(*in.mapping, to);
        const DetectedObject* m = MatchObject(*in.mapping, to);
        r.push_back(Num(fused, 3));
        r.push_back(m ? m->id : "–");
        found += fused > in.mapping->options.object_min_height ? 1 : 0;
      }
      o.rows.push_back(std::move(r));
    }
    std::string text;
    if (in.mapping) {
      text = Format(
          "The fused model stands more than h_min = %.3f m off the CAD surface over %d of the %zu true objects "
          "(fused height: its highest vertex over the object's footprint; nearest object: the detected object "
          "whose centroid is nearest, within the object's half-size plus 0.5 m; true objects placed where the "
          "survey frame puts them). ",
          in.mapping->options.object_min_height, found, truth->objects.size());
    }
    s.blocks.push_back(Paragraph(text + "Deviation: the mean estimated deviation of the " +
                                 ModelTitle(p.adjustment.options.model) +
                                 " adjustment's landmarks on each object; true deviation: the mean true deviation "
                                 "of the same landmarks."));
    s.blocks.push_back(TableBlock(std::move(o)));
  }
  return s;
}

Section NotInspectedSection(const ReportInputs& in) {
  const SurveyBundle& b = *in.bundle;
  const PipelineResult& p = *in.pipeline;
  Section s{"not-inspected", "What was not inspected", false, {}};
  std::vector<std::string> items;
  if (in.mapping) {
    std::map<HullSide, std::vector<int>> missing;
    double area = 0, hull_area = 0;
    for (const ZoneAssessment& z : in.mapping->zones) {
      hull_area += z.hull_area;
      if (z.rating != FoulingRating::kUninspected) continue;
      missing[z.side].push_back(z.station);
      area += z.hull_area;
    }
    std::size_t n = 0;
    for (const auto& [side, st] : missing) n += st.size();
    items.push_back(Format("Uninspected zones: %zu of %zu (%.0f m² of hull, %.1f %%), not rated:", n,
                           in.mapping->zones.size(), area, hull_area > 0 ? 100 * area / hull_area : 0.0));
    for (const auto& [side, st] : missing) {
      items.push_back(std::string("    ") + HullSideName(side) + ": stations " + Ranges(st));
    }
    double partly = 0;
    for (const ZoneAssessment& z : in.mapping->zones) {
      if (z.rating != FoulingRating::kUninspected) partly += z.hull_area - z.inspected_area;
    }
    items.push_back(Format("Within the inspected zones, %.1f m² were not seen by any camera.", partly));
  } else {
    items.push_back("Mapping has not run: the inspected area and the uninspected zones are not known.");
  }
  const AdjustmentResult& a = p.adjustment;
  items.push_back(
      Format("Landmarks left out of the adjustment: %d (too few observations, not triangulable, or lost "
             "to outlier rejection); %zu observed, %zu adjusted.",
             a.num_landmarks_skipped, b.CountLandmarks(), a.landmarks.size()));
  items.push_back(Format("Feature observations rejected as wrong matches: %d.", a.observations_rejected));
  std::array<int, 4> no_return{};
  for (const DvlRecord& d : b.dvl) {
    for (int k = 0; k < 4; ++k) no_return[k] += DvlRecord::HasReturn(d.range[k]) ? 0 : 1;
  }
  const int none = no_return[0] + no_return[1] + no_return[2] + no_return[3];
  items.push_back(Format("DVL beams without a return: %d of %zu (beam 1: %d, 2: %d, 3: %d, 4: %d).", none,
                         4 * b.dvl.size(), no_return[0], no_return[1], no_return[2], no_return[3]));
  int missed = 0;
  for (const DvlResidual& r : a.dvl) missed += std::isfinite(r.final) ? 0 : 1;
  items.push_back(Format("DVL returns whose beam misses the placed mesh after the adjustment: %d.", missed));
  std::map<std::int64_t, int> seen;
  for (const FeatureObservation& f : b.features) ++seen[f.keyframe];
  int blind = 0;
  for (const NavRecord& n : b.nav) blind += seen.count(n.keyframe) ? 0 : 1;
  items.push_back(Format("Keyframes without a single feature: %d of %zu.", blind, b.nav.size()));
  s.blocks.push_back(List(std::move(items)));
  s.blocks.push_back(
      Note("Geometry cannot see slime or microfouling, growth thinner than h_min, or hull without "
           "visual texture (no features, so no shapes); the DVL is too sparse to detect objects and "
           "soft growth may not return its beams. Absence of detected objects is not proof of a "
           "clean hull outside what the cameras saw."));
  return s;
}

}  // namespace

ReportDocument BuildReportDocument(const ReportInputs& in, const ReportOptions& options,
                                   const std::vector<FigureRef>& figures, const std::string& generated) {
  CheckInputs(in);
  const HullFrame hull = ReportHullFrame(in);
  ReportDocument d;
  d.title = options.title.empty() ? "Hull inspection report" : options.title;
  d.subtitle = in.bundle->manifest.name;
  d.generated = generated;
  d.sections.push_back(SummarySection(in, hull));
  d.sections.push_back(MethodSection(in));
  d.sections.push_back(DeviationSection(in, options, figures));
  d.sections.push_back(CrossSectionSection(in, hull, options, figures));
  d.sections.push_back(ObjectsSection(in));
  d.sections.push_back(ZonesSection(in));
  d.sections.push_back(SolverSection(in, figures));
  d.sections.push_back(EvaluationSection(in));
  d.sections.push_back(NotInspectedSection(in));
  return d;
}

}  // namespace hull::report
