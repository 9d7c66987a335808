// Solver statistics: the cost and the share of lambda = 1 per iteration
// (the paper's Fig. 16), DVL range residual histograms before and after each
// model (Fig. 18) and the time per model (Fig. 17).
#include <QFontMetricsF>
#include <QLocale>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

#include "ui/report/figures.h"
#include "ui/report/plot_painter.h"

namespace hull::report {
namespace {

struct ModelRun {
  SurfaceModel model = SurfaceModel::kMaxMixture;
  std::vector<IterationRecord> iterations;
  std::vector<double> initial, final;  // DVL residuals (m)
  double seconds = 0, solver_seconds = 0, final_cost = 0;
  bool converged = false;
};

std::vector<ModelRun> Runs(const PipelineResult& result) {
  std::vector<ModelRun> out;
  for (const AdjustmentResult* r : ModelsInOrder(result)) {
    ModelRun m;
    m.model = r->options.model;
    m.iterations = r->iterations;
    for (const DvlResidual& d : r->dvl) {
      m.initial.push_back(d.initial);
      m.final.push_back(d.final);
    }
    m.seconds = r->seconds;
    m.solver_seconds = r->solver_seconds;
    m.final_cost = r->final_cost;
    m.converged = r->converged;
    out.push_back(std::move(m));
  }
  return out;
}

double RobustSpread(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double med = *mid;
  for (double& x : v) x = std::abs(x - med);
  std::nth_element(v.begin(), mid, v.end());
  return 1.4826 * *mid;
}

double Std(const std::vector<double>& v) {
  double s = 0, s2 = 0;
  int n = 0;
  for (double x : v) {
    if (!std::isfinite(x)) continue;
    s += x;
    s2 += x * x;
    ++n;
  }
  if (n < 2) return 0;
  const double mean = s / n;
  return std::sqrt(std::max(0.0, s2 / n - mean * mean));
}

// Ticks for a log axis: powers of ten, or 1-2-5 steps within one or two decades.
std::vector<double> LogAxisTicks(double lo, double hi) {
  std::vector<double> t = LogTicks(lo, hi);
  if (t.size() >= 3) return t;
  t.clear();
  for (double e = std::floor(std::log10(lo)); e <= std::ceil(std::log10(hi)); e += 1) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, e);
      if (v >= lo && v <= hi) t.push_back(v);
    }
  }
  return t;
}

void PaintNoData(QPainter& p, const QRectF& rect, const QString& text) {
  p.save();
  p.setPen(QColor(0x60, 0x60, 0x60));
  p.setFont(FigureFont(11));
  p.drawText(rect, Qt::AlignCenter | Qt::TextWordWrap, text);
  p.restore();
}

class ConvergenceFigure final : public Figure {
 public:
  ConvergenceFigure(const FigureRef& ref, const PipelineResult& r) : Figure(ref), runs_(Runs(r)) {}
  double Height() const override { return 330; }

  void Paint(QPainter& p) const override {
    const QRectF left(78, 36, 290, 230), right(478, 36, 300, 230);
    DrawTitle(p, left, QStringLiteral("Cost per iteration"));
    DrawTitle(p, right, QStringLiteral("Landmarks with λ = 1 (max-mixture)"));
    PaintCost(p, left);
    PaintFraction(p, right);
  }

