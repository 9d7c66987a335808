// The cross-section profiles side by side (one panel per surface model, the
// columns of the paper's Figs. 14 and 15): the CAD mesh's section as a grey
// line, the DVL returns in blue and the features in the slab coloured by
// their label (green on the hull, red foreign). All panels share one view:
// the wheel zooms about the cursor, Ctrl+wheel stretches the vertical axis
// (an exaggeration shown in the corner), dragging pans, a double click fits
// the data again. Drawn with QPainter.
#pragma once

#include <QPointF>
#include <QString>
#include <QWidget>
#include <vector>

#include "ui/models/cross_section.h"

namespace hull::ui {

struct ProfilePanel {
  QString title;
  bool present = false;  // false: the model was not run (missing_text says how)
  QString missing_text;
  ModelProfile profile;
};

class ProfileCanvas : public QWidget {
  Q_OBJECT

 public:
  explicit ProfileCanvas(QWidget* parent = nullptr);

  // The CAD section (shared by the panels) and the panels; keep_view keeps
  // the zoom and pan (the slab moved), otherwise the view fits the data.
  void SetContents(std::vector<ProfileSegment> cad, std::vector<ProfilePanel> panels, bool keep_view);
  void FitView();

  const std::vector<ProfilePanel>& panels() const { return panels_; }
  std::size_t cadSegments() const { return cad_.size(); }
  double scale() const { return scale_; }  // pixels per metre (horizontal)
  double exaggeration() const { return exaggeration_; }
  void SetExaggeration(double factor);
  // Zooms by `factor` about a widget position (as the wheel does).
  void ZoomAt(const QPointF& position, double factor);

  QSize sizeHint() const override { return {900, 320}; }

 protected:
  void paintEvent(QPaintEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;

 private:
  QRectF PanelRect(int index) const;
  // Plane (u, v) to widget coordinates in a panel, and back.
  QPointF ToWidget(const QRectF& panel, const Eigen::Vector2d& uv) const;
  Eigen::Vector2d ToPlane(const QRectF& panel, const QPointF& at) const;
  int PanelAt(const QPointF& at) const;
  void DrawPanel(QPainter& p, int index) const;
  void DrawLegend(QPainter& p) const;

  std::vector<ProfileSegment> cad_;
  std::vector<ProfilePanel> panels_;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();  // plane point at each panel's centre
  double scale_ = 100.0;                              // px per metre
  double exaggeration_ = 1.0;                         // vertical scale / horizontal scale
  bool dragging_ = false;
  QPointF last_mouse_;
};

}  // namespace hull::ui
