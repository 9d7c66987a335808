#include "ui/views/profile_canvas.h"

#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

namespace hull::ui {

namespace {

const QColor kCadColour(110, 110, 110);
const QColor kDvlColour(40, 90, 230);
const QColor kOnHull(30, 170, 60);
const QColor kForeign(220, 40, 40);
constexpr int kTitleHeight = 22;
constexpr int kLegendHeight = 24;
constexpr int kGap = 8;

}  // namespace

ProfileCanvas::ProfileCanvas(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("profileCanvas"));
  setMouseTracking(false);
  setMinimumSize(360, 200);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  setFocusPolicy(Qt::StrongFocus);
}

void ProfileCanvas::SetContents(std::vector<ProfileSegment> cad, std::vector<ProfilePanel> panels, bool keep_view) {
  cad_ = std::move(cad);
  panels_ = std::move(panels);
  if (!keep_view) FitView();
  update();
}

void ProfileCanvas::FitView() {
  Eigen::AlignedBox2d box;
  for (const ProfilePanel& panel : panels_) {
    for (const ProfilePoint& q : panel.profile.features) box.extend(q.uv);
    for (const ProfilePoint& q : panel.profile.dvl) box.extend(q.uv);
  }
  if (box.isEmpty()) {
    for (const ProfileSegment& s : cad_) {
      box.extend(s.a);
      box.extend(s.b);
    }
  }
  exaggeration_ = 1.0;
  if (box.isEmpty()) {
    centre_.setZero();
    scale_ = 100.0;
    update();
    return;
  }
  centre_ = box.center();
  const QRectF r = PanelRect(0);
  const Eigen::Vector2d size = box.sizes().cwiseMax(Eigen::Vector2d(0.05, 0.05)) * 1.15;
  scale_ = std::min(r.width() / size.x(), r.height() / size.y());
  update();
}

void ProfileCanvas::SetExaggeration(double factor) {
  exaggeration_ = std::clamp(factor, 1.0, 50.0);
  update();
}

QRectF ProfileCanvas::PanelRect(int index) const {
  const int n = std::max<int>(1, static_cast<int>(panels_.size()));
  const double w = (width() - kGap * (n + 1)) / static_cast<double>(n);
  const double top = kTitleHeight + 4;
  return QRectF(kGap + index * (w + kGap), top, std::max(10.0, w), std::max(10.0, height() - top - kLegendHeight - 6));
}

QPointF ProfileCanvas::ToWidget(const QRectF& panel, const Eigen::Vector2d& uv) const {
  return {panel.center().x() + (uv.x() - centre_.x()) * scale_,
          panel.center().y() - (uv.y() - centre_.y()) * scale_ * exaggeration_};
}

Eigen::Vector2d ProfileCanvas::ToPlane(const QRectF& panel, const QPointF& at) const {
  return {centre_.x() + (at.x() - panel.center().x()) / scale_,
          centre_.y() - (at.y() - panel.center().y()) / (scale_ * exaggeration_)};
}

int ProfileCanvas::PanelAt(const QPointF& at) const {
  for (int i = 0; i < static_cast<int>(panels_.size()); ++i) {
    if (PanelRect(i).contains(at)) return i;
  }
  return 0;
}

void ProfileCanvas::ZoomAt(const QPointF& position, double factor) {
  const QRectF panel = PanelRect(PanelAt(position));
  const Eigen::Vector2d before = ToPlane(panel, position);
  scale_ = std::clamp(scale_ * factor, 1.0, 1e5);
  const Eigen::Vector2d after = ToPlane(panel, position);
  centre_ += before - after;  // the point under the cursor stays put
  update();
}

void ProfileCanvas::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  if (steps == 0) return;
  const double factor = std::pow(1.2, steps);
  if (event->modifiers() & Qt::ControlModifier) {
    SetExaggeration(exaggeration_ * factor);
  } else {
    ZoomAt(event->position(), factor);
  }
  event->accept();
}

void ProfileCanvas::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  dragging_ = true;
  last_mouse_ = event->localPos();
  setCursor(Qt::ClosedHandCursor);
}

void ProfileCanvas::mouseMoveEvent(QMouseEvent* event) {
  if (!dragging_) return;
  const QPointF d = event->localPos() - last_mouse_;
  last_mouse_ = event->localPos();
  centre_.x() -= d.x() / scale_;
  centre_.y() += d.y() / (scale_ * exaggeration_);
  update();
}

void ProfileCanvas::mouseReleaseEvent(QMouseEvent*) {
  dragging_ = false;
  unsetCursor();
}

void ProfileCanvas::mouseDoubleClickEvent(QMouseEvent*) { FitView(); }