 private:
  void PaintCost(QPainter& p, const QRectF& rect) const {
    double lo = INFINITY, hi = 0;
    int n = 1;
    for (const ModelRun& m : runs_) {
      for (const IterationRecord& it : m.iterations) {
        if (it.cost > 0) {
          lo = std::min(lo, it.cost);
          hi = std::max(hi, it.cost);
        }
      }
      n = std::max<int>(n, static_cast<int>(m.iterations.size()));
    }
    PlotFrame f;
    f.rect = rect;
    if (!(hi > 0)) {
      DrawAxes(p, f, {});
      PaintNoData(p, rect, QStringLiteral("no iterations recorded"));
      return;
    }
    f.log_y = true;
    f.y0 = std::pow(10, std::floor(std::log10(lo) * 4) / 4);
    f.y1 = std::pow(10, std::ceil(std::log10(hi) * 4) / 4);
    if (f.y1 <= f.y0) f.y1 = f.y0 * 10;
    f.x0 = 0;
    f.x1 = std::max(1, n - 1);
    AxisLabels axes;
    axes.x = QStringLiteral("iteration");
    axes.y = QStringLiteral("cost");
    axes.x_ticks = NiceTicks(f.x0, f.x1, 6);
    axes.x_step = 1;
    axes.y_ticks = LogAxisTicks(f.y0, f.y1);
    DrawAxes(p, f, axes);
    std::vector<LegendEntry> legend;
    p.save();
    p.setClipRect(rect);
    for (const ModelRun& m : runs_) {
      QPainterPath path;
      for (std::size_t i = 0; i < m.iterations.size(); ++i) {
        const QPointF q = f.Map(static_cast<double>(i), std::max(m.iterations[i].cost, f.y0));
        if (i == 0) {
          path.moveTo(q);
        } else {
          path.lineTo(q);
        }
      }
      p.setPen(QPen(ModelColour(m.model), 2.0));
      p.setBrush(Qt::NoBrush);
      p.drawPath(path);
      p.setBrush(ModelColour(m.model));
      for (std::size_t i = 0; i < m.iterations.size(); ++i) {
        p.drawEllipse(f.Map(static_cast<double>(i), std::max(m.iterations[i].cost, f.y0)), 2.2, 2.2);
      }
      legend.push_back(
          {ModelColour(m.model), QStringLiteral("%1 (%2 it.)").arg(ModelLabel(m.model)).arg(m.iterations.size())});
    }
    p.restore();
    DrawLegend(p, rect.topRight(), legend);
  }

  void PaintFraction(QPainter& p, const QRectF& rect) const {
    const ModelRun* mm = nullptr;
    for (const ModelRun& m : runs_) {
      if (m.model == SurfaceModel::kMaxMixture) mm = &m;
    }
    PlotFrame f;
    f.rect = rect;
    if (!mm || mm->iterations.empty()) {
      DrawAxes(p, f, {});
      PaintNoData(p, rect, QStringLiteral("the max-mixture model did not run"));
      return;
    }
    double lo = 1, hi = 0;
    for (const IterationRecord& it : mm->iterations) {
      lo = std::min(lo, it.fraction_on_surface);
      hi = std::max(hi, it.fraction_on_surface);
    }
    f.x0 = 0;
    f.x1 = std::max<double>(1, mm->iterations.size() - 1);
    f.y0 = std::max(0.0, std::floor((lo - 0.02) * 20) / 20);
    f.y1 = std::min(1.0, std::ceil((hi + 0.02) * 20) / 20);
    if (f.y1 <= f.y0) f.y1 = f.y0 + 0.05;
    AxisLabels axes;
    axes.x = QStringLiteral("iteration");
    axes.y = QStringLiteral("share with λ = 1");
    axes.x_ticks = NiceTicks(f.x0, f.x1, 6);
    axes.x_step = 1;
    axes.y_ticks = NiceTicks(f.y0, f.y1, 5);
    axes.y_step = axes.y_ticks.size() > 1 ? axes.y_ticks[1] - axes.y_ticks[0] : 0.1;
    DrawAxes(p, f, axes);
    p.save();
    p.setClipRect(rect);
    QPainterPath path;
    for (std::size_t i = 0; i < mm->iterations.size(); ++i) {
      const QPointF q = f.Map(static_cast<double>(i), mm->iterations[i].fraction_on_surface);
      if (i == 0) {
        path.moveTo(q);
      } else {
        path.lineTo(q);
      }
    }
    const QColor c = ModelColour(SurfaceModel::kMaxMixture);
    p.setPen(QPen(c, 2.0));
    p.drawPath(path);
    p.setBrush(c);
    for (std::size_t i = 0; i < mm->iterations.size(); ++i) {
      p.drawEllipse(f.Map(static_cast<double>(i), mm->iterations[i].fraction_on_surface), 2.2, 2.2);
    }
    p.restore();
    DrawLegend(p, QPointF(rect.right(), rect.bottom() - 50),
               {{c, QStringLiteral("final %1 %").arg(100 * mm->iterations.back().fraction_on_surface, 0, 'f', 1)}});
  }

