// The report's result sections: objects, zones, solver, evaluation and what
// was not inspected.
#include "ui/report/report_sections.h"

#include <array>
#include <cmath>
#include <map>

#include "mapping/fouling.h"
#include "ui/report/report_blocks.h"

namespace hull::report {
namespace {

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

}  // namespace

Section ObjectsSection(const ReportInputs& in) {
  Section s{"objects", "Detected objects", false, {}};
  if (!in.mapping) {
    s.blocks.push_back(Paragraph("Mapping has not run: no objects were detected."));
    return s;
  }
  const MappingResult& m = *in.mapping;
  if (m.objects.empty()) {
    s.blocks.push_back(Paragraph(
        Format("No part of the fused model stands more than %.3f m off the CAD surface over "
               "%.3f m² or more%s: no objects.",
               m.options.object_min_height, m.options.object_min_area,
               m.options.object_min_features > 0 ? Format(" (nor over less, held up by %d features from %d keyframes)",
                                                          m.options.object_min_features, m.options.object_min_views)
                                                       .c_str()
                                                 : "")));
    return s;
  }
  double area = 0;
  for (const DetectedObject& o : m.objects) area += o.area;
  s.blocks.push_back(Paragraph(Format(
      "%zu objects stand more than h_min = %.3f m off the CAD surface, covering %.2f m² in all. Distances are from "
      "the bow along the hull; heights are the fused model's deviation from the CAD surface over each footprint: "
      "the highest vertex with its standard deviation σ (that of the object's feature nearest the peak, from the "
      "adjustment) and the 95th percentile of the footprint's vertex heights.",
      m.objects.size(), m.options.object_min_height, area)));
  Table t = MakeTable({{"Object", false},
                       {"From bow (m)", true},
                       {"Station", true},
                       {"Side", false},
                       {"Area (m²)", true},
                       {"Mean height (m)", true},
                       {"Max height ± σ (m)", true},
                       {"95th pct. (m)", true},
                       {"Features", true},
                       {"Views", true}});
  for (const DetectedObject& o : m.objects) {
    t.rows.push_back({o.id, Num(o.distance_from_bow, 2), std::to_string(o.station), HullSideName(o.side),
                      Num(o.area, 3), Num(o.mean_height, 3),
                      std::isfinite(o.max_height_sigma) ? Num(o.max_height, 3) + " ± " + Num(o.max_height_sigma, 3)
                                                        : Num(o.max_height, 3),
                      Num(o.p95_height, 3), std::to_string(o.num_features), std::to_string(o.num_views)});
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
  Table scale = MakeTable({{"Rating", false}, {"Macrofouling cover", false}, {"Meaning", false}});
  scale.rows = {{"0-1", "below 1 %", "clean (0) or slime and microfouling (1): not told apart by geometry"},
                {"2", "1 % to 15 %", "light macrofouling"},
                {"3", "above 15 % to 40 %", "medium macrofouling"},
                {"4", "above 40 %", "heavy macrofouling"},
                {"uninspected", "–", "no camera saw any of the zone: not rated, never counted as clean"}};
  ToneByRating(scale, 0);
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
  Table t = MakeTable({{"Station", true},
                       {"From–to bow (m)", true},
                       {"Side", false},
                       {"Hull (m²)", true},
                       {"Inspected (m²)", true},
                       {"Inspected (%)", true},
                       {"Covered (m²)", true},
                       {"Cover (%)", true},
                       {"Objects", true},
                       {"Max height (m)", true},
                       {"Rating", false}});
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
  }
  ToneByRating(t, static_cast<int>(t.header.size()) - 1);
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
  Table t = MakeTable({{"Model", false},
                       {"Iterations", true},
                       {"Initial cost", true},
                       {"Final cost", true},
                       {"Time (s)", true},
                       {"Solver (s)", true},
                       {"λ = 1", true},
                       {"Landmarks", true},
                       {"Residual blocks", true},
                       {"Converged", false}});
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
  Table t = MakeTable({{"Measure", false}});
  std::vector<const AdjustmentResult*> models;
  std::vector<const AdjustmentEvaluation*> evals;
  for (const AdjustmentResult* r : ModelsInOrder(p)) {
    if (const AdjustmentEvaluation* e = EvaluationOf(p, r)) {
      models.push_back(r);
      evals.push_back(e);
    }
  }
  for (const AdjustmentResult* r : models) AddColumn(t, {ModelTitle(r->options.model), true});
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
    Table o = MakeTable({{"Object", false},
                         {"Kind", false},
                         {"Height (m)", true},
                         {"Landmarks", true},
                         {"Deviation (m)", true},
                         {"True deviation (m)", true}});
    if (in.mapping) {
      AddColumn(o, {"Fused height (m)", true});
      AddColumn(o, {"Nearest object", false});
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

std::string NotSeenSummary(const ReportInputs& in) {
  std::string text;
  if (in.mapping) {
    std::size_t missing = 0;
    double area = 0, hull_area = 0;
    for (const ZoneAssessment& z : in.mapping->zones) {
      hull_area += z.hull_area;
      if (z.rating != FoulingRating::kUninspected) continue;
      ++missing;
      area += z.hull_area;
    }
    text = Format("%zu of %zu zones uninspected, not rated (%.1f %% of the hull area); ", missing,
                  in.mapping->zones.size(), hull_area > 0 ? 100 * area / hull_area : 0.0);
  } else {
    text = "mapping has not run: the inspected area is not known; ";
  }
  std::map<std::int64_t, int> seen;
  for (const FeatureObservation& f : in.bundle->features) ++seen[f.keyframe];
  std::size_t blind = 0;
  for (const NavRecord& n : in.bundle->nav) blind += seen.count(n.keyframe) ? 0 : 1;
  return text + Format("%zu of %zu keyframes without a feature (see \"What was not inspected\")", blind,
                       in.bundle->nav.size());
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

}  // namespace hull::report
