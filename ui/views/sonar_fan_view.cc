#include "ui/views/sonar_fan_view.h"

#include <Eigen/Eigenvalues>
#include <QPainter>
#include <QPainterPath>
#include <QPolygonF>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "base/axis_ticks.h"

namespace hull::ui {

namespace {

constexpr double kMarginLeft = 36, kMarginTop = 40, kMarginRight = 52, kLegendRow = 18;
const QColor kBackground(34, 36, 42);
const QColor kGrid(150, 200, 230, 150);
const QColor kLabel(205, 225, 240);
const QColor kInState(255, 255, 255);
const QColor kWaitingPair(255, 190, 90);
const QColor kUnassociated(255, 70, 60);

// Echo intensity (0..255) to an amber sonar palette.
QRgb Palette(int v) {
  const int r = std::min(255, v * 5 / 4), g = std::min(255, v * 4 / 5), b = std::min(255, v / 2);
  return qRgb(r, g, b);
}

// A 2-sigma ellipse (times `scale`) of a (range, azimuth) covariance as a polygon in the fan.
QPolygonF Ellipse(const SonarFanGeometry& g, const Eigen::Vector2d& z, const Eigen::Matrix2d& c, double scale) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(0.5 * (c + c.transpose()));
  const Eigen::Vector2d sd = eig.eigenvalues().cwiseMax(0).cwiseSqrt();
  QPolygonF out;
  constexpr int kPoints = 48;
  for (int i = 0; i <= kPoints; ++i) {
    const double t = 2 * M_PI * i / kPoints;
    const Eigen::Vector2d q =
        z + 2.0 * scale *
                (sd[0] * std::cos(t) * eig.eigenvectors().col(0) + sd[1] * std::sin(t) * eig.eigenvectors().col(1));
    out << g.ToPixel(q[0], q[1]);
  }
  return out;
}

// The legend's entries, laid out in rows across `width`: per entry its row and x.
QStringList LegendTexts(double ellipse_scale) {
  return {ellipse_scale == 1 ? QStringLiteral("predicted feature, 2σ")
                             : QStringLiteral("predicted feature, 2σ ×%1").arg(ellipse_scale),
          QStringLiteral("tentative feature"),
          QStringLiteral("detection, associated"),
          QStringLiteral("… with a tentative feature"),
          QStringLiteral("unassociated: new feature"),
          QStringLiteral("association (feature's colour)")};
}

std::vector<QPointF> LegendLayout(const QStringList& texts, const QFontMetricsF& fm, double width) {
  std::vector<QPointF> out;
  double x = 8, row = 0;
  for (const QString& t : texts) {
    const double w = 22 + fm.horizontalAdvance(t) + 14;
    if (x + w > width - 4 && x > 8) {
      x = 8;
      ++row;
    }
    out.emplace_back(x, row);
    x += w;
  }
  return out;
}

void Plus(QPainter& p, const QPointF& c, double r) {
  p.drawLine(QPointF(c.x() - r, c.y()), QPointF(c.x() + r, c.y()));
  p.drawLine(QPointF(c.x(), c.y() - r), QPointF(c.x(), c.y() + r));
}

void Cross(QPainter& p, const QPointF& c, double r) {
  p.drawLine(QPointF(c.x() - r, c.y() - r), QPointF(c.x() + r, c.y() + r));
  p.drawLine(QPointF(c.x() - r, c.y() + r), QPointF(c.x() + r, c.y() - r));
}

}  // namespace

SonarFanView::SonarFanView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("sonarFanView"));
  setAutoFillBackground(false);
  setAttribute(Qt::WA_OpaquePaintEvent);
}

QColor SonarFanView::FeatureColour(std::int64_t id) {
  return QColor::fromHsv(static_cast<int>((id * 67) % 360 + 360) % 360, 170, 255);
}

void SonarFanView::SetRun(std::shared_ptr<const SonarRun> run) {
  run_ = std::move(run);
  step_ = run_ && run_->steps() > 0 ? run_->steps() - 1 : 0;
  image_step_ = -1;
  maps_r0_ = maps_r1_ = -1;
  UpdateWindow();
  update();
}

void SonarFanView::SetStep(int step) {
  if (run_ && run_->steps() > 0) step = std::clamp(step, 0, run_->steps() - 1);
  if (step == step_) return;
  step_ = step;
  update();
}

void SonarFanView::SetZoom(Zoom zoom) {
  zoom_ = zoom;
  UpdateWindow();
  update();
}

void SonarFanView::SetEllipseScale(double scale) {
  ellipse_scale_ = scale;
  update();
}

void SonarFanView::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  update();
}

