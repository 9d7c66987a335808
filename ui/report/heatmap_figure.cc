// The deviation heatmap: the fused model (or, before mapping, the CAD with the
// landmarks) seen orthographically from one side, whole and in detail over
// the surveyed stretch. The same figure draws the fused model's per-vertex
// sigma (sequential colours), its significant deviation (|h| > k sigma; grey
// elsewhere) and, with a comparison, the change in height since the earlier
// survey on the comparison's model, and the photomosaic's per-vertex colour
// on the mosaic's model. The mesh is rasterised back to front into an image at
// the target's resolution (a PDF would not want 10^5 vector triangles); the
// frame, labels, scale bar and colour bar are drawn as vectors.
#include <QFontMetricsF>
#include <QPainterPath>
#include <QPolygonF>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/deviation_colours.h"
#include "geometry/convex_hull_2d.h"
#include "geometry/mesh_index.h"
#include "mapping/vertex_significance.h"
#include "ui/report/figure_geometry.h"
#include "ui/report/figures.h"
#include "ui/report/plot_painter.h"

namespace hull::report {
namespace {

constexpr double kMargin = 10;
constexpr double kPanelWidth = kFigureWidth - 2 * kMargin;
constexpr int kMaxRasterWidth = 2400;  // px: about 360 dpi over an A4 text width

struct Label {
  Eigen::Vector2d at;
  QString text;
};

struct Dot {
  Eigen::Vector2d at;
  double value = 0;
};

// A panel: a window of the view's plane drawn at equal scale in a rectangle.
struct Panel {
  QRectF rect;
  Eigen::AlignedBox2d window;
  std::vector<ProjectedTriangle> triangles;
  std::vector<Dot> dots;
  std::vector<Label> labels;

