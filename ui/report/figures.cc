#include "ui/report/figures.h"

#include <cmath>
#include <stdexcept>

namespace hull::report {

std::unique_ptr<Figure> MakeFigure(const FigureRef& ref, const ReportInputs& inputs, const ReportOptions& options) {
  CheckInputs(inputs);
  switch (ref.kind) {
    case FigureKind::kHeatmap:
    case FigureKind::kSigmaHeatmap:
    case FigureKind::kSignificanceHeatmap:
    case FigureKind::kChangeHeatmap:
    case FigureKind::kMosaic:
      return MakeHeatmapFigure(ref, inputs, options);
    case FigureKind::kCrossSection:
      return MakeCrossSectionFigure(ref, inputs, options);
    case FigureKind::kConvergence:
    case FigureKind::kDvlResiduals:
    case FigureKind::kModelTiming:
      return MakeSolverFigure(ref, inputs);
    case FigureKind::kSonarPlan:
    case FigureKind::kSonarErrors:
      return MakeSonarFigure(ref, inputs);
  }
  throw std::invalid_argument("report: unknown figure kind");
}

void PaintFigure(const Figure& figure, QPainter& painter, const QRectF& target) {
  const double h = figure.Height();
  const double s = std::min(target.width() / kFigureWidth, target.height() / h);
  const QRectF canvas(0, 0, kFigureWidth, h);
  painter.save();
  painter.translate(target.left() + (target.width() - s * kFigureWidth) / 2,
                    target.top() + (target.height() - s * h) / 2);
  painter.scale(s, s);
  painter.setClipRect(canvas);
  painter.fillRect(canvas, Qt::white);
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  painter.setRenderHint(QPainter::SmoothPixmapTransform, true);
  figure.Paint(painter);
  painter.restore();
}

int FigureHeightPx(const Figure& figure, int width_px) {
  return std::max(1, static_cast<int>(std::lround(width_px * figure.Height() / kFigureWidth)));
}

QImage RenderFigure(const Figure& figure, int width_px) {
  width_px = std::max(16, width_px);
  QImage image(width_px, FigureHeightPx(figure, width_px), QImage::Format_ARGB32);
  image.fill(Qt::white);
  QPainter p(&image);
  PaintFigure(figure, p, QRectF(0, 0, image.width(), image.height()));
  p.end();
  return image;
}

}  // namespace hull::report