void SonarFanView::UpdateWindow() {
  if (!run_) return;
  const SonarSensor& s = run_->sequence->sensor;
  r0_ = s.range_min;
  r1_ = s.range_max;
  if (zoom_ != Zoom::kFeatures) return;
  double lo = INFINITY, hi = -INFINITY;
  for (const SonarFrame& f : run_->frames) {
    for (const SonarPrediction& p : f.predictions) {
      lo = std::min(lo, p.z[0]);
      hi = std::max(hi, p.z[0]);
    }
    for (std::size_t j = 0; j < f.detections.size(); ++j) {
      if (f.pairing[j] == SonarPairing::kNew) continue;
      lo = std::min(lo, f.detections[j].range);
      hi = std::max(hi, f.detections[j].range);
    }
  }
  if (!(hi > lo)) return;
  const double margin = std::max(0.25, 0.15 * (hi - lo));
  r0_ = std::max(s.range_min, lo - margin);
  r1_ = std::min(s.range_max, hi + margin);
}

double SonarFanView::LegendWidth() const {
  const QFontMetricsF fm(font());
  double w = 0;
  for (const QString& t : LegendTexts(ellipse_scale_)) w = std::max(w, fm.horizontalAdvance(t));
  return 8 + 20 + w + 8;
}

double SonarFanView::LegendRowsHeight() const {
  const std::vector<QPointF> at = LegendLayout(LegendTexts(ellipse_scale_), QFontMetricsF(font()), width());
  return (at.back().y() + 1) * kLegendRow + 8;
}

QRectF SonarFanView::RectFor(bool side) const {
  const double left = side ? LegendWidth() + kMarginLeft : kMarginLeft;
  const double bottom = side ? 0 : LegendRowsHeight();
  return QRectF(left, kMarginTop, std::max(1.0, width() - left - kMarginRight),
                std::max(1.0, height() - kMarginTop - bottom - 8));
}

// The legend in a column on the left when that leaves the fan larger than
// rows of it below do.
bool SonarFanView::LegendAtSide() const {
  if (!HasGeometry()) return false;
  const SonarImageFormat format = run_->sequence->image ? *run_->sequence->image : SonarImageFormat();
  const SonarSensor& sensor = run_->sequence->sensor;
  const double side = SonarFanGeometry(sensor, format, r0_, r1_, RectFor(true)).pixels_per_metre();
  const double below = SonarFanGeometry(sensor, format, r0_, r1_, RectFor(false)).pixels_per_metre();
  return side > 1.05 * below;
}

double SonarFanView::LegendHeight() const { return LegendAtSide() ? 0 : LegendRowsHeight(); }

QRectF SonarFanView::FanRect() const { return RectFor(LegendAtSide()); }

bool SonarFanView::HasGeometry() const { return run_ && r1_ > r0_; }

SonarFanGeometry SonarFanView::FanGeometry() const {
  const SonarImageFormat format = run_->sequence->image ? *run_->sequence->image : SonarImageFormat();
  return SonarFanGeometry(run_->sequence->sensor, format, r0_, r1_, FanRect());
}