  std::vector<ModelRun> runs_;
};

class ResidualFigure final : public Figure {
 public:
  ResidualFigure(const FigureRef& ref, const PipelineResult& r) : Figure(ref), runs_(Runs(r)) {
    double spread = 0;
    for (const ModelRun& m : runs_) spread = std::max(spread, RobustSpread(m.initial));
    range_ = std::clamp(std::ceil(4 * spread / 0.05) * 0.05, 0.05, 0.5);
  }
  double Height() const override { return 300; }

  void Paint(QPainter& p) const override {
    const int n = std::max<int>(1, static_cast<int>(runs_.size()));
    const double left = 70, gap = 22, width = (kFigureWidth - left - 14 - (n - 1) * gap) / n;
    constexpr int kBins = 50;
    // One vertical scale for every panel: the tallest bar.
    double top = 0;
    std::vector<std::pair<Histogram, Histogram>> hists;
    for (const ModelRun& m : runs_) {
      hists.emplace_back(MakeHistogram(m.initial, -range_, range_, kBins),
                         MakeHistogram(m.final, -range_, range_, kBins));
      for (const Histogram* h : {&hists.back().first, &hists.back().second}) {
        if (h->total > 0) top = std::max(top, 100.0 * h->Max() / h->total);
      }
    }
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      const ModelRun& m = runs_[i];
      PlotFrame f;
      f.rect = QRectF(left + i * (width + gap), 36, width, 200);
      f.x0 = -range_;
      f.x1 = range_;
      f.y0 = 0;
      f.y1 = std::max(1.0, std::ceil(1.45 * top / 10) * 10);  // headroom for the legend
      AxisLabels axes;
      axes.x = QStringLiteral("residual (m)");
      axes.y = i == 0 ? QStringLiteral("share of returns (%)") : QString();
      axes.y_tick_labels = i == 0;
      axes.x_ticks = NiceTicks(f.x0, f.x1, 4);
      axes.x_step = axes.x_ticks.size() > 1 ? axes.x_ticks[1] - axes.x_ticks[0] : 0.1;
      axes.y_ticks = NiceTicks(f.y0, f.y1, 5);
      axes.y_step = axes.y_ticks.size() > 1 ? axes.y_ticks[1] - axes.y_ticks[0] : 10;
      DrawTitle(p, f.rect, ModelLabel(m.model));
      DrawAxes(p, f, axes);
      PaintHistogram(p, f, hists[i].first, QColor(0xa0, 0xa0, 0xa0, 200));
      QColor c = ModelColour(m.model);
      c.setAlpha(190);
      PaintHistogram(p, f, hists[i].second, c);
      DrawLegend(p, f.rect.topRight(),
                 {{QColor(0xa0, 0xa0, 0xa0), QStringLiteral("initial, σ %1 m").arg(Std(m.initial), 0, 'f', 3),
                   LegendEntry::Mark::kBox},
                  {ModelColour(m.model), QStringLiteral("after, σ %1 m").arg(Std(m.final), 0, 'f', 3),
                   LegendEntry::Mark::kBox}});
    }
    if (runs_.empty()) PaintNoData(p, QRectF(0, 0, kFigureWidth, Height()), QStringLiteral("no DVL residuals"));
  }

 private:
  static void PaintHistogram(QPainter& p, const PlotFrame& f, const Histogram& h, const QColor& c) {
    if (h.total == 0) return;
    p.save();
    p.setClipRect(f.rect);
    p.setPen(QPen(c.darker(140), 0.6));
    p.setBrush(c);
    const double w = (h.hi - h.lo) / h.counts.size();
    for (std::size_t b = 0; b < h.counts.size(); ++b) {
      int count = h.counts[b];
      if (b == 0) count += h.below;
      if (b + 1 == h.counts.size()) count += h.above;
      if (count == 0) continue;
      const double share = 100.0 * count / h.total;
      p.drawRect(QRectF(f.Map(h.lo + b * w, share), f.Map(h.lo + (b + 1) * w, 0)));
    }
    p.restore();
  }

  std::vector<ModelRun> runs_;
  double range_ = 0.1;
};

