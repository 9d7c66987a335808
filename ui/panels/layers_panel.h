// The layers panel: what the 3-D scene shows (a check box per layer, hull
// edges), how landmarks are coloured (label or deviation, with the legend's
// range), the frustum stride and where the model is placed. Widgets only; it
// speaks SceneOptions and ModelPlacement, never VTK.
#pragma once

#include <QMap>
#include <QWidget>
#include <vector>

#include "ui/session/scene_options.h"
#include "ui/session/survey_overlays.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QSpinBox;

namespace hull::ui {

class LayersPanel : public QWidget {
  Q_OBJECT

 public:
  explicit LayersPanel(QWidget* parent = nullptr);

  SceneOptions options() const { return options_; }
  void SetOptions(const SceneOptions& options);  // no signal
  // Layers without data are shown disabled.
  void SetLayersWithData(const std::map<SceneLayer, bool>& has_data);
  // The placements the survey offers and the one in force (no signal).
  void SetPlacements(const std::vector<ModelPlacement>& available, ModelPlacement current);
  // The legend's data range, shown while "automatic" is on.
  void SetAutoRange(double min, double max);

  QCheckBox* layerCheckBox(SceneLayer layer) const { return checks_.value(layer); }
  QComboBox* colouringBox() const { return colouring_; }
  QComboBox* placementBox() const { return placement_; }

 signals:
  void optionsChanged(const hull::ui::SceneOptions& options);
  void placementChosen(hull::ui::ModelPlacement placement);

 private:
  void ReadWidgets();
  void WriteWidgets();

  SceneOptions options_;
  QMap<SceneLayer, QCheckBox*> checks_;
  QCheckBox* edges_ = nullptr;
  QComboBox* colouring_ = nullptr;
  QCheckBox* auto_range_ = nullptr;
  QDoubleSpinBox* range_min_ = nullptr;
  QDoubleSpinBox* range_max_ = nullptr;
  QDoubleSpinBox* tolerance_ = nullptr;
  QSpinBox* stride_ = nullptr;
  QComboBox* placement_ = nullptr;
  bool updating_ = false;
};

}  // namespace hull::ui
