#include "ui/views/keyframe_view.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QPainterPath>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <array>
#include <cmath>

#include "base/deviation_colours.h"

namespace hull::ui {

// The image frame with the features and shapes of one keyframe.
class KeyframeCanvas : public QWidget {
 public:
  explicit KeyframeCanvas(QWidget* parent) : QWidget(parent) {
    setObjectName(QStringLiteral("keyframeCanvas"));
    setMinimumSize(280, 200);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  }
  void Set(std::shared_ptr<const MappingRun> mapping, int keyframe) {
    mapping_ = std::move(mapping);
    keyframe_ = keyframe;
    update();
  }
  QSize sizeHint() const override { return {520, 360}; }

 protected:
  void paintEvent(QPaintEvent*) override {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    p.fillRect(rect(), palette().window());
    if (!mapping_ || keyframe_ < 0 || keyframe_ >= static_cast<int>(mapping_->result->keyframes.size())) {
      p.setPen(palette().color(QPalette::PlaceholderText));
      p.drawText(rect(), Qt::AlignCenter, QStringLiteral("No keyframe: run the inspection (F5)"));
      return;
    }
    const KeyframeShapes& k = mapping_->result->keyframes[keyframe_];
    const CameraRig& camera = mapping_->input->camera;
    const int bar = 70;  // room for the colour bar
    const double s = std::min((width() - bar - 16.0) / camera.width, (height() - 16.0) / camera.height);
    const QRectF image(8, (height() - s * camera.height) / 2.0, s * camera.width, s * camera.height);
    p.fillRect(image, QColor(24, 34, 44));
    p.setPen(QPen(QColor(120, 130, 140), 1));
    p.drawRect(image);
    auto at = [&](const Eigen::Vector2d& px) {
      return QPointF(image.left() + (px.x() + 0.5) * s, image.top() + (px.y() + 0.5) * s);
    };
    const double reach =
        std::max({std::abs(mapping_->overlays->min_deviation), std::abs(mapping_->overlays->max_deviation), 0.01});
    // Alpha shapes: white, translucent, with their edges.
    for (const DetectedShape& shape : k.shapes) {
      for (const Face& f : shape.triangles) {
        QPainterPath path;
        path.moveTo(at(shape.pixels[f[0]]));
        path.lineTo(at(shape.pixels[f[1]]));
        path.lineTo(at(shape.pixels[f[2]]));
        path.closeSubpath();
        p.fillPath(path, QColor(255, 255, 255, 70));
        p.setPen(QPen(QColor(255, 255, 255, 200), 1));
        p.drawPath(path);
      }
    }
    // Features.
    for (const ShapePoint& q : k.points) {
      const QPointF c = at(q.pixel);
      if (q.cluster == ShapePoint::kBelowTau) {
        p.setPen(Qt::NoPen);
        p.setBrush(QColor(150, 150, 150));
        p.drawEllipse(c, 2.0, 2.0);
        continue;
      }
      p.setBrush(KeyframeView::DeviationColour(q.deviation, -reach, reach));
      p.setPen(q.cluster == ShapePoint::kNoise ? QPen(Qt::black, 1.2) : Qt::NoPen);
      p.drawEllipse(c, 3.5, 3.5);
    }
    p.setBrush(Qt::NoBrush);
    // Colour bar.
    const QRectF bar_rect(image.right() + 14, image.top() + 20, 14, std::max(40.0, image.height() - 40));
    for (int i = 0; i < static_cast<int>(bar_rect.height()); ++i) {
      const double d = reach - 2 * reach * i / bar_rect.height();
      p.setPen(KeyframeView::DeviationColour(d, -reach, reach));
      p.drawLine(QPointF(bar_rect.left(), bar_rect.top() + i), QPointF(bar_rect.right(), bar_rect.top() + i));
    }
    p.setPen(palette().color(QPalette::WindowText));
    p.drawRect(bar_rect);
    const QFontMetrics fm(font());
    for (double d : {reach, 0.0, -reach}) {
      const double y = bar_rect.top() + (reach - d) / (2 * reach) * bar_rect.height();
      p.drawText(QPointF(bar_rect.right() + 3, y + fm.ascent() / 2.0 - 1),
                 QString::number(d * 100.0, 'f', d == 0 ? 0 : 1));
    }
    p.drawText(QRectF(bar_rect.left() - 10, image.top(), 70, 18), Qt::AlignLeft, QStringLiteral("cm"));
  }