  QPointF ToRect(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d s = window.sizes();
    return {rect.left() + (p.x() - window.min().x()) / s.x() * rect.width(),
            rect.bottom() - (p.y() - window.min().y()) / s.y() * rect.height()};
  }
};

// Grows `box` about its centre to the aspect (width / height) of a rectangle.
Eigen::AlignedBox2d FitAspect(const Eigen::AlignedBox2d& box, double aspect) {
  Eigen::Vector2d c = box.center(), s = box.sizes();
  if (s.x() / s.y() < aspect) {
    s.x() = s.y() * aspect;
  } else {
    s.y() = s.x() / aspect;
  }
  return {c - s / 2, c + s / 2};
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * (v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// Per face of a photomosaic (mosaic.ply read by LoadMesh: the vertex scalars
// red, green and blue, 0-255), the mean of its corners' colours.
std::vector<QRgb> MosaicFaceColours(const TriangleMesh& mesh) {
  const std::vector<double>* rgb[3] = {mesh.FindScalar("red"), mesh.FindScalar("green"), mesh.FindScalar("blue")};
  if (!rgb[0] || !rgb[1] || !rgb[2]) throw std::invalid_argument("report: the mosaic has no red, green and blue");
  std::vector<QRgb> out;
  out.reserve(mesh.faces.size());
  for (const Face& f : mesh.faces) {
    int c[3];
    for (int k = 0; k < 3; ++k) {
      const double mean = ((*rgb[k])[f[0]] + (*rgb[k])[f[1]] + (*rgb[k])[f[2]]) / 3;
      c[k] = std::clamp(static_cast<int>(std::lround(mean)), 0, 255);
    }
    out.push_back(qRgb(c[0], c[1], c[2]));
  }
  return out;
}

class HeatmapFigure final : public Figure {
 public:
  HeatmapFigure(const FigureRef& ref, const ReportInputs& in, const ReportOptions& options) : Figure(ref) {
    const HullFrame hull = ReportHullFrame(in);
    view_ = MakeViewBasis(hull, ref.view);
    kind_ = ref.kind;
    mapped_ = static_cast<bool>(in.mapping);
    if (kind_ != FigureKind::kHeatmap && !mapped_) throw std::invalid_argument("report: this heatmap needs mapping");
    if (kind_ == FigureKind::kChangeHeatmap && !in.comparison) {
      throw std::invalid_argument("report: the change heatmap needs a comparison");
    }
    if (kind_ == FigureKind::kMosaic && !in.mosaic)
      throw std::invalid_argument("report: the mosaic figure needs a mosaic");
    const TriangleMesh& mesh = kind_ == FigureKind::kChangeHeatmap ? in.comparison->comparison.model
                               : kind_ == FigureKind::kMosaic      ? *in.mosaic
                               : mapped_                           ? in.mapping->model
                                                                   : *in.cad;
    if (kind_ == FigureKind::kMosaic) face_colours_ = MosaicFaceColours(mesh);
    const std::vector<double>* dev = mapped_ ? mesh.FindScalar("deviation") : nullptr;
    const std::vector<double>* fusions = mapped_ ? mesh.FindScalar("fusions") : nullptr;
    // What the colours show, and which faces have a value (the others grey).
    const std::vector<double>* values = dev;
    const std::vector<double>* mask = nullptr;
    if (kind_ == FigureKind::kSigmaHeatmap) {
      values = mesh.FindScalar("sigma");
      if (!values) throw std::invalid_argument("report: the fused model has no per-vertex sigma");
      for (const double v : *values) mask_.push_back(std::isfinite(v) ? 1.0 : 0.0);
      mask = &mask_;
    } else if (kind_ == FigureKind::kSignificanceHeatmap) {
      values_ = SignificantDeviation(mesh, options.significance_k);
      for (const double v : values_) mask_.push_back(std::isnan(v) ? 0.0 : 1.0);
      values = &values_;
      mask = &mask_;
    } else if (kind_ == FigureKind::kChangeHeatmap) {
      values = mesh.FindScalar("change");
      if (!values) throw std::invalid_argument("report: the comparison's model has no change");
    }

    // What this view shows of the survey: the adjusted landmarks on this side
    // of the hull (their CAD face turned toward the viewer) place the detail
    // window and outline the footprint; without mapping they are drawn too.
    std::vector<Eigen::Vector2d> seen;
    std::vector<double> magnitudes;
    {
      TriangleMesh cad = *in.cad;
      if (cad.face_normals.size() != cad.faces.size()) cad.ComputeNormals();
      const MeshIndex index(cad);
      for (const PlacedLandmark& l : LandmarksInModel(in.pipeline->adjustment)) {
        const ClosestPoint c = index.Closest(l.p_m);
        if (c.face < 0 || cad.face_normals[c.face].dot(view_.toward_viewer) < 0.3) continue;
        seen.push_back(view_.Project(l.p_m));
        if (!mapped_) {
          magnitudes.push_back(std::abs(l.deviation));
          dots_.push_back({seen.back(), l.deviation});
        }
      }
    }
    footprint_ = ConvexHull(seen);
    if (kind_ == FigureKind::kChangeHeatmap || kind_ == FigureKind::kSigmaHeatmap) {
      magnitudes.clear();
      for (const double v : *values) {
        if (std::isfinite(v)) magnitudes.push_back(std::abs(v));
      }
    } else if (mapped_ && dev) {
      for (std::size_t i = 0; i < dev->size(); ++i) {
        if (!fusions || (*fusions)[i] > 0) magnitudes.push_back(std::abs((*dev)[i]));
      }
    }
    if (kind_ == FigureKind::kSigmaHeatmap) {
      // 0 to the 99th percentile of sigma, rounded up to a millimetre.
      range_ = std::max(0.001, std::ceil(Percentile(magnitudes, 0.99) * 1000.0) / 1000.0);
    } else if (kind_ == FigureKind::kChangeHeatmap) {
      range_ = DeviationColourRange(std::move(magnitudes));
    } else {
      range_ = options.deviation_range > 0 ? options.deviation_range : DeviationColourRange(std::move(magnitudes));
    }
    significance_k_ = options.significance_k;

    // Overview: the whole hull.
    overview_.window = ProjectedBounds(mesh, view_);
    overview_.window.extend(overview_.window.min() - Eigen::Vector2d(0.5, 0.5));
    overview_.window.extend(overview_.window.max() + Eigen::Vector2d(0.5, 0.5));
    const Eigen::Vector2d ov = overview_.window.sizes();
    const double ov_height = std::clamp(kPanelWidth * ov.y() / ov.x(), 60.0, 240.0);
    overview_.rect = QRectF(kMargin, 30, kPanelWidth, ov_height);
    overview_.window = FitAspect(overview_.window, kPanelWidth / ov_height);
    overview_.triangles = ProjectMesh(mesh, view_, values, mask);

    // Detail: the surveyed stretch.
    Eigen::AlignedBox2d detail;
    if (seen.size() >= 3) {
      std::vector<double> xs, ys;
      for (const Eigen::Vector2d& s : seen) {
        xs.push_back(s.x());
        ys.push_back(s.y());
      }
      detail = Eigen::AlignedBox2d(Eigen::Vector2d(Percentile(xs, 0.005), Percentile(ys, 0.005)),
                                   Eigen::Vector2d(Percentile(xs, 0.995), Percentile(ys, 0.995)));
      detail.extend(detail.min() - Eigen::Vector2d(0.6, 0.6));
      detail.extend(detail.max() + Eigen::Vector2d(0.6, 0.6));
    } else {
      detail = overview_.window;
    }
    const Eigen::Vector2d ds = detail.sizes();
    const double detail_height = std::clamp(kPanelWidth * ds.y() / ds.x(), 220.0, 560.0);
    detail_.rect = QRectF(kMargin, overview_.rect.bottom() + 44, kPanelWidth, detail_height);
    detail_.window = FitAspect(detail, kPanelWidth / detail_height);
    detail_.triangles = ProjectMesh(mesh, view_, values, mask, detail_.window);
    detail_.dots = dots_;

    if (mapped_ && kind_ != FigureKind::kChangeHeatmap) {
      // Objects on this side, the largest first, at most 30 labelled.
      std::vector<const DetectedObject*> objects;
      for (const DetectedObject& o : in.mapping->objects) {
        if (o.normal_m.dot(view_.toward_viewer) < 0.3) continue;
        if (!detail_.window.contains(view_.Project(o.centroid_m))) continue;
        objects.push_back(&o);
      }
      std::sort(objects.begin(), objects.end(),
                [](const DetectedObject* a, const DetectedObject* b) { return a->area > b->area; });
      if (objects.size() > 30) objects.resize(30);
      for (const DetectedObject* o : objects) {
        detail_.labels.push_back({view_.Project(o->centroid_m), QString::fromStdString(o->id)});
      }
    }
    height_ = detail_.rect.bottom() + 62;
  }

  double Height() const override { return height_; }

  void Paint(QPainter& p) const override {
    DrawTitle(p, overview_.rect, QStringLiteral("Whole hull"));
    PaintMesh(p, overview_);
    // The detail's window on the overview.
    p.save();
    p.setClipRect(overview_.rect);
    p.setPen(QPen(QColor(0xd0, 0x20, 0x80), 1.6));
    p.setBrush(Qt::NoBrush);
    p.drawRect(QRectF(overview_.ToRect({detail_.window.min().x(), detail_.window.max().y()}),
                      overview_.ToRect({detail_.window.max().x(), detail_.window.min().y()})));
    p.restore();
    PaintFootprint(p, overview_);
    DrawDirections(p, overview_.rect);

    DrawTitle(p, detail_.rect, DetailTitle());
    PaintMesh(p, detail_);
    PaintFootprint(p, detail_);
    PaintDots(p, detail_);
    PaintLabels(p, detail_);
    DrawScaleBar(p, detail_);
    DrawDirections(p, detail_.rect);

    const QRectF bar(kFigureWidth - kMargin - 300, detail_.rect.bottom() + 16, 300, 12);
    switch (kind_) {
      case FigureKind::kSigmaHeatmap:
        DrawSequentialColourBar(p, bar, range_ * 1000.0, QStringLiteral("σ of the deviation (mm)"));
        break;
      case FigureKind::kChangeHeatmap:
        DrawColourBar(p, bar, range_, QStringLiteral("change in height since survey A (m)"));
        break;
      case FigureKind::kMosaic:
        p.save();
        p.setFont(FigureFont(10));
        p.setPen(QColor(0x30, 0x30, 0x30));
        p.drawText(bar.adjusted(-100, -4, 0, 8), Qt::AlignRight | Qt::AlignVCenter,
                   QStringLiteral("colour: estimated albedo (the mosaic's mosaic.ply)"));
        p.restore();
        break;
      case FigureKind::kSignificanceHeatmap:
        DrawColourBar(p, bar, range_, QStringLiteral("deviation (m)"));
        DrawLegendRow(
            p, QRectF(kMargin + 200, bar.top() - 2, 190, 16),
            {{QColor(0xb4, 0xb4, 0xb4), QStringLiteral("not significant: |h| ≤ %1 σ").arg(significance_k_, 0, 'g', 3),
              LegendEntry::Mark::kBox}});
        break;
      default:
        DrawColourBar(p, bar, range_, QStringLiteral("deviation from the CAD surface (m)"));
        break;
    }
    if (footprint_.size() >= 3) {
      DrawLegendRow(
          p, QRectF(kMargin, bar.top() - 2, 200, 16),
          {{QColor(0x20, 0x20, 0x20), QStringLiteral("footprint of the features"), LegendEntry::Mark::kDash}});
    }
  }

 private:
  QString DetailTitle() const {
    switch (kind_) {
      case FigureKind::kSigmaHeatmap:
        return QStringLiteral("Surveyed stretch: σ of the fused model's deviation");
      case FigureKind::kSignificanceHeatmap:
        return QStringLiteral("Surveyed stretch: significant deviation (|h| > %1 σ)").arg(significance_k_, 0, 'g', 3);
      case FigureKind::kChangeHeatmap:
        return QStringLiteral("Surveyed stretch: change in height, survey B minus survey A");
      case FigureKind::kMosaic:
        return QStringLiteral("Surveyed stretch: photomosaic");
      default:
        return mapped_ ? QStringLiteral("Surveyed stretch: fused model")
                       : QStringLiteral("Surveyed stretch: landmarks over the CAD model");
    }
  }

  // Rasterises the panel's triangles at the device resolution of its rectangle.
  void PaintMesh(QPainter& p, const Panel& panel) const {
    const QRectF device = p.transform().mapRect(panel.rect);
    const double scale = std::min(1.0, kMaxRasterWidth / std::max(1.0, device.width()));
    const int w = std::max(8, static_cast<int>(std::lround(device.width() * scale)));
    const int h = std::max(8, static_cast<int>(std::lround(device.height() * scale)));
    QImage image(w, h, QImage::Format_ARGB32_Premultiplied);
    image.fill(QColor(0xfb, 0xfb, 0xfd));
    {
      QPainter r(&image);
      r.setRenderHint(QPainter::Antialiasing, true);
      const Eigen::Vector2d lo = panel.window.min(), size = panel.window.sizes();
      const double sx = w / size.x(), sy = h / size.y();
      QPolygonF poly(3);
      for (const ProjectedTriangle& t : panel.triangles) {
        for (int k = 0; k < 3; ++k) {
          poly[k] = QPointF((t.corner[k].x() - lo.x()) * sx, h - (t.corner[k].y() - lo.y()) * sy);
        }
        const double shade = 0.62 + 0.38 * std::abs(t.facing);
        const QColor base = kind_ == FigureKind::kMosaic         ? QColor(face_colours_[t.face])
                            : !t.valued                          ? QColor(0xb4, 0xb4, 0xb4)
                            : kind_ == FigureKind::kSigmaHeatmap ? SequentialColour(t.value / range_)
                                                                 : DivergingColour(t.value / range_);
        const QColor c = QColor::fromRgbF(base.redF() * shade, base.greenF() * shade, base.blueF() * shade);
        // The pen closes the hairline seams antialiasing leaves between faces.
        r.setPen(QPen(c, 0.9));
        r.setBrush(c);
        r.drawPolygon(poly);
      }
    }
    p.save();
    p.drawImage(panel.rect, image);
    p.setPen(QPen(QColor(0x40, 0x40, 0x40), 1.0));
    p.setBrush(Qt::NoBrush);
    p.drawRect(panel.rect);
    p.restore();
  }

  void PaintFootprint(QPainter& p, const Panel& panel) const {
    if (footprint_.size() < 3) return;
    QPolygonF poly;
    for (const Eigen::Vector2d& v : footprint_) poly << panel.ToRect(v);
    p.save();
    p.setClipRect(panel.rect);
    QPen pen(QColor(0x20, 0x20, 0x20), 1.2, Qt::DashLine);
    pen.setCosmetic(false);
    p.setPen(pen);
    p.setBrush(Qt::NoBrush);
    p.drawPolygon(poly);
    p.restore();
  }

  void PaintDots(QPainter& p, const Panel& panel) const {
    if (panel.dots.empty()) return;
    p.save();
    p.setClipRect(panel.rect);
    std::vector<const Dot*> order;
    for (const Dot& d : panel.dots) order.push_back(&d);
    // Larger deviations on top, so foreign structure is not buried.
    std::sort(order.begin(), order.end(),
              [](const Dot* a, const Dot* b) { return std::abs(a->value) < std::abs(b->value); });
    for (const Dot* d : order) {
      p.setPen(QPen(QColor(0x30, 0x30, 0x30), 0.4));
      p.setBrush(DivergingColour(d->value / range_));
      p.drawEllipse(panel.ToRect(d->at), 2.6, 2.6);
    }
    p.restore();
  }

  void PaintLabels(QPainter& p, const Panel& panel) const {
    p.save();
    p.setClipRect(panel.rect);
    p.setFont(FigureFont(10, true));
    const QFontMetricsF fm(p.font());
    std::vector<Eigen::Vector2d> anchors, sizes;
    for (const Label& l : panel.labels) {
      const QPointF at = panel.ToRect(l.at);
      anchors.emplace_back(at.x(), at.y());
      sizes.emplace_back(fm.horizontalAdvance(l.text) + 6, fm.height() + 2);
    }
    const Eigen::AlignedBox2d bounds(Eigen::Vector2d(panel.rect.left(), panel.rect.top()),
                                     Eigen::Vector2d(panel.rect.right(), panel.rect.bottom()));
    const std::vector<Eigen::AlignedBox2d> boxes = PlaceLabels(bounds, anchors, sizes);
    for (std::size_t i = 0; i < panel.labels.size(); ++i) {
      const Label& l = panel.labels[i];
      const QPointF at = panel.ToRect(l.at);
      const QRectF box(QPointF(boxes[i].min().x(), boxes[i].min().y()),
                       QPointF(boxes[i].max().x(), boxes[i].max().y()));
      p.setPen(QPen(QColor(0x20, 0x20, 0x20), 0.8));
      p.drawLine(at, QPointF(box.center().x() < at.x() ? box.right() : box.left(), box.center().y()));
      p.setBrush(QColor(255, 255, 255, 215));
      p.drawRect(box);
      p.drawText(box, Qt::AlignCenter, l.text);
      p.setBrush(QColor(0x20, 0x20, 0x20));
      p.drawEllipse(at, 1.6, 1.6);
    }
    p.restore();
  }

  void DrawScaleBar(QPainter& p, const Panel& panel) const {
    const double units_per_m = panel.rect.width() / panel.window.sizes().x();
    double metres = 1;
    for (double m : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0}) {
      if (m * units_per_m <= 160) metres = m;
    }
    const double len = metres * units_per_m;
    const QPointF a(panel.rect.left() + 14, panel.rect.bottom() - 14);
    p.save();
    p.setPen(QPen(Qt::black, 2.2));
    p.drawLine(a, a + QPointF(len, 0));
    p.drawLine(a + QPointF(0, -4), a + QPointF(0, 4));
    p.drawLine(a + QPointF(len, -4), a + QPointF(len, 4));
    p.setFont(FigureFont(10.5, true));
    p.drawText(QRectF(a.x(), a.y() - 20, len, 16), Qt::AlignCenter, QStringLiteral("%1 m").arg(metres));
    p.restore();
  }

  void DrawDirections(QPainter& p, const QRectF& rect) const {
    QString text;
    switch (ref().view) {
      case HullView::kBottom:
        text = QStringLiteral("seen from below · bow → · starboard ↑");
        break;
      case HullView::kPort:
        text = QStringLiteral("seen from port · ← bow · up ↑");
        break;
      case HullView::kStarboard:
        text = QStringLiteral("seen from starboard · bow → · up ↑");
        break;
    }
    p.save();
    p.setFont(FigureFont(10));
    p.setPen(QColor(0x30, 0x30, 0x30));
    p.drawText(QRectF(rect.left(), rect.top() - 18, rect.width(), 16), Qt::AlignRight | Qt::AlignBottom, text);
    p.restore();
  }

  ViewBasis view_;
  FigureKind kind_ = FigureKind::kHeatmap;
  std::vector<double> values_, mask_;  // significance: the masked deviation and its mask
  std::vector<QRgb> face_colours_;     // mosaic: per face, the mean of its corners' colours
  double significance_k_ = 1.96;
  bool mapped_ = false;
  double range_ = 0.1;
  Panel overview_, detail_;
  std::vector<Dot> dots_;
  std::vector<Eigen::Vector2d> footprint_;  // convex hull of the landmarks on this side
  double height_ = 400;
};

}  // namespace

std::unique_ptr<Figure> MakeHeatmapFigure(const FigureRef& ref, const ReportInputs& inputs,
                                          const ReportOptions& options) {
  return std::make_unique<HeatmapFigure>(ref, inputs, options);
}

}  // namespace hull::report
