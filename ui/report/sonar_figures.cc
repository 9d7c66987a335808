// The sonar report's figures: the plan view of the vehicle's path (filter,
// dead reckoning, smoother) with the features and their 2-sigma ellipses,
// and, with truth, the errors per step.
#include <Eigen/Eigenvalues>
#include <QPainterPath>
#include <algorithm>
#include <cmath>
#include <limits>

#include "ui/report/figures.h"
#include "ui/report/plot_painter.h"

namespace hull::report {
namespace {

struct Path2 {
  std::vector<QPointF> points;
  QColor colour;
  QString label;
  Qt::PenStyle style = Qt::SolidLine;
};

struct Ellipse2 {
  QPointF centre;
  double a = 0, b = 0, angle = 0;  // 2-sigma semi-axes (m), angle of a (rad)
  bool placed = true;
};

Ellipse2 TwoSigmaEllipse(const SonarFeatureEstimate& f) {
  const Eigen::Matrix2d c = f.covariance.topLeftCorner<2, 2>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(c);
  Ellipse2 e;
  e.centre = QPointF(f.position.x(), f.position.y());
  const Eigen::Vector2d v = es.eigenvalues().cwiseMax(0.0);
  e.a = 2 * std::sqrt(v(1));
  e.b = 2 * std::sqrt(v(0));
  e.angle = std::atan2(es.eigenvectors()(1, 1), es.eigenvectors()(0, 1));
  e.placed = f.in_state;
  return e;
}

// Bounds of every point drawn, squared up with a margin so x and y share a scale.
PlotFrame EqualFrame(const QRectF& rect, const std::vector<QPointF>& pts) {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (!pts.empty()) {
    x0 = x1 = pts[0].x();
    y0 = y1 = pts[0].y();
    for (const QPointF& q : pts) {
      x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
      y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
    }
  }
  const double per_unit = std::max({(x1 - x0) / rect.width(), (y1 - y0) / rect.height(), 1e-6}) * 1.1;
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  PlotFrame f;
  f.rect = rect;
  f.x0 = cx - per_unit * rect.width() / 2;
  f.x1 = cx + per_unit * rect.width() / 2;
  f.y0 = cy - per_unit * rect.height() / 2;
  f.y1 = cy + per_unit * rect.height() / 2;
  return f;
}

class SonarPlanFigure final : public Figure {
 public:
  SonarPlanFigure(const FigureRef& ref, const SonarPipelineResult& r) : Figure(ref) {
    Path2 filter{{}, QColor(0x1f, 0x77, 0xb4), QStringLiteral("filter"), Qt::SolidLine};
    Path2 dr{{}, QColor(0x7f, 0x7f, 0x7f), QStringLiteral("dead reckoning"), Qt::DashLine};
    for (const SonarStepRecord& s : r.run.steps) {
      filter.points.emplace_back(s.estimate.pose(0), s.estimate.pose(1));
      dr.points.emplace_back(s.dead_reckoning(0), s.dead_reckoning(1));
    }
    paths_ = {dr, filter};
    if (r.smoother) {
      Path2 sm{{}, QColor(0xd6, 0x27, 0x28), QStringLiteral("smoother"), Qt::SolidLine};
      for (const Vector6d& x : r.smoother->result.poses) sm.points.emplace_back(x(0), x(1));
      paths_.push_back(sm);
    }
    for (const SonarFeatureEstimate& f : r.run.final_features) ellipses_.push_back(TwoSigmaEllipse(f));
  }
  double Height() const override { return 560; }

  void Paint(QPainter& p) const override {
    const QRectF rect(70, 20, 700, 480);
    std::vector<QPointF> all;
    for (const Path2& path : paths_) all.insert(all.end(), path.points.begin(), path.points.end());
    for (const Ellipse2& e : ellipses_) all.push_back(e.centre);
    const PlotFrame f = EqualFrame(rect, all);
    AxisLabels axes;
    axes.x = QStringLiteral("x (m)");
    axes.y = QStringLiteral("y (m)");
    axes.x_ticks = NiceTicks(f.x0, f.x1, 8);
    axes.y_ticks = NiceTicks(f.y0, f.y1, 6);
    axes.x_step = axes.x_ticks.size() > 1 ? axes.x_ticks[1] - axes.x_ticks[0] : 1;
    axes.y_step = axes.y_ticks.size() > 1 ? axes.y_ticks[1] - axes.y_ticks[0] : 1;
    DrawAxes(p, f, axes);
    p.save();
    p.setClipRect(rect);
    PaintEllipses(p, f);
    PaintPaths(p, f);
    p.restore();
    std::vector<LegendEntry> legend;
    for (const Path2& path : paths_) {
      legend.push_back(
          {path.colour, path.label, path.style == Qt::DashLine ? LegendEntry::Mark::kDash : LegendEntry::Mark::kLine});
    }
    legend.push_back({QColor(0x2c, 0xa0, 0x2c), QStringLiteral("feature (2σ)"), LegendEntry::Mark::kDot});
    legend.push_back({QColor(0xbb, 0xbb, 0xbb), QStringLiteral("waiting"), LegendEntry::Mark::kDot});
    DrawLegendRow(p, QRectF(20, 528, 760, 24), legend);
  }

