#include "ui/panels/layers_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QScrollArea>
#include <QSpinBox>
#include <QVBoxLayout>

namespace hull::ui {

LayersPanel::LayersPanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("layersPanel"));
  qRegisterMetaType<SceneOptions>("hull::ui::SceneOptions");
  qRegisterMetaType<ModelPlacement>("hull::ui::ModelPlacement");
  // The controls scroll when the dock is short.
  auto* root = new QVBoxLayout(this);
  root->setContentsMargins(0, 0, 0, 0);
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* content = new QWidget(scroll);
  auto* outer = new QVBoxLayout(content);

  auto* shown = new QGroupBox(QStringLiteral("Shown in the 3-D view"), content);
  auto* shown_layout = new QVBoxLayout(shown);
  for (SceneLayer layer : AllSceneLayers()) {
    auto* check = new QCheckBox(LayerLabel(layer), shown);
    check->setObjectName(LayerKey(layer));
    shown_layout->addWidget(check);
    checks_.insert(layer, check);
    connect(check, &QCheckBox::toggled, this, &LayersPanel::ReadWidgets);
    if (layer == SceneLayer::kHull) {
      edges_ = new QCheckBox(QStringLiteral("Hull edges"), shown);
      edges_->setObjectName(QStringLiteral("hull_edges"));
      edges_->setContentsMargins(20, 0, 0, 0);
      shown_layout->addWidget(edges_);
      connect(edges_, &QCheckBox::toggled, this, &LayersPanel::ReadWidgets);
    }
  }
  outer->addWidget(shown);

  auto* style = new QGroupBox(QStringLiteral("Colours and frusta"), content);
  auto* form = new QFormLayout(style);
  colouring_ = new QComboBox(style);
  colouring_->setObjectName(QStringLiteral("landmarkColouring"));
  colouring_->addItem(QStringLiteral("Label"), ColouringKey(LandmarkColouring::kLabel));
  colouring_->addItem(QStringLiteral("Deviation"), ColouringKey(LandmarkColouring::kDeviation));
  colouring_->setToolTip(
      QStringLiteral("Label: on the hull green, on a foreign object red. Deviation: the signed "
                     "distance to the CAD surface, with a colour legend."));
  form->addRow(QStringLiteral("Landmarks by"), colouring_);
  auto_range_ = new QCheckBox(QStringLiteral("Automatic"), style);
  auto_range_->setToolTip(QStringLiteral("Symmetric about zero, to the largest |deviation| in the data"));
  auto_range_->setObjectName(QStringLiteral("autoRange"));
  form->addRow(QStringLiteral("Legend range"), auto_range_);
  range_min_ = new QDoubleSpinBox(style);
  range_max_ = new QDoubleSpinBox(style);
  for (QDoubleSpinBox* spin : {range_min_, range_max_}) {
    spin->setRange(-10.0, 10.0);
    spin->setDecimals(3);
    spin->setSingleStep(0.01);
    spin->setSuffix(QStringLiteral(" m"));
    spin->setKeyboardTracking(false);
    connect(spin, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &LayersPanel::ReadWidgets);
  }
  range_min_->setObjectName(QStringLiteral("rangeMin"));
  range_max_->setObjectName(QStringLiteral("rangeMax"));
  form->addRow(QStringLiteral("Minimum"), range_min_);
  form->addRow(QStringLiteral("Maximum"), range_max_);
  tolerance_ = new QDoubleSpinBox(style);
  tolerance_->setObjectName(QStringLiteral("tolerance"));
  tolerance_->setRange(0.0, 10.0);
  tolerance_->setDecimals(3);
  tolerance_->setSingleStep(0.005);
  tolerance_->setSuffix(QStringLiteral(" m"));
  tolerance_->setPrefix(QStringLiteral("± "));
  tolerance_->setSpecialValueText(QStringLiteral("none"));
  tolerance_->setKeyboardTracking(false);
  tolerance_->setToolTip(
      QStringLiteral("Deviations within ± this are drawn green (within tolerance), those beyond it in the "
                     "deviation colours; none: the continuous map"));
  connect(tolerance_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, &LayersPanel::ReadWidgets);
  form->addRow(QStringLiteral("Tolerance"), tolerance_);
  stride_ = new QSpinBox(style);
  stride_->setObjectName(QStringLiteral("frustumStride"));
  stride_->setRange(1, 10000);
  stride_->setSuffix(QStringLiteral(" keyframes"));
  stride_->setKeyboardTracking(false);
  stride_->setToolTip(QStringLiteral("Draw the camera frustum of every Nth keyframe"));
  form->addRow(QStringLiteral("Frustum every"), stride_);
  outer->addWidget(style);

  auto* model = new QGroupBox(QStringLiteral("Model placement x_gM"), content);
  auto* model_layout = new QVBoxLayout(model);
  placement_ = new QComboBox(model);
  placement_->setObjectName(QStringLiteral("modelPlacement"));
  placement_->setToolTip(QStringLiteral("Where the CAD model is drawn in the survey frame g"));
  placement_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  placement_->setMinimumContentsLength(16);
  model_layout->addWidget(placement_);
  outer->addWidget(model);
  outer->addStretch(1);
  scroll->setWidget(content);
  root->addWidget(scroll);

  connect(colouring_, qOverload<int>(&QComboBox::currentIndexChanged), this, &LayersPanel::ReadWidgets);
  connect(auto_range_, &QCheckBox::toggled, this, &LayersPanel::ReadWidgets);
  connect(stride_, qOverload<int>(&QSpinBox::valueChanged), this, &LayersPanel::ReadWidgets);
  connect(placement_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    if (updating_ || index < 0) return;
    ModelPlacement p;
    if (ModelPlacementFromKey(placement_->itemData(index).toString().toStdString(), &p)) emit placementChosen(p);
  });
  SetPlacements({ModelPlacement::kIdentity}, ModelPlacement::kIdentity);
  WriteWidgets();
}

