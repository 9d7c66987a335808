#include "ui/views/images_view.h"

#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QSlider>
#include <QSpinBox>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "base/error.h"
#include "survey/survey_images.h"

namespace hull::ui {

namespace {

const QColor kInlier(40, 210, 80);
const QColor kOutlier(235, 50, 45);
const QColor kUnverified(175, 175, 190);
const QColor kFeature(255, 215, 0);
const QColor kReprojection(70, 170, 255);
const QColor kResidual(255, 130, 20);

QColor VerdictColour(MatchVerdict v) {
  switch (v) {
    case MatchVerdict::kInlier:
      return kInlier;
    case MatchVerdict::kOutlier:
      return kOutlier;
    case MatchVerdict::kUnverified:
      break;
  }
  return kUnverified;
}

// An 8-bit QImage of a survey image (grey or BGR, 8 or 16 bit).
QImage ToQImage(const cv::Mat& m) {
  cv::Mat m8;
  if (m.depth() == CV_16U) {
    m.convertTo(m8, CV_8U, 1.0 / 257.0);
  } else {
    m8 = m;
  }
  if (m8.channels() == 3) {
    return QImage(m8.data, m8.cols, m8.rows, static_cast<int>(m8.step), QImage::Format_BGR888).copy();
  }
  if (m8.channels() == 1) {
    return QImage(m8.data, m8.cols, m8.rows, static_cast<int>(m8.step), QImage::Format_Grayscale8).copy();
  }
  return {};
}

}  // namespace

// The image with its overlay; zoom about the cursor, drag to pan.
class ImagesCanvas : public QWidget {
 public:
  explicit ImagesCanvas(ImagesView* view) : QWidget(view), view_(view) {
    setObjectName(QStringLiteral("imagesCanvas"));
    setMinimumSize(320, 240);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  }
  QSize sizeHint() const override { return {680, 520}; }
  void ResetZoom() {
    zoom_ = 1.0;
    pan_ = QPointF();
    update();
  }
  double zoom() const { return zoom_; }
  double residualScale = 10.0;

 protected:
  // Image pixel -> widget: the fitted image, zoomed and panned.
  QTransform ImageToWidget(const QSize& image) const {
    const double fit = std::min((width() - 8.0) / image.width(), (height() - 8.0) / image.height());
    const double s = fit * zoom_;
    const QPointF origin((width() - s * image.width()) / 2.0 + pan_.x(),
                         (height() - s * image.height()) / 2.0 + pan_.y());
    return QTransform(s, 0, 0, s, origin.x(), origin.y());
  }

  void paintEvent(QPaintEvent*) override {
    QPainter p(this);
    p.fillRect(rect(), QColor(20, 24, 30));
    const ImageOverlay& o = view_->overlay();
    const SurveyBundle* bundle = bundle_ptr_;
    if (!bundle || o.index < 0) {
      p.setPen(QColor(190, 190, 190));
      p.drawText(rect(), Qt::AlignCenter, QStringLiteral("No survey with images: open a version 2 bundle"));
      return;
    }
    const QSize size(bundle->manifest.camera.width, bundle->manifest.camera.height);
    const QTransform t = ImageToWidget(size);
    p.setRenderHint(QPainter::SmoothPixmapTransform, zoom_ < 2.0);
    const QRectF frame = t.mapRect(QRectF(0, 0, size.width(), size.height()));
    if (!view_->image().isNull()) {
      p.drawImage(frame, view_->image());
    } else {
      p.fillRect(frame, QColor(40, 46, 54));
      p.setPen(QColor(200, 200, 200));
      p.drawText(frame, Qt::AlignCenter | Qt::TextWordWrap, view_->missingImageText());
    }
    p.setRenderHint(QPainter::Antialiasing);
    // Pixel centres: a feature at (u, v) is drawn at (u + 0.5, v + 0.5) of the image rectangle.
    auto at = [&t](const Eigen::Vector2d& px) { return t.map(QPointF(px.x() + 0.5, px.y() + 0.5)); };
    const double s = t.m11();
    const ImagesView::Layers& layers = view_->layers();
    if (layers.stereo) {
      for (const OverlayMatch& m : o.stereo) {
        QColor c = VerdictColour(m.verdict);
        c.setAlpha(m.verdict == MatchVerdict::kUnverified ? 90 : 150);
        p.setPen(QPen(c, 1.0, Qt::DashLine));
        p.drawLine(at(m.from), at(m.to));
      }
    }
    if (layers.temporal) {
      for (const OverlayMatch& m : o.temporal) {
        p.setPen(QPen(VerdictColour(m.verdict), 1.6));
        p.drawLine(at(m.from), at(m.to));
      }
    }
    if (layers.features) {
      for (const OverlayFeature& f : o.features) {
        const double r = std::clamp(0.5 * f.size * s, 2.0, 12.0);
        QColor c = kFeature;
        c.setAlpha(f.tracked ? 255 : 150);
        p.setPen(QPen(c, f.tracked ? 1.4 : 0.8));
        p.setBrush(Qt::NoBrush);
        p.drawEllipse(at(f.pixel), r, r);
        if (f.tracked) {
          p.setPen(Qt::NoPen);
          p.setBrush(c);
          p.drawEllipse(at(f.pixel), 1.6, 1.6);
        }
      }
    }
    if (layers.reprojections) {
      for (const OverlayReprojection& r : o.reprojections) {
        const Eigen::Vector2d tip = r.observed + residualScale * (r.projected - r.observed);
        p.setPen(QPen(kResidual, 1.6));
        p.drawLine(at(r.observed), at(tip));
        const QPointF c = at(r.projected);
        p.setPen(QPen(kReprojection, 1.6));
        p.drawLine(c + QPointF(-4, -4), c + QPointF(4, 4));
        p.drawLine(c + QPointF(-4, 4), c + QPointF(4, -4));
      }
    }
    PaintLegend(p, o);
  }