class TimingFigure final : public Figure {
 public:
  TimingFigure(const FigureRef& ref, const PipelineResult& r) : Figure(ref), runs_(Runs(r)) {}
  double Height() const override { return 30 + 44.0 * runs_.size() + 20 + 50; }

  void Paint(QPainter& p) const override {
    double longest = 0;
    for (const ModelRun& m : runs_) longest = std::max(longest, m.seconds);
    PlotFrame f;
    f.rect = QRectF(130, 30, 340, 44.0 * runs_.size() + 20);
    f.x0 = 0;
    f.x1 = longest > 0 ? longest * 1.08 : 1;
    f.y0 = 0;
    f.y1 = 1;
    AxisLabels axes;
    axes.x = QStringLiteral("wall time (s)");
    axes.x_ticks = NiceTicks(f.x0, f.x1, 5);
    axes.x_step = axes.x_ticks.size() > 1 ? axes.x_ticks[1] - axes.x_ticks[0] : 1;
    DrawTitle(p, f.rect, QStringLiteral("Adjustment time per model"));
    DrawAxes(p, f, axes);
    p.save();
    p.setFont(FigureFont(11));
    const QFontMetricsF fm(p.font());
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      const ModelRun& m = runs_[i];
      const double y = f.rect.top() + 12 + 44.0 * i;
      const QColor c = ModelColour(m.model);
      const double x0 = f.Map(0, 0).x();
      p.setPen(Qt::NoPen);
      p.setBrush(c.lighter(150));
      p.drawRect(QRectF(x0, y, f.Map(m.seconds, 0).x() - x0, 28));
      p.setBrush(c);
      p.drawRect(QRectF(x0, y + 7, f.Map(m.solver_seconds, 0).x() - x0, 14));
      p.setPen(QColor(0x20, 0x20, 0x20));
      p.drawText(QRectF(0, y, f.rect.left() - 8, 28), Qt::AlignRight | Qt::AlignVCenter, ModelLabel(m.model));
      const QString note = QStringLiteral("%1 s (solver %2 s) · %3 iterations · final cost %4%5")
                               .arg(m.seconds, 0, 'f', 2)
                               .arg(m.solver_seconds, 0, 'f', 2)
                               .arg(m.iterations.size())
                               .arg(QLocale::c().toString(std::round(m.final_cost), 'f', 0))
                               .arg(m.converged ? QString() : QStringLiteral(" · not converged"));
      p.drawText(QRectF(f.rect.right() + 10, y, kFigureWidth - f.rect.right() - 12, 28),
                 Qt::AlignLeft | Qt::AlignVCenter | Qt::TextWordWrap, note);
    }
    p.restore();
  }

 private:
  std::vector<ModelRun> runs_;
};

}  // namespace

std::unique_ptr<Figure> MakeSolverFigure(const FigureRef& ref, const ReportInputs& inputs) {
  switch (ref.kind) {
    case FigureKind::kConvergence:
      return std::make_unique<ConvergenceFigure>(ref, *inputs.pipeline);
    case FigureKind::kDvlResiduals:
      return std::make_unique<ResidualFigure>(ref, *inputs.pipeline);
    default:
      return std::make_unique<TimingFigure>(ref, *inputs.pipeline);
  }
}

}  // namespace hull::report
