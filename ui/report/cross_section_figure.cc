// The cross-section (the paper's Fig. 14): one column per surface model, three
// rows -- the whole section of the hull, the surveyed part of it, and a
// close-up -- each at equal scales on both axes. The CAD profile, the fused
// model's profile, the DVL returns and the features inside the slab.
#include <QFontMetricsF>
#include <algorithm>
#include <cmath>

#include "ui/report/figures.h"
#include "ui/report/plot_painter.h"

namespace hull::report {
namespace {

constexpr double kLeft = 62, kRight = 12, kGap = 18, kTop = 40;
constexpr double kRowGap = 50;
constexpr double kCloseUpWidth = 1.0;  // m

const QColor kCad(0x10, 0x10, 0x10);
const QColor kFused(0xf0, 0x7f, 0x00);
const QColor kDvl(0x1f, 0x5f, 0xd0);
const QColor kOnHull(0x1a, 0x9e, 0x3a);
const QColor kOffHull(0xd7, 0x19, 0x1c);
const QColor kWindow(0xe0, 0x40, 0xa0);

Eigen::AlignedBox2d Grow(const Eigen::AlignedBox2d& b, double m) {
  return {b.min() - Eigen::Vector2d(m, m), b.max() + Eigen::Vector2d(m, m)};
}

// The window of `box`'s centre with the aspect of a w x h rectangle, no
// smaller than box.
Eigen::AlignedBox2d Fit(const Eigen::AlignedBox2d& box, double w, double h) {
  Eigen::Vector2d c = box.center(), s = box.sizes();
  if (s.x() / s.y() < w / h) {
    s.x() = s.y() * w / h;
  } else {
    s.y() = s.x() * h / w;
  }
  return {c - s / 2, c + s / 2};
}

class CrossSectionFigure final : public Figure {
 public:
  CrossSectionFigure(const FigureRef& ref, const ReportInputs& in, const ReportOptions& options)
      : Figure(ref), cs_(BuildCrossSection(in, ReportHullFrame(in), options)) {
    const int n = std::max<int>(1, static_cast<int>(cs_.models.size()));
    col_width_ = (kFigureWidth - kLeft - kRight - (n - 1) * kGap) / n;
    // Row 1: the whole section.
    Eigen::AlignedBox2d hull = cs_.hull_box.isEmpty()
                                   ? Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1))
                                   : Grow(cs_.hull_box, 0.5);
    const Eigen::Vector2d hs = hull.sizes();
    row_height_[0] = std::clamp(col_width_ * hs.y() / hs.x(), 70.0, 170.0);
    windows_[0] = Fit(hull, col_width_, row_height_[0]);
    // Row 2: the data in the slab.
    Eigen::AlignedBox2d data = cs_.data_box.isEmpty() ? hull : Grow(cs_.data_box, 0.3);
    row_height_[1] = 130;
    windows_[1] = Fit(data, col_width_, row_height_[1]);
    // Row 3: the close-up.
    row_height_[2] = 150;
    // Centred on the focus across the hull, and on the middle of what lies
    // there (the profile, the object's features) along up.
    const double half_w = std::min(kCloseUpWidth, windows_[1].sizes().x()) / 2;
    const double half_h = half_w * row_height_[2] / col_width_;
    Eigen::AlignedBox<double, 1> up;
    for (const SectionModel& m : cs_.models) {
      for (const SectionFeature& f : m.features) {
        if (std::abs(f.p.x() - cs_.focus_point.x()) <= half_w) up.extend(Eigen::Matrix<double, 1, 1>(f.p.y()));
      }
    }
    Eigen::Vector2d centre = cs_.focus_point;
    if (!up.isEmpty() && up.sizes()[0] < 2 * half_h) centre.y() = up.center()[0];
    windows_[2] =
        Eigen::AlignedBox2d(centre - Eigen::Vector2d(half_w, half_h), centre + Eigen::Vector2d(half_w, half_h));
    double y = kTop;
    for (int r = 0; r < 3; ++r) {
      top_[r] = y;
      y += row_height_[r] + kRowGap;
    }
    legend_top_ = y - kRowGap + 30;
    height_ = legend_top_ + 44;
  }

  double Height() const override { return height_; }