  void PaintLegend(QPainter& p, const ImageOverlay& o) {
    struct Row {
      QColor colour;
      int style;  // 0 circle, 1 solid line, 2 dashed line, 3 cross
      QString text;
    };
    std::vector<Row> rows;
    rows.push_back({kFeature, 0, QStringLiteral("features %1 (%2 tracked)").arg(o.features.size()).arg(o.tracked)});
    if (!o.stereo.empty()) {
      rows.push_back({kInlier, 2, QStringLiteral("stereo inliers %1").arg(o.stereo_inliers)});
      rows.push_back({kOutlier, 2, QStringLiteral("stereo outliers %1").arg(o.stereo_outliers)});
      rows.push_back({kUnverified, 2, QStringLiteral("stereo unverified %1").arg(o.stereo_unverified)});
    }
    if (o.previous_keyframe >= 0) {
      rows.push_back(
          {kInlier, 1, QStringLiteral("temporal inliers %1 (to %2)").arg(o.temporal_inliers).arg(o.previous_keyframe)});
      rows.push_back({kOutlier, 1, QStringLiteral("temporal outliers %1").arg(o.temporal_outliers)});
    }
    if (!o.reprojections.empty()) {
      rows.push_back(
          {kReprojection, 3,
           QStringLiteral("reprojections %1, RMS %2 px").arg(o.reprojections.size()).arg(o.rms_residual, 0, 'f', 2)});
      rows.push_back({kResidual, 1, QStringLiteral("residual ×%1").arg(residualScale)});
    }
    const QFontMetrics fm = p.fontMetrics();
    int w = 0;
    for (const Row& r : rows) w = std::max(w, fm.horizontalAdvance(r.text));
    const int line = fm.height() + 2;
    const QRect box(8, 8, w + 40, static_cast<int>(rows.size()) * line + 8);
    p.setPen(Qt::NoPen);
    p.setBrush(QColor(0, 0, 0, 170));
    p.drawRoundedRect(box, 4, 4);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const int y = box.top() + 4 + static_cast<int>(i) * line;
      const QPointF mid(box.left() + 16, y + line / 2.0);
      const Row& r = rows[i];
      p.setBrush(Qt::NoBrush);
      switch (r.style) {
        case 0:
          p.setPen(QPen(r.colour, 1.4));
          p.drawEllipse(mid, 4.5, 4.5);
          break;
        case 1:
        case 2:
          p.setPen(QPen(r.colour, 1.8, r.style == 2 ? Qt::DashLine : Qt::SolidLine));
          p.drawLine(mid - QPointF(9, 0), mid + QPointF(9, 0));
          break;
        default:
          p.setPen(QPen(r.colour, 1.6));
          p.drawLine(mid + QPointF(-4, -4), mid + QPointF(4, 4));
          p.drawLine(mid + QPointF(-4, 4), mid + QPointF(4, -4));
      }
      p.setPen(QColor(235, 235, 235));
      p.drawText(QRect(box.left() + 32, y, w + 4, line), Qt::AlignVCenter | Qt::AlignLeft, r.text);
    }
  }

