#include "ui/views/cross_section_view.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "ui/views/profile_canvas.h"

namespace hull::ui {

namespace {

constexpr int kSliderSteps = 1000;
const SurfaceModel kColumns[] = {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture};

}  // namespace

CrossSectionView::CrossSectionView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("crossSectionView"));
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  auto* row = new QHBoxLayout;
  direction_ = new QComboBox(this);
  direction_->setObjectName(QStringLiteral("slabDirection"));
  direction_->addItem(QStringLiteral("Across the hull"), static_cast<int>(SlabDirection::kTransverse));
  direction_->addItem(QStringLiteral("Along the hull"), static_cast<int>(SlabDirection::kLongitudinal));
  direction_->setToolTip(
      QStringLiteral("Across: a transverse section seen from astern (starboard to the right). Along: a "
                     "longitudinal section seen from starboard (bow to the right)."));
  slider_ = new QSlider(Qt::Horizontal, this);
  slider_->setObjectName(QStringLiteral("slabSlider"));
  slider_->setRange(0, kSliderSteps);
  slider_->setToolTip(QStringLiteral("Where the slab lies along its normal, over the surveyed stretch"));
  position_ = new QDoubleSpinBox(this);
  position_->setObjectName(QStringLiteral("slabPosition"));
  position_->setDecimals(2);
  position_->setSingleStep(0.1);
  position_->setRange(-1e4, 1e4);
  position_->setSuffix(QStringLiteral(" m"));
  position_->setKeyboardTracking(false);
  position_->setToolTip(QStringLiteral("The slab's mid-plane: metres from the model's origin along its normal"));
  width_ = new QDoubleSpinBox(this);
  width_->setObjectName(QStringLiteral("slabWidth"));
  width_->setDecimals(2);
  width_->setRange(0.02, 10.0);
  width_->setSingleStep(0.05);
  width_->setSuffix(QStringLiteral(" m"));
  width_->setKeyboardTracking(false);
  width_->setToolTip(QStringLiteral("The slab's thickness: points within half of it from the mid-plane are drawn"));
  compare_ = new QPushButton(QStringLiteral("Compare models"), this);
  compare_->setObjectName(QStringLiteral("compareModelsButton"));
  compare_->setToolTip(QStringLiteral("Run the models not run yet (naive, all on the surface) for these parameters"));
  at_pick_ = new QPushButton(QStringLiteral("At the pick"), this);
  at_pick_->setObjectName(QStringLiteral("slabAtPick"));
  at_pick_->setToolTip(QStringLiteral("Move the slab to what was last picked in the 3-D view"));
  at_pick_->setEnabled(false);
  connect(at_pick_, &QPushButton::clicked, this, [this] {
    if (picked_) CentreOn(*picked_);
  });
  row->addWidget(new QLabel(QStringLiteral("Slab"), this));
  row->addWidget(direction_);
  row->addWidget(slider_, 1);
  row->addWidget(position_);
  row->addWidget(new QLabel(QStringLiteral("width"), this));
  row->addWidget(width_);
  row->addWidget(at_pick_);
  row->addWidget(compare_);
  outer->addLayout(row);
  canvas_ = new ProfileCanvas(this);
  outer->addWidget(canvas_, 1);
  info_ = new QLabel(this);
  info_->setObjectName(QStringLiteral("crossSectionInfo"));
  outer->addWidget(info_);

  connect(direction_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
    if (updating_) return;
    spec_.direction = static_cast<SlabDirection>(direction_->currentData().toInt());
    positioned_ = false;  // a new direction: start from the middle of the data
    UpdateRange();
    Recompute(false);
  });
  connect(slider_, &QSlider::valueChanged, this, [this](int value) {
    if (updating_) return;
    position_->setValue(range_.first + (range_.second - range_.first) * value / kSliderSteps);
  });
  connect(position_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &CrossSectionView::ReadControls);
  connect(width_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &CrossSectionView::ReadControls);
  connect(compare_, &QPushButton::clicked, this, &CrossSectionView::compareRequested);
  WriteControls();
  Recompute(false);
}

void CrossSectionView::SetMesh(std::shared_ptr<const TriangleMesh> mesh, const std::optional<ModelAxes>& axes) {
  mesh_ = std::move(mesh);
  axes_ = axes;
  positioned_ = false;
  UpdateRange();
  Recompute(false);
}

void CrossSectionView::SetRuns(std::shared_ptr<const AdjustmentRun> current, const RunsByModel& runs) {
  const bool first = !current_ && current;
  current_ = std::move(current);
  runs_ = runs;
  if (current_ && !runs_.count(current_->model())) runs_[current_->model()] = current_;
  UpdateRange();
  Recompute(!first);
}

