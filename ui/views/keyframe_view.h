// The keyframe view (the paper's Fig. 11): one keyframe's top image as a
// frame of its size, the features it observed at their pixels coloured by
// their deviation from the CAD surface (grey: within tau, not clustered;
// ringed: DBSCAN noise) and Algorithm 1's alpha shapes over the clusters as
// white triangle meshes. A combo box and arrows step through the keyframes
// that have shapes; ShowObject jumps to a view of a detected object.
#pragma once

#include <QWidget>
#include <memory>

#include "ui/session/inspection_results.h"

class QComboBox;
class QLabel;
class QToolButton;

namespace hull::ui {

class KeyframeCanvas;

class KeyframeView : public QWidget {
  Q_OBJECT

 public:
  explicit KeyframeView(QWidget* parent = nullptr);

  void SetMapping(std::shared_ptr<const MappingRun> mapping);
  // index into mapping->result->keyframes (-1: none).
  void ShowKeyframe(int index);
  // The keyframe that saw most of the object (index into result->objects).
  void ShowObject(int object_index);
  int keyframe() const { return keyframe_; }
  QComboBox* keyframeBox() const { return box_; }
  QString infoText() const;

  // The colour of a deviation on the diverging map the 3-D view uses.
  static QColor DeviationColour(double deviation, double lo, double hi);

 private:
  void Populate();

  std::shared_ptr<const MappingRun> mapping_;
  int keyframe_ = -1;
  QComboBox* box_ = nullptr;
  QToolButton* previous_ = nullptr;
  QToolButton* next_ = nullptr;
  QLabel* info_ = nullptr;
  KeyframeCanvas* canvas_ = nullptr;
};

}  // namespace hull::ui