 private:
  std::shared_ptr<const MappingRun> mapping_;
  int keyframe_ = -1;
};

KeyframeView::KeyframeView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("keyframeView"));
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  auto* row = new QHBoxLayout;
  previous_ = new QToolButton(this);
  previous_->setArrowType(Qt::LeftArrow);
  previous_->setToolTip(QStringLiteral("The previous keyframe with shapes"));
  next_ = new QToolButton(this);
  next_->setArrowType(Qt::RightArrow);
  next_->setToolTip(QStringLiteral("The next keyframe with shapes"));
  box_ = new QComboBox(this);
  box_->setObjectName(QStringLiteral("keyframeBox"));
  box_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
  row->addWidget(new QLabel(QStringLiteral("Keyframe"), this));
  row->addWidget(previous_);
  row->addWidget(box_);
  row->addWidget(next_);
  row->addStretch(1);
  outer->addLayout(row);
  canvas_ = new KeyframeCanvas(this);
  outer->addWidget(canvas_, 1);
  info_ = new QLabel(this);
  info_->setObjectName(QStringLiteral("keyframeInfo"));
  info_->setWordWrap(true);
  outer->addWidget(info_);

  connect(box_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int i) {
    if (i >= 0) ShowKeyframe(box_->itemData(i).toInt());
  });
  connect(previous_, &QToolButton::clicked, this,
          [this] { box_->setCurrentIndex(std::max(0, box_->currentIndex() - 1)); });
  connect(next_, &QToolButton::clicked, this,
          [this] { box_->setCurrentIndex(std::min(box_->count() - 1, box_->currentIndex() + 1)); });
  SetMapping(nullptr);
}

QColor KeyframeView::DeviationColour(double deviation, double lo, double hi) {
  // The scene's and the report's map (base/deviation_colours.h).
  const double t = std::clamp((deviation - lo) / std::max(hi - lo, 1e-9), 0.0, 1.0);
  const std::array<double, 3> rgb = DivergingRgb(2 * t - 1);
  return QColor::fromRgbF(rgb[0], rgb[1], rgb[2]);
}

void KeyframeView::SetMapping(std::shared_ptr<const MappingRun> mapping) {
  const std::int64_t shown_id = mapping_ && keyframe_ >= 0 ? mapping_->result->keyframes[keyframe_].id : -1;
  mapping_ = std::move(mapping);
  keyframe_ = -1;
  Populate();
  // Stay on the same keyframe when the new result has shapes there.
  int pick = box_->count() > 0 ? 0 : -1;
  for (int i = 0; i < box_->count(); ++i) {
    const int k = box_->itemData(i).toInt();
    if (mapping_->result->keyframes[k].id == shown_id) pick = i;
  }
  if (pick >= 0) {
    box_->setCurrentIndex(pick);
    ShowKeyframe(box_->itemData(pick).toInt());
  } else {
    ShowKeyframe(-1);
  }
}

void KeyframeView::Populate() {
  const QSignalBlocker block(box_);
  box_->clear();
  if (!mapping_) return;
  const auto& keyframes = mapping_->result->keyframes;
  for (int i = 0; i < static_cast<int>(keyframes.size()); ++i) {
    if (keyframes[i].shapes.empty()) continue;
    const std::size_t n = keyframes[i].shapes.size();
    box_->addItem(QStringLiteral("%1 (%2 shape%3)").arg(keyframes[i].id).arg(n).arg(n == 1 ? "" : "s"), i);
  }
}

void KeyframeView::ShowKeyframe(int index) {
  if (!mapping_ || index < 0 || index >= static_cast<int>(mapping_->result->keyframes.size())) index = -1;
  keyframe_ = index;
  canvas_->Set(mapping_, keyframe_);
  previous_->setEnabled(box_->count() > 1);
  next_->setEnabled(box_->count() > 1);
  if (keyframe_ < 0) {
    info_->setText(mapping_ ? QStringLiteral("No keyframe has shapes for these parameters.")
                            : QStringLiteral("The map's keyframes appear here once the inspection has run."));
    return;
  }
  const int item = box_->findData(keyframe_);
  if (item >= 0 && item != box_->currentIndex()) {
    const QSignalBlocker block(box_);
    box_->setCurrentIndex(item);
  }
  const KeyframeShapes& k = mapping_->result->keyframes[keyframe_];
  int clustered = 0, noise = 0;
  for (const ShapePoint& q : k.points) {
    clustered += q.cluster >= 0;
    noise += q.cluster == ShapePoint::kNoise;
  }
  info_->setText(QStringLiteral("Keyframe %1: %2 features seen, %3 in %4 alpha shape(s), %5 isolated (ringed); grey "
                                "ones are within τ of the CAD surface.")
                     .arg(k.id)
                     .arg(k.points.size())
                     .arg(clustered)
                     .arg(k.shapes.size())
                     .arg(noise));
}

void KeyframeView::ShowObject(int object_index) {
  if (!mapping_ || object_index < 0 || object_index >= static_cast<int>(mapping_->result->objects.size())) return;
  const DetectedObject& o = mapping_->result->objects[object_index];
  // The keyframe among the object's views with the most clustered features.
  int best = -1, best_count = -1;
  const auto& keyframes = mapping_->result->keyframes;
  for (int i = 0; i < static_cast<int>(keyframes.size()); ++i) {
    if (!std::binary_search(o.keyframes.begin(), o.keyframes.end(), keyframes[i].id)) continue;
    int count = 0;
    for (const ShapePoint& q : keyframes[i].points) count += q.cluster >= 0;
    if (count > best_count) {
      best = i;
      best_count = count;
    }
  }
  if (best >= 0) ShowKeyframe(best);
}

QString KeyframeView::infoText() const { return info_->text(); }

}  // namespace hull::ui