const QImage& SonarFanView::FanImage(const SonarFanGeometry& g) {
  const QRectF rect = FanRect();
  if (rect != maps_for_ || r0_ != maps_r0_ || r1_ != maps_r1_) {
    // The remap tables: every widget pixel of the fan's box to its polar (column, row).
    maps_for_ = rect;
    maps_r0_ = r0_;
    maps_r1_ = r1_;
    map_x_.create(height(), width(), CV_32F);
    map_y_.create(height(), width(), CV_32F);
    for (int y = 0; y < height(); ++y) {
      auto* mx = map_x_.ptr<float>(y);
      auto* my = map_y_.ptr<float>(y);
      for (int x = 0; x < width(); ++x) {
        const QPointF c(x + 0.5, y + 0.5);  // the pixel's centre
        const Eigen::Vector2d ra = g.FromPixel(c);
        const Eigen::Vector2d rc = g.PixelToBin(c);
        const bool in = g.Contains(ra[0], ra[1]);
        mx[x] = in ? static_cast<float>(rc[1]) : -10.f;
        my[x] = in ? static_cast<float>(rc[0]) : -10.f;
      }
    }
    image_step_ = -1;
  }
  if (image_step_ != step_ || image_.size() != size()) {
    image_ = QImage(size(), QImage::Format_RGB32);
    image_.fill(kBackground);
    const cv::Mat& polar = run_->frames[static_cast<std::size_t>(step_)].image;
    if (!polar.empty()) {
      cv::Mat grey;
      if (polar.depth() == CV_16U) {
        polar.convertTo(grey, CV_8U, 1.0 / 256);
      } else {
        grey = polar;
      }
      cv::Mat fan, inside;
      cv::remap(grey, fan, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
      for (int y = 0; y < image_.height(); ++y) {
        auto* line = reinterpret_cast<QRgb*>(image_.scanLine(y));
        const auto* v = fan.ptr<std::uint8_t>(y);
        const auto* mx = map_x_.ptr<float>(y);
        for (int x = 0; x < image_.width(); ++x) {
          if (mx[x] > -5.f) line[x] = Palette(v[x]);
        }
      }
    }
    image_step_ = step_;
  }
  return image_;
}

void SonarFanView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), kBackground);
  counts_ = Counts();
  p.setPen(kLabel);
  if (!HasGeometry() || run_->steps() == 0) {
    p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap,
               QStringLiteral("Open a sonar sequence with images (File menu) or the sonar demo (Help menu)"));
    return;
  }
  const SonarFanGeometry g = FanGeometry();
  const bool has_frame = run_->from_images && step_ < static_cast<int>(run_->frames.size());
  if (has_frame) {
    p.drawImage(0, 0, FanImage(g));
  } else {
    p.setPen(Qt::NoPen);
    p.setBrush(QColor(10, 10, 12));
    const std::vector<QPointF> sector = g.Sector(g.range_min(), g.range_max(), -g.half_fov(), g.half_fov());
    p.drawPolygon(QPolygonF(QVector<QPointF>(sector.begin(), sector.end())));
  }
  p.setRenderHint(QPainter::Antialiasing, true);
  DrawGrid(p, g);
  if (has_frame) DrawFrame(p, g, run_->frames[static_cast<std::size_t>(step_)]);
  // Title.
  p.setPen(kLabel);
  QFont bold = font();
  bold.setBold(true);
  p.setFont(bold);
  QString title = QStringLiteral("Fan · step %1 / %2").arg(step_).arg(run_->steps() - 1);
  if (has_frame) {
    title += QStringLiteral(" · %1 detections · %2 predicted").arg(counts_.detections).arg(counts_.predictions);
  } else {
    title += QStringLiteral(" · no images (measurements.csv)");
  }
  p.drawText(QRectF(8, 4, width() - 16, 18), Qt::AlignLeft | Qt::AlignVCenter, title);
  p.setFont(font());
  DrawLegend(p);
}

void SonarFanView::DrawGrid(QPainter& p, const SonarFanGeometry& g) {
  const double h = g.half_fov();
  QPen pen(kGrid, 1.0);
  // Range rings: "nice" ranges inside the window, labelled right of the fan's edge.
  const std::vector<double> rings = NiceTicks(g.range_min(), g.range_max(), 6);
  const QFontMetricsF fm(font());
  for (double r : rings) {
    if (r <= g.range_min() + 1e-9 || r >= g.range_max() - 1e-9) continue;
    std::vector<QPointF> arc;
    for (int i = 0; i <= 64; ++i) arc.push_back(g.ToPixel(r, -h + 2 * h * i / 64));
    p.setPen(pen);
    p.drawPolyline(arc.data(), static_cast<int>(arc.size()));
    ++counts_.rings;
    const QString text = QStringLiteral("%1 m").arg(r, 0, 'g', 4);
    const QPointF end = arc.back();
    p.setPen(kLabel);
    p.drawText(QPointF(end.x() + 4, end.y() + fm.ascent() / 2 - 1), text);
  }
  // The window's limits (the sector's outline).
  p.setPen(QPen(kGrid, 1.4));
  const std::vector<QPointF> outline = g.Sector(g.range_min(), g.range_max(), -h, h);
  p.setBrush(Qt::NoBrush);
  p.drawPolygon(QPolygonF(QVector<QPointF>(outline.begin(), outline.end())));
  // Azimuth lines every 5 or 10 degrees (and the edges), labelled beyond the far arc.
  const double deg = h * 180 / M_PI;
  // Labels at least 30 pixels apart along the far arc.
  double step = 5;
  while (step < 45 && g.range_max() * g.pixels_per_metre() * step * M_PI / 180 < 30) step *= 2;
  std::vector<double> azimuths;
  for (double a = -std::floor(deg / step) * step; a <= deg + 1e-9; a += step) azimuths.push_back(a);
  if ((deg - azimuths.back()) * M_PI / 180 * g.range_max() * g.pixels_per_metre() >= 40) {
    azimuths.insert(azimuths.begin(), -deg);
    azimuths.push_back(deg);
  }
  for (double a : azimuths) {
    const double az = a * M_PI / 180;
    p.setPen(QPen(kGrid, 1.0, std::abs(a) < 1e-9 ? Qt::DashLine : Qt::SolidLine));
    const QPointF near = g.ToPixel(g.range_min(), az), far = g.ToPixel(g.range_max(), az);
    p.drawLine(near, far);
    ++counts_.azimuth_lines;
    const QString text = QStringLiteral("%1°").arg(a, 0, 'f', std::abs(a - std::round(a)) > 0.05 ? 1 : 0);
    const QPointF label = g.ToPixel(g.range_max() + 14 / g.pixels_per_metre(), az);
    p.setPen(kLabel);
    p.drawText(QRectF(label.x() - 30, label.y() - 9, 60, 18), Qt::AlignCenter, text);
  }
}

