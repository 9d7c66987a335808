// The cross-section view: a slab across or along the hull (direction,
// position along its normal, width) and the profiles of what lies in it for
// the three surface models side by side (ProfileCanvas; the paper's Figs. 14
// and 15). The models not run yet are computed on demand (the "Compare
// models" button asks the inspection to run them). The slab is drawn in the
// 3-D scene as a translucent box: slabMoved() says when it changed.
#pragma once

#include <QWidget>
#include <memory>
#include <optional>

#include "geometry/triangle_mesh.h"
#include "ui/models/cross_section.h"
#include "ui/models/solver_plot_data.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSlider;

namespace hull::ui {

class ProfileCanvas;

class CrossSectionView : public QWidget {
  Q_OBJECT

 public:
  explicit CrossSectionView(QWidget* parent = nullptr);

  // The CAD mesh in M (nullptr: none) and the hull's axes.
  void SetMesh(std::shared_ptr<const TriangleMesh> mesh, const std::optional<ModelAxes>& axes);
  // The run on screen and the runs of each model for the current parameters.
  void SetRuns(std::shared_ptr<const AdjustmentRun> current, const RunsByModel& runs);

  const SlabSpec& slab() const { return spec_; }
  void SetSlab(const SlabSpec& spec);
  // Moves the slab to a point of g (placed by the run on screen), e.g. the
  // last pick.
  void CentreOn(const Eigen::Vector3d& p_g);
  // The last picked point in g (nullopt: none): the "At the pick" button
  // moves the slab there.
  void SetPickedPoint(const std::optional<Eigen::Vector3d>& p_g);
  // The slab as a box in g for the scene (nullopt without a run).
  std::optional<SlabBox> SlabBoxInG() const;
  // The range the position slider spans (m along the normal).
  std::pair<double, double> positionRange() const { return range_; }

  ProfileCanvas* canvas() const { return canvas_; }
  QPushButton* compareButton() const { return compare_; }
  void SetCompareEnabled(bool enabled);

 signals:
  void slabMoved();
  void compareRequested();

 private:
  void ReadControls();
  void WriteControls();
  void UpdateRange();
  void Recompute(bool keep_view);

  std::shared_ptr<const TriangleMesh> mesh_;
  std::optional<ModelAxes> axes_;
  std::shared_ptr<const AdjustmentRun> current_;
  RunsByModel runs_;
  SlabSpec spec_;
  bool positioned_ = false;  // the slab was placed for these data
  std::pair<double, double> range_{0.0, 0.0};
  Eigen::AlignedBox2d extent_;  // the data in the plane (u, v), for the 3-D box
  bool updating_ = false;

  QComboBox* direction_ = nullptr;
  QSlider* slider_ = nullptr;
  QDoubleSpinBox* position_ = nullptr;
  QDoubleSpinBox* width_ = nullptr;
  QPushButton* compare_ = nullptr;
  QPushButton* at_pick_ = nullptr;
  std::optional<Eigen::Vector3d> picked_;
  QLabel* info_ = nullptr;
  ProfileCanvas* canvas_ = nullptr;
};

}  // namespace hull::ui
