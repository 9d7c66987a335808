#include "ui/models/solver_plot_data.h"

#include <algorithm>
#include <cmath>

namespace hull::ui {

namespace {

const SurfaceModel kOrder[] = {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture};

double NegLogNormal(double h, double sigma) {
  return 0.5 * (h / sigma) * (h / sigma) + std::log(sigma) + 0.5 * std::log(2 * M_PI);
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// One value of the iteration log against the iteration index, in the model's colour.
PlotSeries IterationSeries(SurfaceModel model, const AdjustmentResult& result, double IterationRecord::*value) {
  PlotSeries s;
  s.name = ModelShortName(model);
  s.colour = ModelColour(model);
  int i = 0;
  for (const IterationRecord& r : result.iterations) s.points.emplace_back(i++, r.*value);
  return s;
}

}  // namespace

QColor ModelColour(SurfaceModel model) {
  switch (model) {
    case SurfaceModel::kNaive:
      return QColor(150, 150, 150);
    case SurfaceModel::kAllOnSurface:
      return QColor(230, 140, 30);
    case SurfaceModel::kMaxMixture:
      return QColor(40, 110, 200);
  }
  return {};
}

QString ModelShortName(SurfaceModel model) {
  switch (model) {
    case SurfaceModel::kNaive:
      return QStringLiteral("Naive");
    case SurfaceModel::kAllOnSurface:
      return QStringLiteral("All on surface");
    case SurfaceModel::kMaxMixture:
      return QStringLiteral("Max-mixture");
  }
  return {};
}

double RobustSpread(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  if (values.empty()) return 0;
  const double m = Median(values);
  for (double& v : values) v = std::abs(v - m);
  return 1.4826 * Median(values);
}

PlotData CostPlot(const RunsByModel& runs) {
  PlotData d;
  d.title = QStringLiteral("Cost per iteration");
  d.x_label = QStringLiteral("iteration");
  d.y_label = QStringLiteral("cost ½Σr²");
  d.log_y = true;
  d.empty_text = QStringLiteral("Run the inspection (F5)");
  for (SurfaceModel m : kOrder) {
    auto it = runs.find(m);
    if (it == runs.end()) continue;
    d.series.push_back(IterationSeries(m, *it->second->result, &IterationRecord::cost));
  }
  return d;
}

PlotData FractionPlot(const std::shared_ptr<const AdjustmentRun>& run) {
  PlotData d;
  d.title = QStringLiteral("Features on the hull (λ = 1)");
  d.x_label = QStringLiteral("iteration");
  d.y_label = QStringLiteral("fraction");
  d.empty_text = QStringLiteral("Run the inspection (F5)");
  if (!run) return d;
  const PlotSeries s = IterationSeries(run->model(), *run->result, &IterationRecord::fraction_on_surface);
  PlotSeries dots = s;
  dots.name.clear();
  dots.style = PlotSeries::Style::kPoints;
  d.series.push_back(s);
  d.series.push_back(dots);
  if (!s.points.empty()) {
    d.note = QStringLiteral("final %1 %").arg(100.0 * s.points.back().y(), 0, 'f', 1);
  }
  return d;
}

PlotData TimePlot(const RunsByModel& runs) {
  PlotData d;
  d.title = QStringLiteral("Time per model");
  d.y_label = QStringLiteral("seconds");
  d.empty_text = QStringLiteral("Inspection ▸ Compare models runs the other two models");
  if (runs.size() < 2) return d;
  double naive = 0;
  if (auto it = runs.find(SurfaceModel::kNaive); it != runs.end()) naive = it->second->result->seconds;
  int x = 0;
  QStringList notes;
  for (SurfaceModel m : kOrder) {
    auto it = runs.find(m);
    QString label = ModelShortName(m);
    if (it != runs.end()) {
      PlotSeries s;
      s.colour = ModelColour(m);
      s.style = PlotSeries::Style::kBars;
      s.bin_width = 1.0;
      const AdjustmentResult& r = *it->second->result;
      s.points.emplace_back(x, r.seconds);
      d.series.push_back(s);
      const int iterations = r.iterations.empty() ? 0 : r.iterations.back().iteration;
      label += QStringLiteral("\n%1 it.%2")
                   .arg(iterations)
                   .arg(it->second->warm_started ? QStringLiteral(", warm") : QString());
      if (naive > 0 && m != SurfaceModel::kNaive) {
        notes << QStringLiteral("%1 %2%3 %")
                     .arg(ModelShortName(m))
                     .arg(r.seconds >= naive ? "+" : "")
                     .arg(100.0 * (r.seconds / naive - 1.0), 0, 'f', 1);
      }
    }
    d.x_categories << label;
    ++x;
  }
  d.x_range = std::make_pair(-0.6, 2.6);
  if (!notes.isEmpty()) d.note = QStringLiteral("vs naive: ") + notes.join(QStringLiteral(" / "));
  return d;
}

PlotData DvlResidualPlot(const std::shared_ptr<const AdjustmentRun>& run) {
  PlotData d;
  d.title = QStringLiteral("DVL range residuals");
  d.x_label = QStringLiteral("measured − predicted (m)");
  d.y_label = QStringLiteral("beams");
  d.empty_text = QStringLiteral("Run the inspection (F5)");
  if (!run) return d;
  std::vector<double> initial, final;
  for (const DvlResidual& r : run->result->dvl) {
    if (std::isfinite(r.initial)) initial.push_back(r.initial);
    if (std::isfinite(r.final)) final.push_back(r.final);
  }
  if (initial.empty() && final.empty()) return d;
  // A range that shows the bulk of the initial residuals (their 98th
  // percentile of |r|) and the whole of the final ones' spread.
  std::vector<double> mags;
  for (double v : initial) mags.push_back(std::abs(v));
  for (double v : final) mags.push_back(std::abs(v));
  std::sort(mags.begin(), mags.end());
  double reach = mags[static_cast<std::size_t>(0.98 * (mags.size() - 1))];
  reach = std::max(reach, 0.01);
  const int bins = 41;
  const double width = 2 * reach / bins;
  auto histogram = [&](const std::vector<double>& values, const QString& name, const QColor& colour) {
    PlotSeries s;
    s.name = QStringLiteral("%1: %2 cm").arg(name).arg(100.0 * RobustSpread(values), 0, 'f', 2);
    s.colour = colour;
    s.style = PlotSeries::Style::kHistogram;
    s.bin_width = width;
    std::vector<int> counts(bins, 0);
    for (double v : values) {
      const int b = static_cast<int>(std::floor((v + reach) / width));
      if (b >= 0 && b < bins) ++counts[b];
    }
    for (int b = 0; b < bins; ++b) s.points.emplace_back(-reach + b * width, counts[b]);
    return s;
  };
  d.series.push_back(histogram(initial, QStringLiteral("aligned"), QColor(150, 150, 150)));
  d.series.push_back(histogram(final, QStringLiteral("adjusted"), ModelColour(run->model())));
  d.note = QStringLiteral("robust spread (1.48 MAD)");
  d.x_range = std::make_pair(-reach, reach);
  return d;
}

PlotData MixturePlot(double sigma0, double sigma1) {
  PlotData d;
  d.title = QStringLiteral("Max-mixture surface cost");
  d.x_label = QStringLiteral("signed distance h (m)");
  d.y_label = QStringLiteral("−log N(h; 0, σ²)");
  if (!(sigma0 > sigma1 && sigma1 > 0)) {
    d.empty_text = QStringLiteral("σ₁ must be smaller than σ₀");
    return d;
  }
  AdjustmentOptions o;
  o.sigma0 = sigma0;
  o.sigma1 = sigma1;
  const double b = o.DecisionBoundary();
  const double reach = 3.0 * b;
  PlotSeries c0, c1, mix;
  c0.name = QStringLiteral("λ = 0, σ₀ %1 m").arg(sigma0, 0, 'g', 3);
  c0.colour = QColor(220, 60, 60);
  c1.name = QStringLiteral("λ = 1, σ₁ %1 m").arg(sigma1, 0, 'g', 3);
  c1.colour = QColor(40, 170, 70);
  mix.name = QStringLiteral("max-mixture");
  mix.colour = QColor(30, 30, 30);
  mix.dashed = true;
  mix.width = 1.2;
  const int n = 241;
  double lo = 1e300;
  for (int i = 0; i < n; ++i) {
    const double h = -reach + 2 * reach * i / (n - 1);
    const double a = NegLogNormal(h, sigma0), c = NegLogNormal(h, sigma1);
    c0.points.emplace_back(h, a);
    c1.points.emplace_back(h, c);
    mix.points.emplace_back(h, std::min(a, c));
    lo = std::min({lo, a, c});
  }
  d.series = {c0, c1, mix};
  d.markers.push_back({-b, QString(), QColor(90, 90, 90)});
  d.markers.push_back({b, QString(), QColor(90, 90, 90)});
  // Up to twice the height at the boundary: the crossing stays in view.
  const double at_b = NegLogNormal(b, sigma0);
  d.y_range = std::make_pair(lo - 0.1 * (at_b - lo + 1), at_b + 1.2 * (at_b - lo) + 1.0);
  d.x_range = std::make_pair(-reach, reach);
  d.note = QStringLiteral("boundary |h| = %1 m").arg(b, 0, 'f', 4);
  return d;
}

}  // namespace hull::ui