 private:
  void PaintPaths(QPainter& p, const PlotFrame& f) const {
    for (const Path2& path : paths_) {
      if (path.points.empty()) continue;
      QPainterPath line;
      line.moveTo(f.Map(path.points[0].x(), path.points[0].y()));
      for (const QPointF& q : path.points) line.lineTo(f.Map(q.x(), q.y()));
      p.setPen(QPen(path.colour, 2, path.style));
      p.setBrush(Qt::NoBrush);
      p.drawPath(line);
    }
  }
  void PaintEllipses(QPainter& p, const PlotFrame& f) const {
    const double scale = f.rect.width() / (f.x1 - f.x0);  // figure units per metre, both axes
    for (const Ellipse2& e : ellipses_) {
      const QColor c = e.placed ? QColor(0x2c, 0xa0, 0x2c) : QColor(0xbb, 0xbb, 0xbb);
      const QPointF at = f.Map(e.centre.x(), e.centre.y());
      p.save();
      p.translate(at);
      p.rotate(-e.angle * 180 / M_PI);  // y points up in the data, down on the page
      p.setPen(QPen(c, 1));
      p.setBrush(Qt::NoBrush);
      p.drawEllipse(QPointF(0, 0), std::max(1.0, e.a * scale), std::max(1.0, e.b * scale));
      p.restore();
      p.setPen(Qt::NoPen);
      p.setBrush(c);
      p.drawEllipse(at, 2.5, 2.5);
    }
  }

  std::vector<Path2> paths_;
  std::vector<Ellipse2> ellipses_;
};

struct Series {
  std::vector<double> values;  // per step (NaN: none)
  QColor colour;
  QString label;
};

class SonarErrorsFigure final : public Figure {
 public:
  SonarErrorsFigure(const FigureRef& ref, const SonarPipelineResult& r) : Figure(ref) {
    Series filter{{}, QColor(0x1f, 0x77, 0xb4), QStringLiteral("filter position")};
    Series dr{{}, QColor(0x7f, 0x7f, 0x7f), QStringLiteral("dead reckoning")};
    Series feat{{}, QColor(0x2c, 0xa0, 0x2c), QStringLiteral("filter, mean feature error")};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const SonarStepRecord& s : r.run.steps) {
      filter.values.push_back(s.errors ? s.errors->position : nan);
      dr.values.push_back(s.errors ? s.errors->dr_position : nan);
      feat.values.push_back(s.errors && s.errors->features > 0 ? s.errors->mean_feature_error : nan);
    }
    series_ = {dr, filter, feat};
    if (r.smoother && !r.smoother->pose_position_errors.empty()) {
      series_.push_back({r.smoother->pose_position_errors, QColor(0xd6, 0x27, 0x28), QStringLiteral("smoother")});
    }
  }
  double Height() const override { return 330; }

  void Paint(QPainter& p) const override {
    const QRectF rect(78, 20, 690, 240);
    double hi = 0;
    std::size_t n = 1;
    for (const Series& s : series_) {
      for (double v : s.values) hi = std::isfinite(v) ? std::max(hi, v) : hi;
      n = std::max(n, s.values.size());
    }
    PlotFrame f;
    f.rect = rect;
    f.x0 = 0;
    f.x1 = std::max<double>(1, static_cast<double>(n - 1));
    f.y0 = 0;
    f.y1 = hi > 0 ? hi * 1.1 : 1;
    AxisLabels axes;
    axes.x = QStringLiteral("step");
    axes.y = QStringLiteral("error (m)");
    axes.x_ticks = NiceTicks(f.x0, f.x1, 8);
    axes.x_step = 1;
    axes.y_ticks = NiceTicks(f.y0, f.y1, 5);
    axes.y_step = axes.y_ticks.size() > 1 ? axes.y_ticks[1] - axes.y_ticks[0] : 0.01;
    DrawAxes(p, f, axes);
    p.save();
    p.setClipRect(rect);
    std::vector<LegendEntry> legend;
    for (const Series& s : series_) {
      QPainterPath line;
      bool pen_down = false;
      for (std::size_t k = 0; k < s.values.size(); ++k) {
        if (!std::isfinite(s.values[k])) {
          pen_down = false;
          continue;
        }
        const QPointF q = f.Map(static_cast<double>(k), s.values[k]);
        pen_down ? line.lineTo(q) : line.moveTo(q);
        pen_down = true;
      }
      p.setPen(QPen(s.colour, 2));
      p.setBrush(Qt::NoBrush);
      p.drawPath(line);
      legend.push_back({s.colour, s.label, LegendEntry::Mark::kLine});
    }
    p.restore();
    DrawLegendRow(p, QRectF(20, 296, 760, 24), legend);
  }

 private:
  std::vector<Series> series_;
};

}  // namespace

std::unique_ptr<Figure> MakeSonarFigure(const FigureRef& ref, const ReportInputs& inputs) {
  if (!inputs.sonar) throw std::invalid_argument("report: a sonar figure needs a sonar run");
  if (ref.kind == FigureKind::kSonarPlan) return std::make_unique<SonarPlanFigure>(ref, *inputs.sonar);
  return std::make_unique<SonarErrorsFigure>(ref, *inputs.sonar);
}

}  // namespace hull::report