void LayersPanel::SetOptions(const SceneOptions& options) {
  options_ = options;
  WriteWidgets();
}

void LayersPanel::SetLayersWithData(const std::map<SceneLayer, bool>& has_data) {
  for (auto it = checks_.begin(); it != checks_.end(); ++it) {
    auto found = has_data.find(it.key());
    it.value()->setEnabled(found != has_data.end() && found->second);
  }
  edges_->setEnabled(checks_.value(SceneLayer::kHull)->isEnabled());
}

void LayersPanel::SetPlacements(const std::vector<ModelPlacement>& available, ModelPlacement current) {
  updating_ = true;
  placement_->clear();
  for (ModelPlacement p : available) {
    placement_->addItem(QString::fromUtf8(ModelPlacementLabel(p)), QString::fromLatin1(ModelPlacementKey(p)));
  }
  placement_->setCurrentIndex(placement_->findData(QString::fromLatin1(ModelPlacementKey(current))));
  placement_->setEnabled(available.size() > 1);
  updating_ = false;
}

void LayersPanel::SetAutoRange(double min, double max) {
  if (!options_.auto_range) return;
  updating_ = true;
  range_min_->setValue(min);
  range_max_->setValue(max);
  updating_ = false;
}

void LayersPanel::ReadWidgets() {
  if (updating_) return;
  SceneOptions o = options_;
  for (auto it = checks_.begin(); it != checks_.end(); ++it) o.visible[it.key()] = it.value()->isChecked();
  o.hull_edges = edges_->isChecked();
  o.colouring = ColouringFromKey(colouring_->currentData().toString()).value_or(LandmarkColouring::kLabel);
  o.auto_range = auto_range_->isChecked();
  if (!o.auto_range) {
    o.range_min = range_min_->value();
    o.range_max = range_max_->value();
    if (o.range_max <= o.range_min) {
      // Keep the range valid: move the other end to follow the one edited.
      if (sender() == range_min_) {
        o.range_max = o.range_min + 0.001;
      } else {
        o.range_min = o.range_max - 0.001;
      }
    }
  }
  o.tolerance = tolerance_->value();
  o.frustum_stride = stride_->value();
  if (o == options_) return;
  options_ = o;
  WriteWidgets();
  emit optionsChanged(options_);
}

void LayersPanel::WriteWidgets() {
  updating_ = true;
  for (auto it = checks_.begin(); it != checks_.end(); ++it) it.value()->setChecked(options_.IsVisible(it.key()));
  edges_->setChecked(options_.hull_edges);
  colouring_->setCurrentIndex(colouring_->findData(ColouringKey(options_.colouring)));
  auto_range_->setChecked(options_.auto_range);
  if (!options_.auto_range) {
    range_min_->setValue(options_.range_min);
    range_max_->setValue(options_.range_max);
  }
  range_min_->setEnabled(!options_.auto_range);
  range_max_->setEnabled(!options_.auto_range);
  tolerance_->setValue(options_.tolerance);
  stride_->setValue(options_.frustum_stride);
  updating_ = false;
}

}  // namespace hull::ui