void ProfileCanvas::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), palette().window());
  if (panels_.empty()) {
    p.setPen(palette().color(QPalette::PlaceholderText));
    p.drawText(rect(), Qt::AlignCenter, QStringLiteral("Run the inspection (F5) to see cross-sections"));
    return;
  }
  for (int i = 0; i < static_cast<int>(panels_.size()); ++i) DrawPanel(p, i);
  DrawLegend(p);
}

void ProfileCanvas::DrawPanel(QPainter& p, int index) const {
  const ProfilePanel& panel = panels_[index];
  const QRectF r = PanelRect(index);
  const QFontMetrics fm(font());
  QFont bold = font();
  bold.setBold(true);
  p.setFont(bold);
  p.setPen(palette().color(QPalette::WindowText));
  p.drawText(QRectF(r.left(), 2, r.width(), kTitleHeight), Qt::AlignCenter, panel.title);
  p.setFont(font());
  p.fillRect(r, palette().base());
  p.setPen(palette().color(QPalette::Mid));
  p.drawRect(r);
  p.save();
  p.setClipRect(r);
  p.setPen(QPen(kCadColour, 2.0));
  for (const ProfileSegment& s : cad_) p.drawLine(ToWidget(r, s.a), ToWidget(r, s.b));
  if (!panel.present) {
    p.setPen(palette().color(QPalette::PlaceholderText));
    p.drawText(r.adjusted(8, 8, -8, -8), Qt::AlignCenter | Qt::TextWordWrap, panel.missing_text);
    p.restore();
    return;
  }
  p.setPen(Qt::NoPen);
  p.setBrush(kDvlColour);
  for (const ProfilePoint& q : panel.profile.dvl) p.drawEllipse(ToWidget(r, q.uv), 2.2, 2.2);
  for (const ProfilePoint& q : panel.profile.features) {
    p.setBrush(q.label == 1 ? kOnHull : kForeign);
    p.drawEllipse(ToWidget(r, q.uv), 2.8, 2.8);
  }
  p.setBrush(Qt::NoBrush);
  // A scale bar of a round length about a fifth of the panel wide.
  const double target = r.width() / 5.0 / scale_;
  const double mag = std::pow(10.0, std::floor(std::log10(target)));
  double length = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * mag <= target) length = m * mag;
  }
  const double px = length * scale_;
  const QPointF a(r.left() + 10, r.bottom() - 12), b(a.x() + px, a.y());
  p.setPen(QPen(palette().color(QPalette::Text), 2));
  p.drawLine(a, b);
  p.drawLine(a + QPointF(0, -4), a + QPointF(0, 4));
  p.drawLine(b + QPointF(0, -4), b + QPointF(0, 4));
  const QString text = length >= 1 ? QStringLiteral("%1 m").arg(length) : QStringLiteral("%1 cm").arg(length * 100);
  p.drawText(QRectF(a.x(), a.y() - fm.height() - 4, px + 80, fm.height()), Qt::AlignLeft, text);
  QString corner =
      QStringLiteral("%1 features, %2 DVL").arg(panel.profile.features.size()).arg(panel.profile.dvl.size());
  if (exaggeration_ > 1.0001) corner += QStringLiteral(" · vertical ×%1").arg(exaggeration_, 0, 'f', 1);
  p.drawText(r.adjusted(6, 4, -6, -4), Qt::AlignRight | Qt::AlignTop, corner);
  p.restore();
}

void ProfileCanvas::DrawLegend(QPainter& p) const {
  const QFontMetrics fm(font());
  struct Item {
    QColor colour;
    QString text;
    bool line;
  };
  const Item items[] = {{kCadColour, QStringLiteral("CAD section"), true},
                        {kDvlColour, QStringLiteral("DVL returns"), false},
                        {kOnHull, QStringLiteral("features on the hull (λ = 1)"), false},
                        {kForeign, QStringLiteral("foreign (λ = 0)"), false}};
  double x = kGap + 4;
  const double y = height() - kLegendHeight / 2.0 - 2;
  for (const Item& item : items) {
    if (item.line) {
      p.setPen(QPen(item.colour, 2.0));
      p.drawLine(QPointF(x, y), QPointF(x + 18, y));
    } else {
      p.setPen(Qt::NoPen);
      p.setBrush(item.colour);
      p.drawEllipse(QPointF(x + 9, y), 3.5, 3.5);
      p.setBrush(Qt::NoBrush);
    }
    p.setPen(palette().color(QPalette::WindowText));
    p.drawText(QPointF(x + 24, y + fm.ascent() / 2.0 - 1), item.text);
    x += 24 + fm.horizontalAdvance(item.text) + 18;
  }
  p.setPen(palette().color(QPalette::PlaceholderText));
  const QString hint = QStringLiteral("wheel: zoom · Ctrl+wheel: stretch vertically · drag: pan · double-click: fit");
  p.drawText(QRectF(x, y - fm.height() / 2.0, width() - x - kGap, fm.height()), Qt::AlignRight | Qt::AlignVCenter,
             hint);
}

}  // namespace hull::ui
