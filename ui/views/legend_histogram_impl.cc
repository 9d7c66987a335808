#include "ui/views/legend_histogram_impl.h"

#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty2D.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <QString>
#include <cmath>

#include "ui/views/scene_layers_impl.h"

namespace hull::ui {

namespace {

constexpr int kGap = 4;      // between the histogram and the colour bar
constexpr int kLength = 64;  // pixels of the longest bar

void AddQuad(vtkPoints* points, vtkCellArray* cells, double x0, double y0, double x1, double y1) {
  const vtkIdType first = points->GetNumberOfPoints();
  points->InsertNextPoint(x0, y0, 0.0);
  points->InsertNextPoint(x1, y0, 0.0);
  points->InsertNextPoint(x1, y1, 0.0);
  points->InsertNextPoint(x0, y1, 0.0);
  const vtkIdType ids[4] = {first, first + 1, first + 2, first + 3};
  cells->InsertNextCell(4, ids);
}

}  // namespace

LegendHistogram::LegendHistogram(vtkRenderer* renderer) {
  bars_ = vtkSmartPointer<vtkPolyData>::New();
  panel_ = vtkSmartPointer<vtkPolyData>::New();
  bars_actor_ = OverlayActor2D(bars_);
  panel_actor_ = OverlayActor2D(panel_);
  panel_actor_->GetProperty()->SetColor(kOverlayPanel[0], kOverlayPanel[1], kOverlayPanel[2]);
  panel_actor_->GetProperty()->SetOpacity(kOverlayPanelOpacity);
  text_ = vtkSmartPointer<vtkTextActor>::New();
  StyleOverlayText(text_->GetTextProperty(), 12);
  text_->GetTextProperty()->SetJustificationToRight();
  text_->GetTextProperty()->SetVerticalJustificationToTop();
  text_->PickableOff();
  renderer->AddViewProp(panel_actor_);
  renderer->AddViewProp(bars_actor_);
  renderer->AddViewProp(text_);
  SetVisible(false);
}

void LegendHistogram::Set(const DeviationHistogram& histogram, vtkLookupTable* lut) {
  histogram_ = histogram;
  lut_ = lut;
  Rebuild();
}

void LegendHistogram::SetVisible(bool visible) {
  visible_ = visible;
  const bool shown = this->visible() && bar_[3] > 0;
  panel_actor_->SetVisibility(shown);
  bars_actor_->SetVisibility(shown);
  text_->SetVisibility(shown);
}

bool LegendHistogram::visible() const { return visible_ && histogram_.total > 0 && !histogram_.counts.empty(); }

bool LegendHistogram::Place(const std::array<int, 4>& bar) {
  if (bar == bar_) return false;
  bar_ = bar;
  Rebuild();
  return visible_;
}

void LegendHistogram::Rebuild() {
  SetVisible(visible_);
  const int n = static_cast<int>(histogram_.counts.size());
  if (n == 0 || bar_[3] <= 0 || !lut_) return;
  const double right = bar_[0] - kGap, bottom = bar_[1], height = bar_[3];
  vtkNew<vtkPoints> panel_points;
  vtkNew<vtkCellArray> panel_cells;
  AddQuad(panel_points, panel_cells, right - kLength - 4, bottom - 2, right + 1, bottom + height + 2);
  panel_->SetPoints(panel_points);
  panel_->SetPolys(panel_cells);

  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  const double scale = std::log1p(std::max(1, histogram_.max_count()));
  for (int i = 0; i < n; ++i) {
    const int count = histogram_.counts[static_cast<std::size_t>(i)];
    if (count == 0) continue;
    const double length = std::max(1.0, kLength * std::log1p(count) / scale);
    AddQuad(points, cells, right - length, bottom + height * i / n, right, bottom + height * (i + 1) / n);
    const double centre = histogram_.lo + (i + 0.5) * (histogram_.hi - histogram_.lo) / n;
    const unsigned char* rgba = lut_->MapValue(centre);
    colours->InsertNextTypedTuple(rgba);
  }
  bars_->SetPoints(points);
  bars_->SetPolys(cells);
  bars_->GetCellData()->SetScalars(colours);
  bars_->Modified();
  panel_->Modified();

  QString text = QStringLiteral("%1 vertices (log)").arg(histogram_.total);
  if (histogram_.above > 0) text += QStringLiteral("\n%1 above the range (yellow)").arg(histogram_.above);
  if (histogram_.below > 0) text += QStringLiteral("\n%1 below the range (cyan)").arg(histogram_.below);
  if (histogram_.tolerance > 0) {
    text += QStringLiteral("\n%1 % within +-%2 (green)")
                .arg(100.0 * histogram_.WithinFraction(), 0, 'f', 1)
                .arg(histogram_.tolerance, 0, 'f', 3);
  }
  text_->SetInput(text.toUtf8().constData());
  text_->SetPosition(right + 1, bottom - 6);  // under the histogram
}

}  // namespace hull::ui