void CrossSectionView::SetSlab(const SlabSpec& spec) {
  const bool direction_changed = spec.direction != spec_.direction;
  spec_ = spec;
  positioned_ = true;
  if (direction_changed) UpdateRange();
  WriteControls();
  Recompute(!direction_changed);
}

void CrossSectionView::CentreOn(const Eigen::Vector3d& p_g) {
  if (!current_) return;
  const Eigen::Vector3d p_M = current_->x_gM().Inverse() * p_g;
  SlabSpec s = spec_;
  s.position = MakeSlabFrame(axes_, s).normal.dot(p_M);
  SetSlab(s);
}

void CrossSectionView::SetPickedPoint(const std::optional<Eigen::Vector3d>& p_g) {
  picked_ = p_g;
  at_pick_->setEnabled(picked_.has_value());
}

void CrossSectionView::SetCompareEnabled(bool enabled) { compare_->setEnabled(enabled); }

void CrossSectionView::ReadControls() {
  if (updating_) return;
  spec_.position = position_->value();
  spec_.width = width_->value();
  positioned_ = true;
  WriteControls();
  Recompute(true);
}

void CrossSectionView::WriteControls() {
  updating_ = true;
  direction_->setCurrentIndex(direction_->findData(static_cast<int>(spec_.direction)));
  position_->setValue(spec_.position);
  width_->setValue(spec_.width);
  const double span = range_.second - range_.first;
  slider_->setEnabled(span > 0);
  slider_->setValue(span > 0 ? static_cast<int>(std::lround((spec_.position - range_.first) / span * kSliderSteps))
                             : 0);
  updating_ = false;
}

void CrossSectionView::UpdateRange() {
  std::vector<Eigen::Vector3d> points_M;
  extent_.setEmpty();
  if (current_) {
    const Pose x_Mg = current_->x_gM().Inverse();
    for (const AdjustedLandmark& l : current_->overlays->landmarks) points_M.push_back(x_Mg * l.position);
  }
  range_ = SlabRange(axes_, spec_.direction, points_M);
  const SlabFrame frame = MakeSlabFrame(axes_, spec_);
  for (const Eigen::Vector3d& p : points_M) extent_.extend(frame.Project(p));
  if (!extent_.isEmpty()) {
    extent_.min() -= Eigen::Vector2d(0.3, 0.3);
    extent_.max() += Eigen::Vector2d(0.3, 0.3);
  }
  if (!positioned_ && !points_M.empty()) {
    std::vector<double> along;
    for (const auto& p : points_M) along.push_back(frame.normal.dot(p));
    std::nth_element(along.begin(), along.begin() + static_cast<std::ptrdiff_t>(along.size() / 2), along.end());
    spec_.position = along[along.size() / 2];
    positioned_ = true;
  }
  WriteControls();
}

void CrossSectionView::Recompute(bool keep_view) {
  const SlabFrame frame = MakeSlabFrame(axes_, spec_);
  std::vector<ProfileSegment> cad = mesh_ ? MeshSection(*mesh_, frame) : std::vector<ProfileSegment>();
  std::vector<ProfilePanel> panels;
  if (current_) {
    for (SurfaceModel m : kColumns) {
      ProfilePanel panel;
      panel.title = ModelShortName(m);
      auto it = runs_.find(m);
      if (it != runs_.end()) {
        panel.present = true;
        panel.profile = ComputeModelProfile(*it->second, frame);
      } else {
        panel.missing_text = QStringLiteral("Not run for these parameters:\nCompare models runs it.");
      }
      panels.push_back(std::move(panel));
    }
  }
  QString info;  // the canvas says what to do while there is nothing to show
  if (current_) {
    const ModelProfile shown = ComputeModelProfile(*current_, frame);
    info = QStringLiteral("Slab %1 m wide at %2 m: %3 features and %4 DVL returns of the %5 model (on screen).")
               .arg(spec_.width, 0, 'f', 2)
               .arg(spec_.position, 0, 'f', 2)
               .arg(shown.features.size())
               .arg(shown.dvl.size())
               .arg(ModelShortName(current_->model()).toLower());
  }
  info_->setText(info);
  canvas_->SetContents(std::move(cad), std::move(panels), keep_view);
  emit slabMoved();
}

std::optional<SlabBox> CrossSectionView::SlabBoxInG() const {
  if (!current_ || extent_.isEmpty()) return std::nullopt;
  return MakeSlabBox(MakeSlabFrame(axes_, spec_), extent_, current_->x_gM());
}

}  // namespace hull::ui