void SonarFanView::DrawFrame(QPainter& p, const SonarFanGeometry& g, const SonarFrame& frame) {
  // Predictions: 2-sigma ellipses (dashed for tentative features) and their ids.
  for (const SonarPrediction& pr : frame.predictions) {
    const QColor c = FeatureColour(pr.id);
    p.setPen(QPen(c, 1.6, pr.waiting ? Qt::DashLine : Qt::SolidLine));
    p.setBrush(Qt::NoBrush);
    p.drawPolygon(Ellipse(g, pr.z, pr.covariance, ellipse_scale_));
    const QPointF centre = g.ToPixel(pr.z[0], pr.z[1]);
    p.setBrush(c);
    p.setPen(Qt::NoPen);
    p.drawEllipse(centre, 1.8, 1.8);
    p.setPen(c);
    p.drawText(QPointF(centre.x() + 6, centre.y() - 5), QString::number(pr.id));
    ++counts_.predictions;
    ++counts_.ellipses;
    counts_.waiting_predictions += pr.waiting;
    // The association line.
    if (pr.detection >= 0 && pr.detection < static_cast<int>(frame.detections.size())) {
      const SonarDetection& d = frame.detections[static_cast<std::size_t>(pr.detection)];
      p.setPen(QPen(c, 2.0));
      p.drawLine(centre, g.ToPixel(d.range, d.azimuth));
    }
  }
  // Detections: + associated (white: a feature in the state, orange: a tentative one), x new.
  for (std::size_t j = 0; j < frame.detections.size(); ++j) {
    const SonarDetection& d = frame.detections[j];
    const QPointF c = g.ToPixel(d.range, d.azimuth);
    ++counts_.detections;
    switch (frame.pairing[j]) {
      case SonarPairing::kInState:
        p.setPen(QPen(kInState, 1.6));
        Plus(p, c, 5);
        ++counts_.in_state_pairs;
        break;
      case SonarPairing::kWaiting:
        p.setPen(QPen(kWaitingPair, 1.6));
        Plus(p, c, 5);
        ++counts_.waiting_pairs;
        break;
      case SonarPairing::kNew:
        p.setPen(QPen(kUnassociated, 1.8));
        Cross(p, c, 4.5);
        ++counts_.unassociated;
        break;
    }
  }
}

void SonarFanView::DrawLegend(QPainter& p) {
  const QFontMetricsF fm(font());
  const QStringList texts = LegendTexts(ellipse_scale_);
  std::vector<QPointF> at;
  double top = 0;
  if (LegendAtSide()) {
    // One entry a row, in the left column, from the bottom up.
    top = height() - texts.size() * kLegendRow - 8;
    p.fillRect(QRectF(0, top - 4, LegendWidth(), height() - top + 4), kBackground.darker(130));
    for (int i = 0; i < texts.size(); ++i) at.emplace_back(8, i);
  } else {
    top = height() - LegendHeight();
    p.fillRect(QRectF(0, top, width(), height() - top), kBackground.darker(130));
    at = LegendLayout(texts, fm, width());
  }
  const QColor sample = FeatureColour(3);
  for (int i = 0; i < texts.size(); ++i) {
    const QPointF c(at[static_cast<std::size_t>(i)].x() + 8,
                    top + 13 + at[static_cast<std::size_t>(i)].y() * kLegendRow);
    p.setBrush(Qt::NoBrush);
    switch (i) {
      case 0:
      case 1:
        p.setPen(QPen(sample, 1.6, i == 0 ? Qt::SolidLine : Qt::DashLine));
        p.drawEllipse(c, 7, 4);
        break;
      case 2:
      case 3:
        p.setPen(QPen(i == 2 ? kInState : kWaitingPair, 1.6));
        Plus(p, c, 5);
        break;
      case 4:
        p.setPen(QPen(kUnassociated, 1.8));
        Cross(p, c, 4.5);
        break;
      default:
        p.setPen(QPen(sample, 2.0));
        p.drawLine(QPointF(c.x() - 7, c.y()), QPointF(c.x() + 7, c.y()));
        break;
    }
    p.setPen(kLabel);
    p.drawText(QPointF(c.x() + 12, c.y() + fm.ascent() / 2 - 1), texts[i]);
  }
}

}  // namespace hull::ui
