// The report's uncertainty and change sections: the fused model's per-vertex
// sigma and significance (M3C2's level of detection, |h| > k sigma) and,
// with a comparison, the change since an earlier survey of the hull.
#include <algorithm>
#include <array>
#include <cmath>

#include "mapping/vertex_significance.h"
#include "ui/report/report_blocks.h"
#include "ui/report/report_sections.h"

namespace hull::report {
namespace {

bool HasSigma(const ReportInputs& in) { return in.mapping && HasVertexSigma(in.mapping->model); }

}  // namespace

void PlanTrustFigures(const ReportInputs& in, const ReportOptions& options, std::vector<FigureRef>& figures) {
  const std::vector<HullView> views = HeatmapViews(figures);
  const std::string k = Num(options.significance_k, 2);
  if (HasSigma(in)) {
    for (const HullView v : views) {
      figures.push_back(ViewFigure(
          FigureKind::kSigmaHeatmap, "sigma", v, "Uncertainty of the deviation, " + ViewWords(v),
          "The fused model coloured by each vertex's standard deviation σ of its deviation (the σ_h of the nearest "
          "adjusted feature, from the adjustment's covariance), seen " +
              ViewWords(v) + "; grey where no feature has a σ."));
    }
    for (const HullView v : views) {
      figures.push_back(ViewFigure(
          FigureKind::kSignificanceHeatmap, "significance", v, "Significant deviation, " + ViewWords(v),
          "The fused model's deviation h where it exceeds its level of detection, |h| > " + k +
              " σ (red: off the hull, blue: below it), and grey where it does not, seen " + ViewWords(v) + "."));
    }
  }
  if (in.comparison) {
    for (const HullView v : views) {
      figures.push_back(ViewFigure(
          FigureKind::kChangeHeatmap, "change", v, "Change in height since the earlier survey, " + ViewWords(v),
          "This survey's (B's) fused model coloured by its change in height since survey A at the same point of "
          "the CAD surface (red: grown, blue: lower), seen " +
              ViewWords(v) + "."));
    }
  }
}

Section UncertaintySection(const ReportInputs& in, const ReportOptions& options,
                           const std::vector<FigureRef>& figures) {
  Section s{"uncertainty", "Uncertainty and significance", true, {}};
  if (!in.mapping) {
    s.blocks.push_back(Paragraph("Mapping has not run: there is no fused model to give an uncertainty."));
    return s;
  }
  if (!HasSigma(in)) {
    s.blocks.push_back(
        Paragraph("The adjustment gave no landmark covariances (adjust --covariance none), so the fused model has no "
                  "per-vertex σ and no deviation can be called significant."));
    return s;
  }
  const TriangleMesh& model = in.mapping->model;
  const std::vector<double>& sigma = *model.FindScalar("sigma");
  std::vector<double> finite;
  for (const double v : sigma) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  const std::size_t significant = CountSignificant(model, options.significance_k);
  s.blocks.push_back(Paragraph(
      "The adjustment gives each feature a covariance, propagated to the standard deviation σ_h of its signed "
      "distance from the CAD surface; each vertex of the fused model takes the σ_h of the nearest feature. Over the " +
      Count(finite.size()) + " vertices with a σ it runs from " + Quantile(finite, 0.0, 4) + " m to " +
      Quantile(finite, 1.0, 4) + " m (median " + Quantile(finite, 0.5, 4) +
      " m). A deviation h is significant "
      "where |h| > k σ (k = " +
      Num(options.significance_k, 2) + "; 1.96 is the 95 % level of detection for a normal error): " +
      Count(static_cast<long long>(significant)) + " of " + Count(static_cast<long long>(model.num_vertices())) +
      " vertices (" + Percent(model.num_vertices() ? double(significant) / model.num_vertices() : 0.0, 1) + ")."));
  for (const FigureRef& f : figures) {
    if (f.kind == FigureKind::kSigmaHeatmap || f.kind == FigureKind::kSignificanceHeatmap) {
      s.blocks.push_back(FigureBlock(f));
    }
  }
  return s;
}

Section ChangeSection(const ReportInputs& in, const std::vector<FigureRef>& figures) {
  Section s{"change", "Change between surveys", true, {}};
  if (!in.comparison) {
    s.blocks.push_back(
        Paragraph("No earlier survey of this hull was compared with this one (the GUI's Inspection ▸ Compare with…, or "
                  "hullinspect-cli report RESULTS --compare-with EARLIER_RESULTS --out DIR, or the report of a "
                  "comparison folder: hullinspect-cli report CHANGE --out DIR)."));
    return s;
  }
  const SurveyComparisonRun& r = *in.comparison;
  const SurveyComparison& c = r.comparison;
  std::array<int, 5> n{};
  for (const ObjectChange& o : c.objects) ++n[static_cast<std::size_t>(o.kind)];
  auto count = [&](ObjectChangeKind k) { return n[static_cast<std::size_t>(k)]; };
  s.blocks.push_back(
      Facts({{"Survey A (earlier)", r.folder_a},
             {"Survey B (this one)", r.folder_b},
             {"CAD mesh", r.mesh.empty() ? "(in memory)" : r.mesh},
             {"Vertices changed significantly", Count(static_cast<long long>(c.significant_vertices)) + " of " +
                                                    Count(static_cast<long long>(c.model.num_vertices()))},
             {"Objects", Format("%d new, %d grown, %d shrunk, %d removed, %d unchanged", count(ObjectChangeKind::kNew),
                                count(ObjectChangeKind::kGrown), count(ObjectChangeKind::kShrunk),
                                count(ObjectChangeKind::kRemoved), count(ObjectChangeKind::kUnchanged))}}));
  s.blocks.push_back(Paragraph(
      "Both surveys were mapped against the same CAD mesh. The change in height at a vertex of B's model is B's "
      "deviation minus A's at the same point of the CAD surface; it is significant where it exceeds k times the "
      "combined σ of both. B's map is first registered to A's by the peaks the two have in common. Objects are "
      "compared at their peaks (each object's highest point and its other local maxima), where both maps' highest "
      "heights nearby are read: an object grew or shrank where a peak's height changed by the threshold or more, "
      "is new or removed where the other map has no object and stands below the threshold, and was there below "
      "the other map's detection otherwise. One row per pair of objects and kind, at the peak that changed most: "
      "two maps may join touching lumps that the other splits."));
  Table t = MakeTable({{"Change", false},
                       {"Survey A", false},
                       {"Survey B", false},
                       {"Peak x, y, z (m)", true},
                       {"Height A (m)", true},
                       {"Height B (m)", true},
                       {"Height change (m)", true}});
  for (const ObjectChange& o : c.objects) {
    t.rows.push_back({ObjectChangeKindName(o.kind), o.id_a.empty() ? "–" : o.id_a, o.id_b.empty() ? "–" : o.id_b,
                      Format("%.2f, %.2f, %.2f", o.centroid.x(), o.centroid.y(), o.centroid.z()),
                      o.kind == ObjectChangeKind::kNew ? "–" : Num(o.height_a, 3),
                      o.kind == ObjectChangeKind::kRemoved ? "–" : Num(o.height_b, 3), Format("%+.3f", o.change)});
  }
  s.blocks.push_back(TableBlock(std::move(t)));
  for (const FigureRef& f : figures) {
    if (f.kind == FigureKind::kChangeHeatmap) s.blocks.push_back(FigureBlock(f));
  }
  return s;
}

}  // namespace hull::report