  void wheelEvent(QWheelEvent* e) override {
    const double factor = std::pow(1.0015, e->angleDelta().y());
    const double zoom = std::clamp(zoom_ * factor, 1.0, 40.0);
    // Keep the point under the cursor in place.
    const QPointF c(width() / 2.0, height() / 2.0);
    const QPointF cursor = e->position();
    pan_ = cursor - c - (cursor - c - pan_) * (zoom / zoom_);
    zoom_ = zoom;
    if (zoom_ == 1.0) pan_ = QPointF();
    update();
    e->accept();
  }
  void mousePressEvent(QMouseEvent* e) override { last_ = e->pos(); }
  void mouseMoveEvent(QMouseEvent* e) override {
    if (!(e->buttons() & Qt::LeftButton)) return;
    pan_ += e->pos() - last_;
    last_ = e->pos();
    update();
  }
  void mouseDoubleClickEvent(QMouseEvent*) override { ResetZoom(); }

 private:
  ImagesView* view_;
  double zoom_ = 1.0;
  QPointF pan_;
  QPoint last_;
  friend class ImagesView;
  const SurveyBundle* bundle_ptr_ = nullptr;
};

ImagesView::ImagesView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("imagesView"));
  auto* root = new QVBoxLayout(this);
  root->setContentsMargins(4, 4, 4, 4);
  auto* bar = new QHBoxLayout;
  bar->addWidget(new QLabel(QStringLiteral("Keyframe"), this));
  slider_ = new QSlider(Qt::Horizontal, this);
  slider_->setObjectName(QStringLiteral("imagesSlider"));
  spin_ = new QSpinBox(this);
  spin_->setObjectName(QStringLiteral("imagesKeyframe"));
  spin_->setToolTip(QStringLiteral("Row of nav.csv (the keyframe id is in the legend)"));
  camera_ = new QComboBox(this);
  camera_->setObjectName(QStringLiteral("imagesCamera"));
  camera_->addItem(QStringLiteral("Top camera"));
  camera_->addItem(QStringLiteral("Bottom camera"));
  bar->addWidget(slider_, 1);
  bar->addWidget(spin_);
  bar->addWidget(camera_);
  auto check = [this, bar](const char* name, const QString& text, bool Layers::*field) {
    auto* box = new QCheckBox(text, this);
    box->setObjectName(QString::fromLatin1(name));
    box->setChecked(true);
    connect(box, &QCheckBox::toggled, this, [this, field](bool on) {
      layers_.*field = on;
      canvas_->update();
    });
    bar->addWidget(box);
    return box;
  };
  show_features_ = check("imagesShowFeatures", QStringLiteral("Features"), &Layers::features);
  show_stereo_ = check("imagesShowStereo", QStringLiteral("Stereo"), &Layers::stereo);
  show_temporal_ = check("imagesShowTemporal", QStringLiteral("Temporal"), &Layers::temporal);
  show_reprojections_ = check("imagesShowReprojections", QStringLiteral("Reprojections"), &Layers::reprojections);
  root->addLayout(bar);
  canvas_ = new ImagesCanvas(this);
  root->addWidget(canvas_, 1);
  legend_ = new QLabel(this);
  legend_->setObjectName(QStringLiteral("imagesLegend"));
  legend_->setWordWrap(true);
  root->addWidget(legend_);

  connect(slider_, &QSlider::valueChanged, this, [this](int v) { ShowKeyframe(v); });
  connect(spin_, qOverload<int>(&QSpinBox::valueChanged), this, [this](int v) { ShowKeyframe(v); });
  connect(camera_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int i) { SetBottomCamera(i == 1); });
  Refresh();
}

ImagesView::~ImagesView() = default;

void ImagesView::SetSurvey(std::shared_ptr<const SurveyBundle> bundle,
                           std::shared_ptr<const FrontEndResult> front_end) {
  const bool same_survey = bundle_ && bundle && bundle_->directory == bundle->directory;
  bundle_ = std::move(bundle);
  front_end_ = std::move(front_end);
  canvas_->bundle_ptr_ = bundle_.get();
  const int n = bundle_ ? static_cast<int>(bundle_->nav.size()) : 0;
  const bool stereo = bundle_ && bundle_->manifest.camera.stereo();
  camera_->setEnabled(stereo);
  if (!stereo) bottom_ = false;
  {
    const QSignalBlocker b1(slider_), b2(spin_), b3(camera_);
    slider_->setRange(0, std::max(0, n - 1));
    spin_->setRange(0, std::max(0, n - 1));
    camera_->setCurrentIndex(bottom_ ? 1 : 0);
  }
  image_index_ = -2;
  if (!same_survey) {
    canvas_->ResetZoom();
    index_ = -1;
  }
  ShowKeyframe(n == 0 ? -1 : std::clamp(index_ < 0 ? std::min(1, n - 1) : index_, 0, n - 1));
}

