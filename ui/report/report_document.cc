#include "ui/report/report_document.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "geometry/mesh_index.h"
#include "ui/report/report_blocks.h"
#include "ui/report/report_sections.h"
#include "ui/report/sonar_report.h"

namespace hull::report {
namespace {

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

}  // namespace

void CheckInputs(const ReportInputs& in) {
  if (in.sonar) {
    if (in.sonar->run.steps.empty()) throw std::invalid_argument("report: a sonar run without steps");
    return;
  }
  if (!in.bundle) throw std::invalid_argument("report: no survey bundle");
  if (!in.cad || in.cad->empty()) throw std::invalid_argument("report: no prior (CAD) mesh");
  if (!in.pipeline) throw std::invalid_argument("report: no pipeline result");
}

std::vector<std::string> SectionIds() {
  return {"summary",     "not-inspected", "method", "deviation", "uncertainty", "cross-section",
          "photomosaic", "objects",       "zones",  "change",    "solver",      "evaluation"};
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
  if (in.sonar) return PlanSonarFigures(in);
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
      f.title = "Deviation of the fused model, " + ViewWords(views[s], true);
      f.caption =
          "The fused, locally remeshed model coloured by its signed deviation from the CAD surface "
          "(red: standing off the hull, blue: below it), seen " +
          ViewWords(views[s], true) +
          ". Top: the whole hull; the box marks the detail below. Bottom: the surveyed stretch, detected "
          "objects labelled; the dashed line encloses the adjusted features on this side of the hull.";
    } else {
      f.title = "Landmark deviation over the CAD model, " + ViewWords(views[s], true);
      f.caption =
          "Mapping has not run: the adjusted landmarks, coloured by their signed deviation from the CAD "
          "surface, over the CAD model seen " +
          ViewWords(views[s], true) + ". Top: the whole hull; bottom: the surveyed stretch.";
    }
    out.push_back(f);
  }
  PlanTrustFigures(in, options, out);
  PlanMosaicFigures(in, out);
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
  f.emplace_back("Not seen", NotSeenSummary(in));
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
  Table t = MakeTable({{"Parameter", false}, {"Value", true}, {"Meaning", false}});
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
    if (m.shape_grow_height < m.tau) {
      row("Clusters grown above", Metres(m.shape_grow_height),
          "hysteresis: clusters grow through features above this and are kept when one exceeds τ");
    }
    if (m.peak_fit) {
      row("Peak fit", "on", "each lump's apex estimated beyond its highest feature by a local quadric fit");
    }
    row("α", Metres(m.alpha), "alpha-shape radius");
    row("ε", Metres(m.dbscan_eps), "DBSCAN neighbourhood radius");
    row("Min points", std::to_string(m.dbscan_min_points), "DBSCAN core-point count");
    row("Refinement edge", Metres(m.refine_edge), "target edge length where shapes depart from the CAD");
    row("h_min", Metres(m.object_min_height), "height that makes part of an object");
    row("Min object area", Num(m.object_min_area, 3) + " m²", "smallest footprint reported ...");
    row("Min object features",
        m.object_min_features > 0
            ? std::to_string(m.object_min_features) + " from " + std::to_string(m.object_min_views) + " keyframes"
            : std::string("off"),
        "... unless that many features above h_min hold a smaller one up");
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

}  // namespace

ReportDocument BuildReportDocument(const ReportInputs& in, const ReportOptions& options,
                                   const std::vector<FigureRef>& figures, const std::string& generated) {
  CheckInputs(in);
  if (in.sonar) return BuildSonarReportDocument(in, options, figures, generated);
  const HullFrame hull = ReportHullFrame(in);
  ReportDocument d;
  d.title = options.title.empty() ? "Hull inspection report" : options.title;
  d.subtitle = in.bundle->manifest.name;
  d.generated = generated;
  d.sections.push_back(SummarySection(in, hull));
  d.sections.push_back(NotInspectedSection(in));
  d.sections.push_back(MethodSection(in));
  d.sections.push_back(DeviationSection(in, options, figures));
  d.sections.push_back(UncertaintySection(in, options, figures));
  d.sections.push_back(CrossSectionSection(in, hull, options, figures));
  d.sections.push_back(MosaicSection(in, figures));
  d.sections.push_back(ObjectsSection(in));
  d.sections.push_back(ZonesSection(in));
  d.sections.push_back(ChangeSection(in, figures));
  d.sections.push_back(SolverSection(in, figures));
  d.sections.push_back(EvaluationSection(in));
  return d;
}

}  // namespace hull::report