  void Paint(QPainter& p) const override {
    static const char* const kRows[] = {"whole section", "surveyed part", "close-up"};
    for (std::size_t c = 0; c < cs_.models.size(); ++c) {
      const SectionModel& m = cs_.models[c];
      const double x = kLeft + c * (col_width_ + kGap);
      for (int r = 0; r < 3; ++r) {
        PlotFrame f;
        f.rect = QRectF(x, top_[r], col_width_, row_height_[r]);
        f.x0 = windows_[r].min().x();
        f.x1 = windows_[r].max().x();
        f.y0 = windows_[r].min().y();
        f.y1 = windows_[r].max().y();
        PaintPanel(p, f, m, r, c == 0);
        const QString letter = QString(QChar('a' + static_cast<char>(3 * c + r)));
        QString title = QStringLiteral("(%1) ").arg(letter);
        title += r == 0 ? ModelLabel(m.model) : QString::fromLatin1(kRows[r]);
        if (r == 0 && cs_.models.size() == 1) title += QStringLiteral(", whole section");
        if (r == 2 && !cs_.focus.empty()) title += QStringLiteral(" of %1").arg(QString::fromStdString(cs_.focus));
        DrawTitle(p, f.rect, title);
      }
    }
    std::vector<LegendEntry> legend{{kCad, QStringLiteral("CAD profile"), LegendEntry::Mark::kLine}};
    bool fused = false;
    for (const SectionModel& m : cs_.models) fused = fused || !m.fused.empty();
    if (fused) legend.push_back({kFused, QStringLiteral("fused model"), LegendEntry::Mark::kLine});
    legend.push_back({kDvl, QStringLiteral("DVL returns"), LegendEntry::Mark::kDot});
    legend.push_back({kOnHull, QStringLiteral("features on the hull"), LegendEntry::Mark::kDot});
    legend.push_back(
        {kOffHull, QStringLiteral("features off the hull (λ = 0 or |h| > %1 m)").arg(cs_.decision_boundary, 0, 'f', 3),
         LegendEntry::Mark::kDot});
    DrawLegendRow(p, QRectF(0, legend_top_, kFigureWidth, 16), legend);
    p.save();
    p.setFont(FigureFont(10));
    p.setPen(QColor(0x30, 0x30, 0x30));
    p.drawText(QRectF(0, legend_top_ + 22, kFigureWidth, 16), Qt::AlignCenter,
               QStringLiteral("slab %1 m wide at %2 m from the bow, seen looking aft: starboard ← → port (m), up (m)")
                   .arg(cs_.width, 0, 'f', 2)
                   .arg(cs_.from_bow, 0, 'f', 2));
    p.restore();
  }

 private:
  void PaintPanel(QPainter& p, const PlotFrame& f, const SectionModel& m, int row, bool first_column) const {
    AxisLabels axes;
    axes.y_tick_labels = first_column;
    axes.x_ticks = NiceTicks(f.x0, f.x1, row == 2 ? 4 : 5);
    axes.y_ticks = NiceTicks(f.y0, f.y1, 3);
    axes.x_step = axes.x_ticks.size() > 1 ? axes.x_ticks[1] - axes.x_ticks[0] : 1;
    axes.y_step = axes.y_ticks.size() > 1 ? axes.y_ticks[1] - axes.y_ticks[0] : 1;
    DrawAxes(p, f, axes);
    p.save();
    p.setClipRect(f.rect.adjusted(0.5, 0.5, -0.5, -0.5));
    const double dot = row == 2 ? 2.4 : 1.7;
    p.setPen(QPen(kCad, row == 0 ? 1.2 : 1.6));
    for (const Segment2& s : cs_.cad) p.drawLine(f.Map(s.a.x(), s.a.y()), f.Map(s.b.x(), s.b.y()));
    p.setPen(QPen(kFused, 1.6));
    for (const Segment2& s : m.fused) p.drawLine(f.Map(s.a.x(), s.a.y()), f.Map(s.b.x(), s.b.y()));
    p.setPen(Qt::NoPen);
    p.setBrush(kDvl);
    for (const Eigen::Vector2d& d : m.dvl) p.drawEllipse(f.Map(d.x(), d.y()), dot, dot);
    for (const bool off : {false, true}) {  // off-hull features on top
      p.setBrush(off ? kOffHull : kOnHull);
      for (const SectionFeature& s : m.features) {
        if (s.off_hull == off) p.drawEllipse(f.Map(s.p.x(), s.p.y()), dot, dot);
      }
    }
    // The next row's window.
    if (row < 2) {
      const Eigen::AlignedBox2d& w = windows_[row + 1];
      p.setPen(QPen(kWindow, 1.4));
      p.setBrush(Qt::NoBrush);
      QRectF box(f.Map(w.min().x(), w.max().y()), f.Map(w.max().x(), w.min().y()));
      if (box.width() < 3) box.adjust(-1.5, 0, 1.5, 0);
      if (box.height() < 3) box.adjust(0, -1.5, 0, 1.5);
      p.drawRect(box);
    }
    p.restore();
  }

  CrossSection cs_;
  double col_width_ = 200;
  double row_height_[3] = {100, 130, 150};
  double top_[3] = {0, 0, 0};
  Eigen::AlignedBox2d windows_[3];
  double legend_top_ = 450, height_ = 500;
};

}  // namespace

std::unique_ptr<Figure> MakeCrossSectionFigure(const FigureRef& ref, const ReportInputs& inputs,
                                               const ReportOptions& options) {
  return std::make_unique<CrossSectionFigure>(ref, inputs, options);
}

}  // namespace hull::report
