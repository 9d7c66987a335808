// The VTK side of SonarView: one actor per layer, rebuilt at every step.
// Only sonar_view.cc includes this.
#pragma once

#include <vtkSmartPointer.h>

#include <QImage>
#include <memory>
#include <vector>

#include "ui/session/sonar_results.h"

class vtkActor;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

namespace hull::ui {

class SonarViewImpl {
 public:
  SonarViewImpl();
  ~SonarViewImpl();

  vtkGenericOpenGLRenderWindow* window() const { return window_; }
  void SetRun(std::shared_ptr<const SonarRun> run);
  void SetStep(int step);
  void SetEllipsoidScale(double scale);
  void ResetCamera(bool whole_run);
  void Render();
  QImage Grab();

  int true_features = 0, initial = 0, estimated = 0, feature_ellipsoids = 0, pose_ellipsoids = 0;

 private:
  enum Layer {
    kTrueFeatures,
    kInitial,
    kEstimated,
    kFeatureEllipsoids,
    kTrueTrajectory,
    kDeadReckoning,
    kTrajectory,
    kPoseEllipsoids,
    kFieldOfView,
    kLayers
  };
  void Rebuild();

  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  std::vector<vtkSmartPointer<vtkActor>> actors_;
  std::shared_ptr<const SonarRun> run_;
  int step_ = 0;
  double scale_ = 1.0;
};

}  // namespace hull::ui
