// The sonar's 3-D view (the paper of Mai et al., Figs. 6, 8 and 11a): the
// true feature points (green), their first estimates (blue), the estimates
// at the current step (red) with 3-sigma covariance ellipsoids, the true
// trajectory (green), dead reckoning (grey) and the EKF's trajectory (red)
// with a 3-sigma position ellipsoid per step, up to the current step, and
// the sonar's field of view at it; or the batch smoother's points and poses
// with their covariance ellipsoids; and the scene mesh. World frame z down.
//
// A QWidget around a QVTKOpenGLNativeWidget; VTK lives in SonarViewImpl.
#pragma once

#include <QImage>
#include <QWidget>
#include <memory>

#include "ui/session/sonar_results.h"
#include "ui/views/render_coalescer.h"

class QVTKOpenGLNativeWidget;

namespace hull::ui {

class SonarViewImpl;

class SonarView : public QWidget {
  Q_OBJECT

 public:
  explicit SonarView(QWidget* parent = nullptr);
  ~SonarView() override;

  void SetRun(std::shared_ptr<const SonarRun> run);  // nullptr clears
  void SetStep(int step);
  // Ellipsoids are drawn at 3 sigma times this factor (small pose
  // uncertainties become visible).
  void SetEllipsoidScale(double scale);
  // The filter's estimates at the step, or the batch smoother's (its final
  // points and its poses up to the step) when the run has them.
  void SetSmoother(bool smoother);
  // The scene mesh (truth/scene.ply), translucent, when the run has one.
  void SetSceneVisible(bool visible);
  int step() const;  // the step shown (clamped to the run)
  // Looks at the feature points (the paper's Fig. 8a), or at the whole run
  // with the trajectory.
  void ResetCamera(bool whole_run = false);
  QImage Grab();

  struct Counts {
    int true_features = 0, initial = 0, estimated = 0, feature_ellipsoids = 0, pose_ellipsoids = 0;
    int scene_triangles = 0;
    bool smoother = false;  // showing the smoother's estimates
  };
  Counts counts() const;

 private:
  void ScheduleRender();
  void RenderNow();  // the coalesced frame

  QVTKOpenGLNativeWidget* vtk_widget_ = nullptr;
  std::unique_ptr<SonarViewImpl> impl_;
  RenderCoalescer render_{this, [this] { RenderNow(); }};
};

}  // namespace hull::ui