void ImagesView::SetAdjustment(std::shared_ptr<const AdjustmentResult> adjustment) {
  adjustment_ = std::move(adjustment);
  Refresh();
}

void ImagesView::ShowKeyframe(int index) {
  const int n = bundle_ ? static_cast<int>(bundle_->nav.size()) : 0;
  index_ = n == 0 ? -1 : std::clamp(index, 0, n - 1);
  {
    const QSignalBlocker b1(slider_), b2(spin_);
    slider_->setValue(std::max(0, index_));
    spin_->setValue(std::max(0, index_));
  }
  Refresh();
}

void ImagesView::SetBottomCamera(bool bottom) {
  bottom_ = bottom && bundle_ && bundle_->manifest.camera.stereo();
  const QSignalBlocker b(camera_);
  camera_->setCurrentIndex(bottom_ ? 1 : 0);
  Refresh();
}

void ImagesView::SetResidualScale(double scale) {
  residual_scale_ = scale;
  canvas_->residualScale = scale;
  canvas_->update();
}

void ImagesView::ReadImage() {
  if (image_index_ == index_ && image_bottom_ == bottom_) return;
  image_index_ = index_;
  image_bottom_ = bottom_;
  image_ = QImage();
  image_error_.clear();
  if (!bundle_ || index_ < 0 || !overlay_.has_image) return;
  try {
    image_ = ToQImage(ReadSurveyImage(*bundle_, overlay_.keyframe, bottom_));
  } catch (const std::exception& e) {
    image_error_ = QString::fromStdString(e.what());
  }
}

void ImagesView::Refresh() {
  overlay_ =
      bundle_ ? ComputeImageOverlay(*bundle_, front_end_.get(), adjustment_.get(), index_, bottom_) : ImageOverlay();
  ReadImage();
  slider_->setEnabled(bundle_ != nullptr);
  spin_->setEnabled(bundle_ != nullptr);
  show_temporal_->setEnabled(!bottom_);
  legend_->setText(legendText());
  canvas_->update();
}

QString ImagesView::missingImageText() const {
  if (!image_.isNull() || !bundle_) return {};
  if (!image_error_.isEmpty()) return image_error_;
  // A survey of feature tracks has no images at all: not a dropped frame.
  if (bundle_->images && bundle_->images->present() > 0) return QStringLiteral("No image (a dropped frame)");
  return QStringLiteral(
      "This survey has no camera images (its features came as tracks): they are drawn on the "
      "image frame");
}

QString ImagesView::legendText() const {
  const ImageOverlay& o = overlay_;
  if (!bundle_ || o.index < 0) return QStringLiteral("No survey open.");
  QString text = QStringLiteral("Keyframe %1 (row %2, %3 camera)")
                     .arg(o.keyframe)
                     .arg(o.index)
                     .arg(o.bottom ? QStringLiteral("bottom") : QStringLiteral("top"));
  if (!o.has_image) text += QStringLiteral(", no image");
  text += QStringLiteral(": %1 features, %2 tracked").arg(o.features.size()).arg(o.tracked);
  if (!o.from_images) text += QStringLiteral(" (from features.csv)");
  if (!o.stereo.empty()) {
    text += QStringLiteral("; stereo matches %1 (inliers %2, outliers %3, unverified %4)")
                .arg(o.stereo.size())
                .arg(o.stereo_inliers)
                .arg(o.stereo_outliers)
                .arg(o.stereo_unverified);
  }
  if (o.previous_keyframe >= 0) {
    text += QStringLiteral("; temporal matches with keyframe %1: %2 (inliers %3, outliers %4%5)")
                .arg(o.previous_keyframe)
                .arg(o.temporal.size())
                .arg(o.temporal_inliers)
                .arg(o.temporal_outliers)
                .arg(o.previous_pair_accepted ? QString() : QStringLiteral(", pair dropped"));
  }
  if (!o.reprojections.empty()) {
    text += QStringLiteral("; reprojections %1, RMS residual %2 px (vectors ×%3)")
                .arg(o.reprojections.size())
                .arg(o.rms_residual, 0, 'f', 2)
                .arg(residual_scale_);
  }
  return text + QLatin1Char('.');
}

}  // namespace hull::ui
