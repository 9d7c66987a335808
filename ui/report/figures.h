// The report's figures, drawn with QPainter: the same Paint() fills a PNG
// (RenderFigure, through a QImage; works with QT_QPA_PLATFORM=offscreen and
// no display) and a rectangle of a PDF page (PaintFigure). No VTK.
//
// A figure is laid out in figure units: kFigureWidth wide and Height() tall;
// painting scales it uniformly into the target, so text and lines keep
// their proportions at any size.
#pragma once

#include <QImage>
#include <QPainter>
#include <QRectF>
#include <memory>
#include <vector>

#include "ui/report/report_document.h"
#include "ui/report/report_inputs.h"

namespace hull::report {

inline constexpr double kFigureWidth = 800;

class Figure {
 public:
  explicit Figure(FigureRef ref) : ref_(std::move(ref)) {}
  virtual ~Figure() = default;
  Figure(const Figure&) = delete;
  Figure& operator=(const Figure&) = delete;

  const FigureRef& ref() const { return ref_; }
  // Height in figure units for a width of kFigureWidth.
  virtual double Height() const = 0;
  // Paints on a white kFigureWidth x Height() canvas at the painter's origin.
  virtual void Paint(QPainter& p) const = 0;

 private:
  FigureRef ref_;
};

// The figure a reference names (the inputs are copied from as needed; the
// figure does not keep references to them). Throws std::invalid_argument
// for inputs that fail CheckInputs().
std::unique_ptr<Figure> MakeFigure(const FigureRef& ref, const ReportInputs& inputs, const ReportOptions& options);

// Paints a figure into `target`, scaled uniformly and centred, on white.
void PaintFigure(const Figure& figure, QPainter& painter, const QRectF& target);

// The figure as an image width_px wide (its height follows the figure's
// aspect), ARGB32 on white.
QImage RenderFigure(const Figure& figure, int width_px);
// Its pixel height at width_px.
int FigureHeightPx(const Figure& figure, int width_px);

// Per kind (figures.cc dispatches to these).
std::unique_ptr<Figure> MakeHeatmapFigure(const FigureRef& ref, const ReportInputs& inputs,
                                          const ReportOptions& options);
std::unique_ptr<Figure> MakeCrossSectionFigure(const FigureRef& ref, const ReportInputs& inputs,
                                               const ReportOptions& options);
std::unique_ptr<Figure> MakeSolverFigure(const FigureRef& ref, const ReportInputs& inputs);
std::unique_ptr<Figure> MakeSonarFigure(const FigureRef& ref, const ReportInputs& inputs);  // sonar_figures.cc

}  // namespace hull::report
